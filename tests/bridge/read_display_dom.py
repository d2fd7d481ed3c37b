#!/usr/bin/python3
"""Reads a DOM dump of the bridge display (chromium --dump-dom) with
Python's html.parser and prints, for every element with a data-value
attribute, one line:

  <id> <data-value> <displayed text>

For tests/bridge/display_browser_test. Usage: read_display_dom.py <dom file>
"""
import html.parser
import sys


class Values(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.open = None  # [id, value, text] of the element being read

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "data-value" in a and "id" in a:
            self.open = [a["id"], a["data-value"] or "nan", ""]

    def handle_data(self, data):
        if self.open is not None:
            self.open[2] += data

    def handle_endtag(self, tag):
        if self.open is not None:
            print(self.open[0], self.open[1], self.open[2].strip() or "-")
            self.open = None


def main():
    with open(sys.argv[1], encoding="utf-8") as dom:
        Values().feed(dom.read())


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Reads a text/event-stream of the bridge display (one `data: <json>` line
per event) with Python's json module and prints, one line per event:

  <seq> <t> <x> <y> <heading> <rudder_angle> <rudder_order> <propeller_rps> <phase>

in the units of ship_state_t (repr: the doubles exactly). For
tests/bridge/http_display_test.

Usage: decode_state_stream.py <stream file>
"""
import json
import sys

FIELDS = ("t", "x", "y", "heading", "rudder_angle", "rudder_order", "propeller_rps")


def main():
    with open(sys.argv[1], encoding="utf-8") as stream:
        for line in stream:
            if not line.startswith("data: "):
                continue
            update = json.loads(line[len("data: "):])
            state = update["state"]
            if state is None:
                continue
            print(state["seq"], *(repr(float(state[k])) for k in FIELDS), state["phase"])


if __name__ == "__main__":
    main()

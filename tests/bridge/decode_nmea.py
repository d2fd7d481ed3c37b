#!/usr/bin/python3
"""Decodes a file of NMEA 0183 sentences with two parsers from Debian and
prints what they read, one record a line, for tests/bridge/nmea_gpsd_test:

  TPV <unix time s> <mode> <lat deg> <lon deg> <track deg> <speed m/s>
      one per fix that gpsd's decoder (gpsdecode, gpsd-clients) reports;
      nan where gpsd gives no value (mode 1: no fix)
  ATT <heading deg>
      one per heading gpsd reads (from HDT)
  FIX <unix time s> <rate of turn deg/min> <rudder deg>
      one per RMC read by pynmea2 (python3-nmea2), with the ROT and RSA
      sentences that follow it; gpsd 3.22 decodes neither

Usage: decode_nmea.py <sentences file>
"""
import calendar
import datetime
import json
import math
import subprocess
import sys

import pynmea2


def iso_to_unix(text):
    """'2023-11-14T22:13:20.250Z' -> seconds since the UNIX epoch."""
    stamp = datetime.datetime.strptime(text, "%Y-%m-%dT%H:%M:%S.%fZ")
    return calendar.timegm(stamp.timetuple()) + stamp.microsecond * 1e-6


def number(record, key):
    value = record.get(key)
    return math.nan if value is None else float(value)


def gpsd_records(path):
    with open(path, "rb") as sentences:
        out = subprocess.run(["gpsdecode"], stdin=sentences, capture_output=True, check=True).stdout
    for line in out.decode().splitlines():
        record = json.loads(line)
        if record.get("class") == "TPV":
            time = iso_to_unix(record["time"]) if "time" in record else math.nan
            print("TPV", repr(time), record.get("mode", 0),
                  *(repr(number(record, k)) for k in ("lat", "lon", "track", "speed")))
        elif record.get("class") == "ATT" and "heading" in record:
            print("ATT", repr(float(record["heading"])))


def pynmea2_records(path):
    fix = None

    def flush():
        if fix is not None:
            print("FIX", repr(fix["time"]), repr(fix["rot"]), repr(fix["rudder"]))

    with open(path, encoding="ascii") as sentences:
        for line in sentences:
            message = pynmea2.parse(line.strip(), check=True)
            if isinstance(message, pynmea2.types.talker.RMC):
                flush()
                stamp = datetime.datetime.combine(message.datestamp, message.timestamp)
                time = calendar.timegm(stamp.timetuple()) + stamp.microsecond * 1e-6
                fix = {"time": time, "rot": math.nan, "rudder": math.nan}
            elif isinstance(message, pynmea2.types.talker.ROT) and fix is not None:
                fix["rot"] = float(message.rate_of_turn)
            elif isinstance(message, pynmea2.types.talker.RSA) and fix is not None:
                fix["rudder"] = float(message.rsa_starboard)
    flush()


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: decode_nmea.py <sentences file>")
    gpsd_records(sys.argv[1])
    pynmea2_records(sys.argv[1])


if __name__ == "__main__":
    main()

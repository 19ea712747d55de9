#!/usr/bin/env python3
"""Cuts a piece out of an LCM event log: some channels, over a time window.

Usage: deploy/tools/lcmlog_cut.py IN.lcmlog OUT.lcmlog --channels A,B,... [--start S] [--length S]

Keeps the events of the named channels whose log timestamp lies in [first + start, first + start
+ length) seconds, where `first` is the first kept channel's first event; renumbers the events
from 0, as lcm-logger would have written them. How the checked-in sample logs under logs/ were
made from a recorded run (see logs/README.md). Reads the event format directly (no LCM
bindings): sync word, event number, timestamp, channel and data lengths, channel, data.
"""
import argparse
import struct
import sys

SYNC = 0xEDA1DA01
HEADER = ">IqqII"
HEADER_SIZE = struct.calcsize(HEADER)


def events(data):
    """(timestamp_us, channel bytes, payload bytes) of every whole event, in file order."""
    i = 0
    while i + HEADER_SIZE <= len(data):
        sync, _, utime, clen, dlen = struct.unpack(HEADER, data[i:i + HEADER_SIZE])
        if sync != SYNC:  # not at an event: resynchronise byte by byte
            i += 1
            continue
        end = i + HEADER_SIZE + clen + dlen
        if end > len(data):
            return  # a truncated last event
        yield utime, data[i + HEADER_SIZE:i + HEADER_SIZE + clen], data[i + HEADER_SIZE + clen:end]
        i = end


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--channels", required=True, help="comma-separated channel names to keep")
    p.add_argument("--start", type=float, default=0.0, help="[s] after the first kept event")
    p.add_argument("--length", type=float, default=float("inf"), help="[s] of log to keep")
    a = p.parse_args()
    keep = {c.encode() for c in a.channels.split(",") if c}
    with open(a.input, "rb") as f:
        data = f.read()
    first = None
    kept = 0
    with open(a.output, "wb") as out:
        for utime, channel, payload in events(data):
            if channel not in keep:
                continue
            if first is None:
                first = utime
            t = (utime - first) / 1e6
            if t < a.start:
                continue
            if t >= a.start + a.length:
                break
            out.write(struct.pack(HEADER, SYNC, kept, utime, len(channel), len(payload)))
            out.write(channel)
            out.write(payload)
            kept += 1
    if kept == 0:
        sys.exit(f"lcmlog_cut: no event of {a.channels} in {a.input}")
    print(f"lcmlog_cut: {kept} events written to {a.output}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Compares two benchmark JSON files leaf by leaf: does a change move any result?

Usage: deploy/tools/bench_compare.py BEFORE.json AFTER.json [--skip KEY ...] [--show N]

Walks both files together and reports every leaf that differs. Keys that measure the machine
rather than the result (names with cpu, seconds, time, rate, speed, wall, elapsed, factor, hz, or
ending in _s / _ms, or holding _ms_) are left out, and so are strings holding a path under different checkouts.
--skip leaves out whole subtrees by key (e.g. --skip loop for bench control's jitter section).
Exits 1 when anything differs, so a refactor can be checked with `./rgnav bench NAME` on both
commits and this script.
"""
import argparse
import json
import re
import sys

TIMING = re.compile(r"cpu|seconds|_s$|_ms$|_ms_|time|rate|per_s|wall|elapsed|factor|speed|hz", re.I)


def is_path(value):
    return isinstance(value, str) and value.startswith("/")


def compare(a, b, where, skip, out, counted):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if TIMING.search(key) or key in skip:
                continue
            if key not in a or key not in b:
                out.append((f"{where}.{key}", "only in one file"))
                continue
            compare(a[key], b[key], f"{where}.{key}", skip, out, counted)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append((where, f"{len(a)} items, then {len(b)}"))
            return
        for i, (x, y) in enumerate(zip(a, b)):
            compare(x, y, f"{where}[{i}]", skip, out, counted)
    else:
        counted[0] += 1
        if a != b and not (is_path(a) and is_path(b)):
            out.append((where, f"{a!r} -> {b!r}"))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--skip", nargs="*", default=[], help="keys whose subtrees are left out")
    p.add_argument("--show", type=int, default=40, help="differences to print at most")
    a = p.parse_args()
    with open(a.before) as f:
        before = json.load(f)
    with open(a.after) as f:
        after = json.load(f)
    diffs, counted = [], [0]
    compare(before, after, "", set(a.skip), diffs, counted)
    print(f"{len(diffs)} differences over {counted[0]} compared values")
    for where, what in diffs[: a.show]:
        print(f"  {where}: {what}")
    sys.exit(1 if diffs else 0)


if __name__ == "__main__":
    main()

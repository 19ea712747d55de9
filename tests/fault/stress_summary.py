#!/usr/bin/env python3
"""The stress section's figures (tests/fault/stress.sh): merges {"stress": {...}} into OUT.

  stress_summary.py OUT SOAK_S LOAD RESTARTS SOAK_LOG PROBES

RESTARTS is the restart count after the soak ("null" when no status was heard); SOAK_LOG the
supervisor's output during the soak; PROBES the hang probes' result file (stress_probes.sh:
"NAME MS", "NAME missed" or "NAME not_running:STATE"). Exits 1 when a hang probe failed (a
stopped process never reported hung, or one that was not running when its probe was due) or the
restarts are unknown: such a run has not shown that hangs are detected under load.
"""
import json
import os
import re
import sys


def seconds(stamp):  # HH:MM:SS.mmm
    h, m, s = stamp.split(":")
    return int(h) * 3600 + int(m) * 60 + float(s)


def events(lines, gap_s=2.0):
    """Lines within gap_s of the one before are one event (a stop logs a line per drive and state)."""
    n, last = 0, None
    for line in lines:
        t = seconds(line.split()[0])
        if last is None or t - last > gap_s:
            n += 1
        last = t
    return n


def read_probes(path):
    """(detect ms per process or None, processes stopped but not detected, {process: why not probed})."""
    detect, missed, not_probed = {}, [], {}
    for line in open(path):
        if not line.strip():
            continue
        name, value = line.split(None, 1)
        value = value.strip()
        detect[name] = None
        if value == "missed":
            missed.append(name)
        elif value.startswith("not_running:"):
            not_probed[name] = value.split(":", 1)[1].replace("_", " ")
        else:
            detect[name] = float(value)
    return detect, sorted(missed), not_probed


def main(out, soak_s, load, restarts, soak_log, probes):
    lines = [l for l in open(soak_log, errors="replace") if re.match(r"\d\d:\d\d:\d\d\.\d+ ", l)]
    grep = lambda pattern: [l for l in lines if re.search(pattern, l)]
    stalls = [int(m.group(1)) for l in lines for m in [re.search(r"host stalled for (\d+) ms", l)] if m]
    detect, missed, not_probed = read_probes(probes)
    measured = [v for v in detect.values() if v is not None]
    probes_failed = len(missed) + len(not_probed)
    doc = {}
    if os.path.exists(out):
        try:
            doc = json.load(open(out))
        except ValueError:
            doc = {}
    doc["stress"] = {
        "load": "stress-ng " + load,
        "soak_s": int(soak_s),
        "false_restarts": None if restarts == "null" else int(restarts),
        "hung_reports": [l.split("] ", 1)[1].strip() for l in grep(r"\[supervisor\] .* is hung: ")],
        "stall_stops": events(grep(r"\[base_driver\] base stopped by a fault")) + events(grep(r"\[lld\] controlled stop: stale")),
        "base_fault_stops": events(grep(r"\[base_driver\] base stopped by a fault")),
        "lld_stale_stops": events(grep(r"\[lld\] controlled stop: stale")),
        "collisions": events(grep(r"\] collision with")),
        "disk_waits": len(grep(r"waiting on the disk")),
        "host_stalls": len(stalls),
        "host_stall_max_ms": max(stalls, default=0),
        # Only a run whose every probe measured a detection has a worst case.
        "hang_detect_ms_max": max(measured) if detect and probes_failed == 0 else None,
        "hang_detect_ms": detect,
        "hangs_missed": missed,
        "hangs_not_probed": not_probed,
        "hang_probes": len(detect),
        "hang_probes_failed": probes_failed,
    }
    json.dump(doc, open(out, "w"), indent=2)
    s = doc["stress"]
    print(f"stress: {s['false_restarts']} false restarts, {s['stall_stops']} stall stops, {s['collisions']} collisions in "
          f"{soak_s} s; hangs detected in <= {s['hang_detect_ms_max']} ms ({len(detect)} processes, "
          f"{probes_failed} probes failed: missed {missed}, not running when due {sorted(not_probed)})",
          file=sys.stderr)
    return 1 if probes_failed > 0 or not detect or s["false_restarts"] is None else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

#!/usr/bin/env python3
"""Where the lld's loop stalls came from (deploy/bench/control.sh): matches every stall of
the lld (loop.json, CLOCK_MONOTONIC wake times) against the stalls of the bare canary loops
pinned one per CPU (canaryN.json), and summarises the machine's steal time, CPU pressure and
vmstat over the measurement. Prints JSON.

  loop_evidence.py DIR   (DIR holds loop.json, canary*.json, cpu_before.json, cpu_after.json, vmstat.txt)

A stall is "shared" when a canary was stalled over part of the same interval (the deadline
the lld missed to its late wake): something stopped every thread on that CPU (the scheduler,
or the host not running the virtual CPU), not the lld's own code. A stall whose step overran
(the lld's own work ran past its deadline) is the lld's, whatever the canaries saw."""
import glob
import json
import os
import sys


def load(path, default=None):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return default


def stat_fields(line):
    # cpu user nice system idle iowait irq softirq steal guest guest_nice (USER_HZ ticks)
    parts = line.split()
    names = ["user", "nice", "system", "idle", "iowait", "irq", "softirq", "steal"]
    return {n: int(v) for n, v in zip(names, parts[1:9])}


def pressure_total(text):
    # "some avg10=.. avg60=.. avg300=.. total=US;full ..." -> {"some": us, "full": us}
    out = {}
    for part in text.split(";"):
        words = part.split()
        if words:
            out[words[0]] = int(next((w.split("=")[1] for w in words if w.startswith("total=")), 0))
    return out


def main(d):
    loop = load(os.path.join(d, "loop.json"), {})
    canaries = {}
    for path in sorted(glob.glob(os.path.join(d, "canary*.json"))):
        cpu = os.path.basename(path)[len("canary"):-len(".json")]
        c = load(path)
        if c is not None:
            canaries[cpu] = c
    # Canary stall intervals: from when it should have woken (its deadline) to its wake.
    intervals = {cpu: [(s["wake_ns"] - s["late_ms"] * 1e6, s["wake_ns"]) for s in c.get("stalls", [])]
                 for cpu, c in canaries.items()}
    matched = []
    for s in loop.get("stalls", []):
        a, b = s["wake_ns"] - s["late_ms"] * 1e6, s["wake_ns"]
        seen = {}
        for cpu, iv in intervals.items():
            overlap = sum(max(0.0, min(b, y) - max(a, x)) for x, y in iv)
            if overlap > 0:
                seen[cpu] = round(overlap * 1e-6, 3)
        cause = "lld step" if s.get("step_overran") else ("shared with a canary" if seen else "lld only")
        matched.append({"wake_ns": s["wake_ns"], "late_ms": round(s["late_ms"], 3), "step_ms": round(s["step_ms"], 3),
                        "step_overran": s.get("step_overran", False), "missed": s.get("missed", 0),
                        "canary_stalled_ms": seen, "cause": cause})
    own = [m for m in matched if m["cause"] != "shared with a canary"]
    every_cpu = sum(1 for m in matched if len(m["canary_stalled_ms"]) == len(canaries) > 1)
    if not matched:
        verdict = "no lld stall over the threshold"
    elif not own:
        verdict = ("every lld stall coincided with a stall of a bare canary loop (same loop, nothing in its step, "
                   "pinned, same SCHED_FIFO priority); %d of %d hit every CPU at once; the lld's own step never "
                   "overran (max %.3f ms, %d page faults after warm-up): the stalls come from outside the lld "
                   "(a virtual CPU the host did not run, or kernel work above the loop's priority)"
                   % (every_cpu, len(matched), loop.get("step_max_ms", 0.0), loop.get("minor_faults", 0)))
    else:
        verdict = "%d of %d lld stalls are the lld's own (its step overran, or no canary stalled then)" % (len(own), len(matched))
    out = {"verdict": verdict,
           "lld_stalls_on_every_cpu": every_cpu,
           "lld_stalls": matched,
           "lld_stalls_shared_with_canary": sum(1 for m in matched if m["cause"] == "shared with a canary"),
           "lld_stalls_lld_only": sum(1 for m in matched if m["cause"] != "shared with a canary"),
           "canaries": {cpu: {k: c.get(k) for k in ("ticks", "overruns", "jitter_p99_ms", "jitter_max_ms", "late_wakes",
                                                     "long_steps", "minor_faults")}
                        | {"worst_stalls_ms": [round(s["late_ms"], 2) for s in c.get("stalls", [])[:8]]}
                        for cpu, c in canaries.items()}}
    before, after = load(os.path.join(d, "cpu_before.json")), load(os.path.join(d, "cpu_after.json"))
    if before and after:
        b, a = stat_fields(before["stat"]), stat_fields(after["stat"])
        delta = {k: a[k] - b[k] for k in b}
        total = sum(delta.values()) or 1
        out["cpu_ticks"] = delta
        out["steal_pct"] = round(100.0 * delta["steal"] / total, 3)
        pb, pa = pressure_total(before.get("pressure", "")), pressure_total(after.get("pressure", ""))
        out["cpu_pressure_stall_us"] = {k: pa[k] - pb.get(k, 0) for k in pa}
    if out.get("steal_pct") == 0.0:
        out["steal_note"] = "steal 0: this VM's kernel may not get steal time from its host (no evidence either way)"
    try:
        rows = [line.split() for line in open(os.path.join(d, "vmstat.txt"))]
        head = next((r for r in rows if "st" in r and "r" in r), None)
        if head:
            data = [r for r in rows if len(r) == len(head) and r[0].isdigit()]
            col = {name: i for i, name in enumerate(head)}
            out["vmstat"] = {"samples": len(data),
                             "runnable_max": max((int(r[col["r"]]) for r in data), default=0),
                             "steal_max_pct": max((int(r[col["st"]]) for r in data), default=0),
                             "idle_min_pct": min((int(r[col["id"]]) for r in data), default=0)}
    except OSError:
        pass
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main(sys.argv[1])

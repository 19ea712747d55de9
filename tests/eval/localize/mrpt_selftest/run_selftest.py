#!/usr/bin/env python3
"""Self-test of deploy/bench/mrpt/mrpt_localize.py (MRPT pf-localization half of
`./rgnav bench localize`) on a synthetic world with exact ground truth.

Usage: run_selftest.py [--dir DIR] [--keep] [--seed N]

1. make_synthetic_drive.py writes a two-room world (map origin deliberately off the cell grid,
   odometry frame far from the map frame, laser 0.12 m ahead of the base, 2-3 % odometry scale
   error): one tracking drive (33 s) and one global drive (26 s).
2. mrpt_localize.py with the shipped ini (likelihood field): both drives must run; tracking
   RMSE < 0.06 m, no step over 0.5 m; the global drive must succeed.
3. Pipeline check, tracking drive only, with MRPT's ray-tracing beam model instead of the
   likelihood field (no systematic bias of its own, see README.md): RMSE < 0.05 m and the
   mean error in the robot frame (forward / left) within 0.03 m. A wrong laser mount, map
   origin, PGM row order, frame or timestamp pairing shows up here as a bias of 0.1 m or more.
4. The same with the map as rendered (--solid-walls): reported, loosely checked (< 0.15 m).
Every run must also have put the log's own timestamps on the rawlog (error < 0.1 ms), paired
MRPT's steps with the scans (MRPT's own odometry integration agrees with the log), and moved
its estimate (not frozen). Prints the figures; exit status 0 when every check passes.
MRPT seeds its random generator from the clock, so figures vary a little from run to run.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
TOOL = os.path.join(ROOT, "deploy", "bench", "mrpt", "mrpt_localize.py")
BEAM = ["--set", "MetricMap_occupancyGrid_00_likelihoodOpts.likelihoodMethod=1",
        "--set", "MetricMap_occupancyGrid_00_likelihoodOpts.rayTracing_decimation=5",
        "--set", "MetricMap_occupancyGrid_00_likelihoodOpts.rayTracing_stdHit=0.05",
        "--set", "MetricMap_occupancyGrid_00_likelihoodOpts.rayTracing_useDistanceFilter=0"]


def run_tool(world, out, extra):
    cmd = [sys.executable, TOOL, world, "--out", out, "--jobs", "2"] + extra
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if p.returncode != 0:
        print(p.stdout.decode(errors="replace"))
        raise SystemExit("FAIL: %s exited %d" % (" ".join(cmd), p.returncode))
    return json.load(open(out))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", help="work folder (default: a new temporary folder)")
    ap.add_argument("--keep", action="store_true", help="keep the work folder")
    ap.add_argument("--seed", type=int, default=7)
    a = ap.parse_args()
    if shutil.which("pf-localization") is None:
        print("SKIP: pf-localization (Debian package mrpt-apps) is not installed")
        return 77
    base = a.dir or tempfile.mkdtemp(prefix="mrpt_selftest_")
    os.makedirs(base, exist_ok=True)
    world = os.path.join(base, "world")
    fails = []

    def check(cond, what):
        print("  [%s] %s" % ("ok" if cond else "FAIL", what))
        if not cond:
            fails.append(what)

    subprocess.run([sys.executable, os.path.join(HERE, "make_synthetic_drive.py"), world,
                    "--seed", str(a.seed)], check=True)

    def common(res, label):
        for d, r in res["per_drive"].items():
            check(r["status"] == "ok", "%s %s ran (%s)" % (label, d, r.get("reason", "ok")))
            if r["status"] != "ok":
                continue
            check(r["rawlog_timestamp_error_s"] < 1e-4,
                  "%s %s rawlog carries the log's timestamps (error %.6f s)"
                  % (label, d, r["rawlog_timestamp_error_s"]))
            check(r.get("odometry_pairing_error_m", 1) < 0.01,
                  "%s %s MRPT step k is scan k (MRPT's odometry vs the log: %.4f m)"
                  % (label, d, r.get("odometry_pairing_error_m", -1)))
            check(not r["estimate_frozen"], "%s %s estimate moves (%.2f m for %.2f m of truth)"
                  % (label, d, r["estimate_path_m"], r["truth_path_m"]))

    summary = {}
    print("== shipped ini (likelihood field, wall interiors unknown)")
    res = run_tool(world, os.path.join(base, "default.json"), [])
    common(res, "default")
    t, g = res["tracking"], res["global"]
    tr = res["per_drive"].get("track", {})
    gl = res["per_drive"].get("global", {})
    print("  tracking: RMSE %s m / %s deg, p95 %s m, max %s m, bias fwd %s m left %s m, cpu %s s"
          % (t["rmse_m"], t["rmse_deg"], t["p95_m"], t["max_m"], tr.get("bias_forward_m"),
             tr.get("bias_left_m"), tr.get("cpu_s")))
    print("  global: success %s, time %s s, travel %s m, RMSE %s m, cpu %s s"
          % (gl.get("success"), gl.get("time_s"), gl.get("travel_m"), gl.get("rmse_m"),
             gl.get("cpu_s")))
    check(t["rmse_m"] is not None and t["rmse_m"] < 0.06, "tracking RMSE %s m < 0.06 m" % t["rmse_m"])
    check(t["divergences"] == 0, "tracking did not diverge")
    check(g["success_ratio"] == 1.0, "global localization succeeded (t* - t0 = %s s)" % gl.get("time_s"))
    summary["default"] = {"tracking": t, "global": g, "track": tr, "global_drive": gl}

    print("== pipeline check: ray-tracing beam model, tracking drive")
    res = run_tool(world, os.path.join(base, "beam.json"), ["--drives", "track"] + BEAM)
    common(res, "beam")
    tr = res["per_drive"].get("track", {})
    print("  tracking: RMSE %s m / %s deg, max %s m, bias fwd %s m left %s m, map-frame bias %s"
          % (tr.get("rmse_m"), tr.get("rmse_deg"), tr.get("max_m"), tr.get("bias_forward_m"),
             tr.get("bias_left_m"), tr.get("bias_map_m")))
    if tr.get("status") == "ok":
        check(tr["rmse_m"] < 0.05, "beam-model tracking RMSE %s m < 0.05 m" % tr["rmse_m"])
        check(abs(tr["bias_forward_m"]) < 0.03 and abs(tr["bias_left_m"]) < 0.03,
              "no bias from frames / mount / origin (fwd %s m, left %s m)"
              % (tr["bias_forward_m"], tr["bias_left_m"]))
    summary["beam"] = tr

    print("== map as rendered (--solid-walls), tracking drive")
    res = run_tool(world, os.path.join(base, "solid.json"), ["--drives", "track", "--solid-walls"])
    common(res, "solid")
    tr = res["per_drive"].get("track", {})
    print("  tracking: RMSE %s m, max %s m, bias fwd %s m left %s m"
          % (tr.get("rmse_m"), tr.get("max_m"), tr.get("bias_forward_m"), tr.get("bias_left_m")))
    if tr.get("status") == "ok":
        check(tr["rmse_m"] < 0.15 and not tr["diverged"], "solid-wall tracking RMSE %s m < 0.15 m" % tr["rmse_m"])
    summary["solid"] = tr

    with open(os.path.join(base, "selftest.json"), "w") as f:
        json.dump({"passed": not fails, "failures": fails, "figures": summary}, f, indent=1)
    remove = not fails and not a.keep and not a.dir
    print("%s (%d failed checks); work folder %s%s" % ("PASS" if not fails else "FAIL", len(fails),
                                                      base, " (removed)" if remove else ""))
    if remove:
        shutil.rmtree(base)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())

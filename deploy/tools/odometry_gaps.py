#!/usr/bin/env python3
"""Where the ODOMETRY of a simulated run lost or gained motion against the simulator's SIM_TRUTH.

Usage: deploy/tools/odometry_gaps.py RUN/lcm/rgnav.lcmlog [--from S] [--to S] [--tolerance M] [--gap-ms MS]

For every pair of consecutive ODOMETRY messages it compares the distance the odometry moved with
the distance the true pose moved over the same message times (interpolated), and prints the
pairs that differ by more than the tolerance or are further apart than --gap-ms. Times are
seconds from the first SLAM_POSE (as slam_vs_truth.py prints them). A heartbeat outage that
re-baselined base_driver's odometry shows as a gap with "odo 0.000" while the truth moved. The
closing sum (truth minus odometry path length) also holds the simulator's configured odometry
scale error, so compare it over short windows.
"""
import argparse
import bisect
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from slam_vs_truth import read_poses  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log")
    ap.add_argument("--from", dest="t0", type=float, default=0.0)
    ap.add_argument("--to", dest="t1", type=float, default=1e12)
    ap.add_argument("--tolerance", type=float, default=0.01, help="[m] per message pair")
    ap.add_argument("--gap-ms", type=float, default=100.0, help="print message pairs further apart than this")
    args = ap.parse_args()
    poses = read_poses(args.log, ["SIM_TRUTH", "ODOMETRY", "SLAM_POSE"])
    truth, odometry = poses["SIM_TRUTH"], poses["ODOMETRY"]
    if not truth or not odometry or not poses["SLAM_POSE"]:
        print("odometry_gaps: the log lacks SIM_TRUTH, ODOMETRY or SLAM_POSE", file=sys.stderr)
        return 1
    base = poses["SLAM_POSE"][0][0]
    stamps = [t for t, _ in truth]

    def truth_at(utime):
        k = min(max(bisect.bisect_left(stamps, utime), 1), len(stamps) - 1)
        (ua, a), (ub, b) = truth[k - 1], truth[k]
        s = (utime - ua) / (ub - ua) if ub > ua else 0.0
        return a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])

    lost = 0.0
    for (u0, p0), (u1, p1) in zip(odometry, odometry[1:]):
        t = (u1 - base) / 1e6
        if t < args.t0 or t > args.t1:
            continue
        odo = math.hypot(p1[0] - p0[0], p1[1] - p0[1])
        a, b = truth_at(u0), truth_at(u1)
        true = math.hypot(b[0] - a[0], b[1] - a[1])
        gap_ms = (u1 - u0) / 1e3
        if gap_ms > args.gap_ms or abs(odo - true) > args.tolerance:
            print(f"{t:8.2f} s  gap {gap_ms:6.1f} ms  odo {odo:.3f} m  truth {true:.3f} m")
        lost += true - odo
    print(f"truth minus odometry path length over the window: {lost:+.3f} m")
    return 0


if __name__ == "__main__":
    sys.exit(main())

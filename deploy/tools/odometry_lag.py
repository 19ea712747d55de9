#!/usr/bin/env python3
"""Is a log's odometry in step with its scans? Compares the heading increments of the raw
odometry with those of the mapper's estimate between consecutive accepted scans, with the
odometry shifted by -N..N scans, and prints the rms difference per shift: the smallest is where
the two are in step (0 for a well-paired log). Input: trajectory.txt of `rgnav map` or of
`./rgnav bench slam` (columns: scan_id utime x y theta odom_x odom_y odom_theta).
  deploy/tools/odometry_lag.py logs/bench/slam/intel/trajectory.txt [--max-lag N]"""
import argparse
import math


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trajectory")
    ap.add_argument("--max-lag", type=int, default=3)
    args = ap.parse_args()
    rows = [l.split() for l in open(args.trajectory) if l.strip() and not l.startswith("#")]
    est = [wrap(float(b[4]) - float(a[4])) for a, b in zip(rows, rows[1:])]
    odo = [wrap(float(b[7]) - float(a[7])) for a, b in zip(rows, rows[1:])]
    n = len(est)
    for lag in range(-args.max_lag, args.max_lag + 1):
        pairs = [(odo[i + lag], est[i]) for i in range(n) if 0 <= i + lag < n]
        rms = math.sqrt(sum((o - e) ** 2 for o, e in pairs) / len(pairs))
        print(f"odometry shifted by {lag:+d} scans: heading increment rms difference {rms:.4f} rad")


if __name__ == "__main__":
    main()

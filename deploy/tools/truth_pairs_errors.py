#!/usr/bin/env python3
"""Where a simulated run's SLAM error arises. Reads a truth_pairs.txt of `./rgnav bench slam`
(sim_<map>/) or `./rgnav bench rgmap` (<world>/): per accepted scan the true pose and the final
estimate, in the SLAM bench also the online estimate (when the scan was added) and whether it
closed a loop. Both estimates are put in the world frame by the first scan's pose (no fit), and
every --every-th scan prints its position error (x, y in the world frame) and heading error;
--loops also prints each scan that closed a loop with the online error of the scan before it,
which shows what the closure moved.
  deploy/tools/truth_pairs_errors.py logs/bench/slam/sim_office_c/truth_pairs.txt --every 100 --loops"""
import argparse
import math


def in_world(first_truth, first_est, pose):
    """pose (estimate's frame) carried into the world frame by the first scan's truth."""
    ex, ey, et = first_est
    c, s = math.cos(et), math.sin(et)
    dx, dy = pose[0] - ex, pose[1] - ey
    lx, ly = c * dx + s * dy, -s * dx + c * dy
    tx, ty, tt = first_truth
    c, s = math.cos(tt), math.sin(tt)
    return tx + c * lx - s * ly, ty + s * lx + c * ly, tt + pose[2] - et


def error(row, first, col):
    """(dx, dy, dtheta_deg) of the estimate in columns col..col+2 against the truth (2..4)."""
    x, y, t = in_world(first[2:5], first[col:col + 3], row[col:col + 3])
    return x - row[2], y - row[3], math.degrees(math.remainder(t - row[4], 2 * math.pi))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("pairs")
    ap.add_argument("--every", type=int, default=100, help="print every n-th scan")
    ap.add_argument("--loops", action="store_true", help="also print every scan that closed a loop")
    a = ap.parse_args()
    rows = [list(map(float, line.split())) for line in open(a.pairs) if not line.startswith("#")]
    if not rows:
        raise SystemExit(a.pairs + ": no scans")
    first, online = rows[0], len(rows[0]) >= 12
    prev = None
    for k, r in enumerate(rows):
        fx, fy, fth = error(r, first, 5)
        line = "%5d t=%7.1f s true (%6.1f, %6.1f)  final (%+.2f, %+.2f) m %+.2f deg" % (
            k, (r[1] - first[1]) * 1e-6, r[2], r[3], fx, fy, fth)
        on = error(r, first, 8) if online else None
        if on:
            line += "  online (%+.2f, %+.2f) m %+.2f deg" % on
        closed = online and r[11] > 0
        if k % a.every == 0 or (a.loops and closed):
            if a.loops and closed and prev:
                line += "  LOOP (online before: %+.2f, %+.2f)" % prev[:2]
            print(line)
        prev = on


if __name__ == "__main__":
    main()

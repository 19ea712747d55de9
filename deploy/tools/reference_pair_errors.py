#!/usr/bin/env python3
"""How the estimate's local geometry differs from a reference's. Reads a reference_pairs.txt of
`./rgnav bench slam` (reference pose and estimate at every scan with a reference) and compares
the relative pose of every two consecutive reference scans: the translation error along and
across the reference's motion between them, the heading error, the length scale (least-squares
slope of the along error on the length) and the heading error by how far the pair turned.
  deploy/tools/reference_pair_errors.py logs/bench/slam/intel/reference_pairs.txt"""
import argparse
import math


def relative(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi)


def mean(xs):
    return sum(xs) / len(xs) if xs else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("pairs")
    a = ap.parse_args()
    rows = [list(map(float, line.split())) for line in open(a.pairs) if not line.startswith("#")]
    along, across, heading, length, turn = [], [], [], [], []
    for p, q in zip(rows, rows[1:]):
        r = relative(p[2:5], q[2:5])
        e = relative(p[5:8], q[5:8])
        d = math.hypot(r[0], r[1])
        heading.append(math.degrees(math.remainder(e[2] - r[2], 2 * math.pi)))
        turn.append(abs(r[2]))
        if d < 0.05:
            continue
        ux, uy = r[0] / d, r[1] / d
        ex, ey = e[0] - r[0], e[1] - r[1]
        along.append(ex * ux + ey * uy)
        across.append(-ex * uy + ey * ux)
        length.append(d)
    print("consecutive pairs: %d, mean length %.2f m" % (len(rows) - 1, mean(length)))
    print("along:   mean %+.4f m, mean |.| %.4f m" % (mean(along), mean([abs(x) for x in along])))
    print("across:  mean %+.4f m, mean |.| %.4f m" % (mean(across), mean([abs(x) for x in across])))
    print("heading: mean %+.3f deg, mean |.| %.3f deg" % (mean(heading), mean([abs(x) for x in heading])))
    slope = sum(x * d for x, d in zip(along, length)) / sum(d * d for d in length)
    print("length scale (estimate / reference - 1): %+.4f" % slope)
    for lo, hi in [(0, 0.1), (0.1, 0.5), (0.5, 1.5), (1.5, 4.0)]:
        sel = [abs(h) for h, t in zip(heading, turn) if lo <= t < hi]
        if sel:
            print("turned %.1f-%.1f rad: %3d pairs, mean |heading error| %.3f deg" % (lo, hi, len(sel), mean(sel)))


if __name__ == "__main__":
    main()

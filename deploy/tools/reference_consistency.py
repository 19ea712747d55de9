#!/usr/bin/env python3
"""How self-consistent are two sets of poses for the same scans? Projects every scan with a
reference_pairs.txt of `./rgnav bench slam` (reference pose and estimate at every scan with a
reference) and prints, for the reference and for the estimate, the share of end points within
2 cm of another scan's (of the end points with another scan's within 10 cm, scans more than 2
apart). No ground truth needed: the better poses give the sharper map. --geometry chooses how
the CARMEN log's 180 beams spread over 180 deg: carmen ([-90, 89] deg at 1 deg), inclusive
(MRPT's: fov / (n - 1)), half (shifted half a beam), plus1 / minus1 (shifted one beam).
  deploy/tools/reference_consistency.py logs/bench/slam/intel/reference_pairs.txt \\
      ../shared/data/laser/raw/intel/intel-raw-odometry.carmen.log.gz --geometry carmen"""
import argparse
import gzip
import math

GEOMETRY = {
    "carmen": lambda k, n: k * 180.0 / n,
    "inclusive": lambda k, n: k * 180.0 / (n - 1),
    "half": lambda k, n: (k + 0.5) * 180.0 / n,
    "plus1": lambda k, n: (k + 1) * 180.0 / n,
    "minus1": lambda k, n: (k - 1) * 180.0 / n,
}
CELL = 0.05


def read_scans(path, geometry, max_range=29.9):
    """Scan id (1, 2, ... as rgnav_import numbers FLASER lines) -> end points in the laser frame."""
    spread = GEOMETRY[geometry]
    scans = {}
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        for line in f:
            if not line.startswith("FLASER"):
                continue
            v = line.split()
            n = int(v[1])
            pts = []
            for k, r in enumerate(map(float, v[2:2 + n])):
                if 0.05 < r < max_range:
                    a = math.radians(-90.0 + spread(k, n))
                    pts.append((r * math.cos(a), r * math.sin(a)))
            scans[len(scans) + 1] = pts
    return scans


def share_within(poses, scans, near=0.02, overlap=0.1, min_gap=3):
    grid, world = {}, []
    for idx, (scan_id, (x, y, th)) in enumerate(poses):
        c, s = math.cos(th), math.sin(th)
        pts = [(x + c * px - s * py, y + s * px + c * py) for px, py in scans[scan_id]]
        world.append(pts)
        for p in pts:
            grid.setdefault((math.floor(p[0] / CELL), math.floor(p[1] / CELL)), []).append((p, idx))
    overlapping = close = 0
    for idx, pts in enumerate(world):
        for p in pts:
            cx, cy = math.floor(p[0] / CELL), math.floor(p[1] / CELL)
            best = math.inf
            for i in (cx - 1, cx, cx + 1):
                for j in (cy - 1, cy, cy + 1):
                    for q, other in grid.get((i, j), ()):
                        if abs(other - idx) >= min_gap:
                            best = min(best, (q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2)
            if best < overlap ** 2:
                overlapping += 1
                close += best < near ** 2
    return close / overlapping if overlapping else 0.0, overlapping


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("reference_pairs")
    ap.add_argument("carmen_log")
    ap.add_argument("--geometry", choices=sorted(GEOMETRY), default="carmen")
    args = ap.parse_args()
    scans = read_scans(args.carmen_log, args.geometry)
    ref, est = [], []
    for line in open(args.reference_pairs):
        if line.startswith("#") or not line.strip():
            continue
        v = line.split()
        scan_id = int(v[0])
        ref.append((scan_id, tuple(map(float, v[2:5]))))
        est.append((scan_id, tuple(map(float, v[5:8]))))
    for name, poses in (("reference", ref), ("estimate", est)):
        share, n = share_within(poses, scans)
        print(f"{name}: {share:.3f} of {n} overlapping end points within 2 cm of another scan's ({args.geometry} beams)")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes a small synthetic world folder in the `./rgnav bench localize` input contract.

Usage: make_synthetic_drive.py OUT_DIR [--seed N] [--laser-hz HZ]

OUT_DIR/map.pgm + map.yaml   ROS map_server trinary map (0.05 m cells) of a two-room building
                             with a door, rendered from the same rectangles the laser is cast on
OUT_DIR/track/               tracking drive: drive.carmen, truth.txt, start.txt (tracking ...)
OUT_DIR/global/              global drive (start.txt: global ...)

The world is a set of axis-aligned wall rectangles in the map frame. The map's origin is
deliberately not a multiple of the cell size and the odometry frame is deliberately far from the
map frame (odom starts at (1, -2, 0.5 rad)), so a mistake in the map origin, the PGM row order,
the laser mount or the frames shows up as an error of at least a few cells. Laser: 181 beams
-90..+90 deg, 1 deg apart, max range 8.18 m (= no return), range noise 0.01 m, mounted at
(0.12, 0, 0) on the base. Odometry: 50 Hz, +2 % translation scale, -3 % rotation scale, small
random walk. stdlib only.
"""
import argparse
import math
import os
import random

RES = 0.05
ORIGIN = (-1.037, -0.962)   # lower-left pixel corner in the map frame (not cell aligned)
WIDTH_M, HEIGHT_M = 12.1, 8.05
MAX_RANGE = 8.18
LASER_X = 0.12
T0 = 1000000000.0
ODOM_HZ = 50.0
SPEED = 0.4
ODOM0 = (1.0, -2.0, 0.5)   # odometry frame pose of the robot at the start of every drive


def walls():
    """Occupied rectangles (xmin, ymin, xmax, ymax) in the map frame."""
    t = 0.15
    r = [
        # outer shell of a 10 x 6 m building (inner faces at x=0, x=10, y=0, y=6)
        (-t, -t, 10 + t, 0), (-t, 6, 10 + t, 6 + t), (-t, -t, 0, 6 + t), (10, -t, 10 + t, 6 + t),
        # dividing wall at x = 5 with a 1 m door between y = 2.5 and 3.5
        (5 - t / 2, 0, 5 + t / 2, 2.5), (5 - t / 2, 3.5, 5 + t / 2, 6),
        # room A (west): a cupboard, a desk, a column
        (0, 4.6, 1.2, 6), (2.0, 0.8, 3.4, 1.5), (3.9, 4.3, 4.3, 4.7),
        # room B (east): an alcove wall, two boxes and a column
        (7.0, 0, 7.15, 1.6), (8.4, 3.8, 9.6, 4.4), (5.6, 5.2, 6.2, 6), (8.8, 1.2, 9.1, 1.5),
    ]
    return r


def inside_building(x, y):
    return 0 <= x <= 10 and 0 <= y <= 6


def write_map(out, rects):
    w = int(round(WIDTH_M / RES))
    h = int(round(HEIGHT_M / RES))
    rows = []
    for row in range(h):               # PGM row 0 is the top of the image
        j = h - 1 - row                  # cell index from the bottom
        y = ORIGIN[1] + (j + 0.5) * RES
        line = bytearray(w)
        for i in range(w):
            x = ORIGIN[0] + (i + 0.5) * RES
            if any(a <= x <= c and b <= y <= d for a, b, c, d in rects):
                line[i] = 0
            elif inside_building(x, y):
                line[i] = 254
            else:
                line[i] = 205
        rows.append(bytes(line))
    with open(os.path.join(out, "map.pgm"), "wb") as f:
        f.write(b"P5\n# synthetic two-room map\n%d %d\n255\n" % (w, h))
        for r in rows:
            f.write(r)
    with open(os.path.join(out, "map.yaml"), "w") as f:
        f.write("image: map.pgm\nresolution: %.3f\norigin: [%.3f, %.3f, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n" % (RES, ORIGIN[0], ORIGIN[1]))


def ray_cast(rects, x, y, a):
    """Distance along direction a to the first rectangle, or MAX_RANGE."""
    dx, dy = math.cos(a), math.sin(a)
    best = MAX_RANGE
    for (x0, y0, x1, y1) in rects:
        tmin, tmax = 0.0, best
        if abs(dx) < 1e-12:
            if x < x0 or x > x1:
                continue
        else:
            ta, tb = (x0 - x) / dx, (x1 - x) / dx
            if ta > tb:
                ta, tb = tb, ta
            tmin, tmax = max(tmin, ta), min(tmax, tb)
            if tmin > tmax:
                continue
        if abs(dy) < 1e-12:
            if y < y0 or y > y1:
                continue
        else:
            ta, tb = (y0 - y) / dy, (y1 - y) / dy
            if ta > tb:
                ta, tb = tb, ta
            tmin, tmax = max(tmin, ta), min(tmax, tb)
            if tmin > tmax:
                continue
        if tmin < best:
            best = tmin
    return best


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def compose(p, q):
    c, s = math.cos(p[2]), math.sin(p[2])
    return (p[0] + c * q[0] - s * q[1], p[1] + s * q[0] + c * q[1], wrap(p[2] + q[2]))


def simulate(start, waypoints, rng, laser_hz):
    """True poses at 50 Hz following the waypoints (unicycle, turn-then-drive), odometry with
    drift, and which samples carry a laser scan."""
    dt = 1.0 / ODOM_HZ
    x, y, th = start
    ox, oy, oth = ODOM0
    true, odom = [(x, y, th)], [(ox, oy, oth)]
    vel = [(0.0, 0.0)]
    for wx, wy in waypoints:
        while True:
            d = math.hypot(wx - x, wy - y)
            if d < 0.05:
                break
            err = wrap(math.atan2(wy - y, wx - x) - th)
            w = max(-0.8, min(0.8, 2.0 * err))
            v = SPEED * max(0.0, math.cos(err)) ** 4 if abs(err) < 1.0 else 0.0
            v = min(v, d / dt)
            # true motion (exact arc)
            ds, dth = v * dt, w * dt
            x += ds * math.cos(th + dth / 2)
            y += ds * math.sin(th + dth / 2)
            th = wrap(th + dth)
            # odometry: scale errors and a little noise
            ods = ds * 1.02 + rng.gauss(0, 0.0005) * (ds > 0)
            odth = dth * 0.97 + rng.gauss(0, 0.0005)
            ox += ods * math.cos(oth + odth / 2)
            oy += ods * math.sin(oth + odth / 2)
            oth = wrap(oth + odth)
            true.append((x, y, th))
            odom.append((ox, oy, oth))
            vel.append((v, w))
    every = max(1, int(round(ODOM_HZ / laser_hz)))
    return true, odom, vel, every


def write_drive(folder, rects, mode, start, waypoints, rng, laser_hz):
    os.makedirs(folder, exist_ok=True)
    true, odom, vel, every = simulate(start, waypoints, rng, laser_hz)
    angles = [math.radians(-90 + k) for k in range(181)]
    carmen, truth = [], []
    for k, (tp, op, (v, w)) in enumerate(zip(true, odom, vel)):
        t = T0 + k / ODOM_HZ
        carmen.append("ODOM %.6f %.6f %.6f %.4f %.4f 0.0 %.3f sim %.3f" % (op + (v, w, t, t)))
        if k % every:
            continue
        lp = compose(tp, (LASER_X, 0.0, 0.0))
        ranges = []
        for a in angles:
            r = ray_cast(rects, lp[0], lp[1], lp[2] + a)
            if r < MAX_RANGE:
                r = min(MAX_RANGE - 0.01, max(0.02, r + rng.gauss(0, 0.01)))
            ranges.append("%.3f" % r)
        olp = compose(op, (LASER_X, 0.0, 0.0))
        carmen.append("FLASER 181 %s %.6f %.6f %.6f %.6f %.6f %.6f %.3f sim %.3f" % (
            " ".join(ranges), olp[0], olp[1], olp[2], op[0], op[1], op[2], t, t))
        truth.append("%.3f %.6f %.6f %.6f" % (t, tp[0], tp[1], tp[2]))
    with open(os.path.join(folder, "drive.carmen"), "w") as f:
        f.write("# synthetic drive (make_synthetic_drive.py)\n" + "\n".join(carmen) + "\n")
    with open(os.path.join(folder, "truth.txt"), "w") as f:
        f.write("\n".join(truth) + "\n")
    with open(os.path.join(folder, "start.txt"), "w") as f:
        f.write("%s %.6f %.6f %.6f\n" % ((mode,) + tuple(start)))
    return len(truth), (len(true) - 1) / ODOM_HZ


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--laser-hz", type=float, default=10.0)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    os.makedirs(a.out, exist_ok=True)
    rects = walls()
    write_map(a.out, rects)
    # tracking: room A -> door -> room B
    n1, d1 = write_drive(os.path.join(a.out, "track"), rects, "tracking", (1.0, 1.0, 0.3),
                         [(3.5, 2.6), (4.4, 3.0), (6.0, 3.0), (8.0, 2.4), (8.0, 5.2), (6.8, 4.4)],
                         rng, a.laser_hz)
    # global: starts in room B, drives into room A
    n2, d2 = write_drive(os.path.join(a.out, "global"), rects, "global", (8.2, 3.0, 2.6),
                         [(6.0, 3.0), (4.0, 3.0), (2.0, 3.4), (1.6, 2.0), (3.0, 2.2)],
                         rng, a.laser_hz)
    print("wrote %s: track %d scans / %.1f s, global %d scans / %.1f s" % (a.out, n1, d1, n2, d2))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""How far the scan mapper's SLAM_POSE was from the simulator's SIM_TRUTH over a recorded run.

Usage: deploy/tools/slam_vs_truth.py RUN/lcm/rgnav.lcmlog [--every S] [--trajectory FILE]

Reads the LCM event log directly (no LCM bindings needed): both channels carry fingerprinted
structs whose first fields are utime and a pose (odometry_t: utime, seq, pose; slam_pose_t:
utime, scan_id, pose). The SLAM map frame is the robot's pose at the first scan, so the true
pose is expressed relative to the first truth sample. Prints the error every S seconds and the
maximum; exits 1 if either channel is missing.

--trajectory FILE compares an offline replay instead of the logged SLAM_POSE: the trajectory.txt
that `rgnav map LOG --out DIR` writes (scan_id utime x y theta ..., final estimates, so after
every loop closure), against the same log's SIM_TRUTH.
"""
import argparse
import bisect
import math
import struct
import sys

SYNC = 0xEDA1DA01


def read_poses(path, channels):
    """{channel: [(utime, (x, y, theta))]} for the given channels."""
    data = open(path, "rb").read()
    out = {c: [] for c in channels}
    i = 0
    while i + 28 <= len(data):
        sync, _, _, clen, dlen = struct.unpack(">IqqII", data[i:i + 28])
        if sync != SYNC:  # not at an event: resynchronise byte by byte
            i += 1
            continue
        channel = data[i + 28:i + 28 + clen].decode(errors="replace")
        payload = data[i + 28 + clen:i + 28 + clen + dlen]
        if channel in out and len(payload) >= 48:
            # 8-byte fingerprint, utime, a second int64, then pose2d_t (x, y, theta).
            utime = struct.unpack(">q", payload[8:16])[0]
            out[channel].append((utime, struct.unpack(">ddd", payload[24:48])))
        i += 28 + clen + dlen
    return out


def read_trajectory(path):
    """[(utime, (x, y, theta))] of a trajectory.txt (comment lines start with #)."""
    out = []
    for line in open(path):
        f = line.split()
        if f and not f[0].startswith("#"):
            out.append((int(f[1]), (float(f[2]), float(f[3]), float(f[4]))))
    return out


def relative(a, b):
    """b in the frame of a (2D poses)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    th = (b[2] - a[2] + math.pi) % (2 * math.pi) - math.pi
    return c * dx + s * dy, -s * dx + c * dy, th


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log")
    ap.add_argument("--every", type=float, default=10.0, help="print interval [s] (0: only the summary)")
    ap.add_argument("--trajectory", help="rgnav map's trajectory.txt to compare instead of SLAM_POSE")
    args = ap.parse_args()
    poses = read_poses(args.log, ["SIM_TRUTH", "SLAM_POSE"])
    truth, slam = poses["SIM_TRUTH"], poses["SLAM_POSE"]
    if args.trajectory:
        slam = read_trajectory(args.trajectory)
    if not truth or not slam:
        print("slam_vs_truth: the log has no SIM_TRUTH or no SLAM_POSE", file=sys.stderr)
        return 1
    stamps = [t for t, _ in truth]
    origin = truth[min(bisect.bisect_left(stamps, slam[0][0]), len(stamps) - 1)][1]
    worst, last_print = (0.0, 0.0), -1e18
    for utime, est in slam:
        k = min(bisect.bisect_left(stamps, utime), len(stamps) - 1)
        true_world = truth[k][1]
        x, y, th = relative(origin, true_world)
        err = math.hypot(est[0] - x, est[1] - y)
        err_deg = math.degrees((est[2] - th + math.pi) % (2 * math.pi) - math.pi)
        t = (utime - slam[0][0]) / 1e6
        if err > worst[0]:
            worst = (err, t)
        if args.every > 0 and t - last_print >= args.every:
            last_print = t
            print(f"{t:7.1f} s  true ({true_world[0]:6.2f}, {true_world[1]:6.2f})  error {err:5.2f} m {err_deg:6.1f} deg")
    what = "trajectory poses" if args.trajectory else "SLAM_POSE messages"
    print(f"max error {worst[0]:.2f} m at {worst[1]:.1f} s over {len(slam)} {what}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""MRPT's pf-localization (Debian mrpt-apps 2.5.x) on the drives of a localize-benchmark world.

Usage: mrpt_localize.py W [--drives D1 D2 ...] [--out W/mrpt.json] [--jobs 1]
                          [--ini deploy/bench/mrpt/pf-localization.ini] [--work W/mrpt_work]
                          [--scan-period S] [--max-range 8.18] [--solid-walls]
                          [--set SECTION.KEY=VALUE ...]

W holds map.pgm + map.yaml (ROS map_server, the map frame) and one folder per drive with
drive.carmen (ODOM + FLASER in the odometry frame, the log's own timestamps), truth.txt
(t x y theta of the base in the map frame at every scan) and start.txt ("tracking x y theta":
start there; "global x y theta": start uniformly over the free cells, the pose is only the truth).
Once per world it
  * converts map.yaml with ros-map-yaml2mrpt to a .gridmap, writes the ini's likelihood options
    into it (pf-localization takes them from the .gridmap, not from the ini), sets the occupied
    cells that touch no free cell to unknown (wall interiors; --solid-walls keeps them) and
    reads back where MRPT put the grid: MRPT snaps the map origin to a multiple of the cell
    size, so the MRPT frame is the map frame shifted by delta = (grid x_min, y_min) - yaml
    origin; starting boxes are shifted by +delta and every estimate by -delta;
and per drive it
  1. converts the FLASER lines (one per [rgnav] scan_period_s) to an observations-only rawlog
     with carmen2rawlog and puts the log's own timestamps on every observation
     (carmen2rawlog 2.5.x stamps all of them with the wall time of the conversion; see
     carmen2rawlog_timestamp_scale()), verified against the log afterwards;
  2. runs pf-localization with a per-drive copy of the ini template (start box or uniform start,
     particle count, the [rgnav] "<mode>.<Section>.<key>" settings, then --set) and reads the
     mean of the particles after every filter step from its log ("PDF estimation: (x,y,phi)"),
     checking step k against scan k with MRPT's own odometry integration;
  3. compares with truth.txt: at every truth time the last estimate is carried forward with the
     odometry since its scan (est (+) (odo_k (-) odo_t)), errors are wrapped (angles), and writes
     W/mrpt_work/<drive>/estimate.txt (t, estimate, truth, errors).
The JSON (default W/mrpt.json) holds tracking RMSE/p95/max over all steps of all tracking drives
and the divergences (drives with any step over 0.5 m), the global success ratio (a t* exists with
every later step within 0.3 m and 10 deg, t* - t0 <= 10 s) with the median time and odometry
travel to t* over the successful trials, and per drive the figures, the mean error in the robot
frame (bias), the CPU seconds of pf-localization and the reason of any failure. A drive whose run
fails is counted as failed (and as an unsuccessful global trial), never dropped. stdlib only.
"""
import argparse
import bisect
import concurrent.futures
import gzip
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_INI = os.path.join(HERE, "pf-localization.ini")
TRACK_DIVERGED_M = 0.5
GLOBAL_OK_M, GLOBAL_OK_DEG, GLOBAL_MAX_S = 0.3, 10.0, 10.0


class DriveError(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# small pose helpers
def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def compose(p, q):
    c, s = math.cos(p[2]), math.sin(p[2])
    return (p[0] + c * q[0] - s * q[1], p[1] + s * q[0] + c * q[1], wrap(p[2] + q[2]))


def inverse(p):
    c, s = math.cos(p[2]), math.sin(p[2])
    return (-c * p[0] - s * p[1], s * p[0] - c * p[1], wrap(-p[2]))


def percentile(values, q):
    """Linear-interpolated percentile (q in 0..100) of a non-empty list."""
    v = sorted(values)
    if len(v) == 1:
        return v[0]
    k = (len(v) - 1) * q / 100.0
    i = int(math.floor(k))
    j = min(i + 1, len(v) - 1)
    return v[i] + (v[j] - v[i]) * (k - i)


def rnd(x, n=4):
    return None if x is None else round(x, n)


# ---------------------------------------------------------------------------------------------
# ini template handling (MRPT's ini dialect: [section], key = value, # and // comments)
class Ini:
    def __init__(self, path):
        self.lines = open(path).read().splitlines()

    def _find(self, section, key):
        sec = None
        for i, line in enumerate(self.lines):
            s = line.strip()
            if s.startswith("[") and s.endswith("]"):
                sec = s[1:-1].strip()
                continue
            if sec == section and "=" in s and not s.startswith(("#", "//", ";")):
                if s.split("=", 1)[0].strip() == key:
                    return i
        return None

    def get(self, section, key, default=None):
        i = self._find(section, key)
        if i is None:
            return default
        v = self.lines[i].split("=", 1)[1]
        v = re.split(r"\s//|\s#", " " + v)[0] if ("//" in v or "#" in v) else v
        return v.strip()

    def getf(self, section, key, default):
        v = self.get(section, key)
        return default if v is None or v == "" else float(v)

    def items(self, section):
        """(key, value) of a section, in order."""
        sec, out = None, []
        for line in self.lines:
            s = line.strip()
            if s.startswith("[") and s.endswith("]"):
                sec = s[1:-1].strip()
                continue
            if sec == section and "=" in s and not s.startswith(("#", "//", ";")):
                k, v = s.split("=", 1)
                out.append((k.strip(), v.strip()))
        return out

    def set(self, section, key, value):
        i = self._find(section, key)
        text = "%s = %s" % (key, value)
        if i is not None:
            self.lines[i] = text
            return
        # append at the end of the section (create it if needed)
        sec, last = None, None
        for j, line in enumerate(self.lines):
            s = line.strip()
            if s.startswith("[") and s.endswith("]"):
                sec = s[1:-1].strip()
            if sec == section:
                last = j
        if last is None:
            self.lines += ["", "[%s]" % section, text]
        else:
            self.lines.insert(last + 1, text)

    def write(self, path):
        with open(path, "w") as f:
            f.write("\n".join(self.lines) + "\n")


# ---------------------------------------------------------------------------------------------
# inputs
def read_map_yaml(path):
    """The few keys of a ROS map_server yaml we need (flat yaml, no library needed)."""
    out = {}
    for line in open(path):
        line = line.split("#", 1)[0].strip()
        if ":" not in line:
            continue
        k, v = line.split(":", 1)
        out[k.strip()] = v.strip()
    res = float(out["resolution"])
    origin = [float(x) for x in out["origin"].strip("[]").split(",")]
    if len(origin) < 2:
        raise ValueError("map.yaml origin: %r" % out["origin"])
    if len(origin) > 2 and abs(origin[2]) > 1e-9:
        raise ValueError("map.yaml origin yaw %g != 0 is not supported" % origin[2])
    return res, origin[0], origin[1]


def read_carmen(path):
    """ODOM samples [(t, (x, y, th))] and FLASER scans [dict]."""
    odom, scans = [], []
    for ln, line in enumerate(open(path), 1):
        f = line.split()
        if not f:
            continue
        if f[0] == "ODOM":
            if len(f) < 8:
                raise DriveError("drive.carmen line %d: short ODOM" % ln)
            odom.append((float(f[7]), (float(f[1]), float(f[2]), float(f[3]))))
        elif f[0] == "FLASER":
            n = int(f[1])
            if len(f) < 2 + n + 7:
                raise DriveError("drive.carmen line %d: short FLASER" % ln)
            r = f[2:2 + n]
            p = [float(x) for x in f[2 + n:2 + n + 6]]
            scans.append({"t": float(f[2 + n + 6]), "ranges": r, "laser": tuple(p[0:3]),
                          "odom": tuple(p[3:6]), "host": f[2 + n + 7] if len(f) > 2 + n + 7 else "x"})
    odom.sort(key=lambda s: s[0])
    scans.sort(key=lambda s: s["t"])
    return odom, scans


def read_truth(path):
    out = []
    for line in open(path):
        f = line.split()
        if len(f) >= 4 and not f[0].startswith("#"):
            out.append((float(f[0]), (float(f[1]), float(f[2]), float(f[3]))))
    out.sort(key=lambda s: s[0])
    return out


def read_start(path):
    f = open(path).read().split()
    if len(f) < 4 or f[0] not in ("tracking", "global"):
        raise DriveError("start.txt: expected 'tracking|global x y theta', got %r" % " ".join(f))
    return f[0], (float(f[1]), float(f[2]), float(f[3]))


class OdomLookup:
    """Odometry pose at any time: exact at FLASER/ODOM samples, linear in between."""

    def __init__(self, odom, scans):
        d = {}
        for t, p in odom:
            d[t] = p
        for s in scans:
            d[s["t"]] = s["odom"]     # the scan's own odometry wins at its time
        self.t = sorted(d)
        self.p = [d[t] for t in self.t]

    def at(self, t):
        i = bisect.bisect_left(self.t, t)
        if i < len(self.t) and abs(self.t[i] - t) < 1e-6:
            return self.p[i]
        if i == 0 or i >= len(self.t):
            return self.p[0] if i == 0 else self.p[-1]
        t0, t1 = self.t[i - 1], self.t[i]
        a, b = self.p[i - 1], self.p[i]
        u = (t - t0) / (t1 - t0)
        return (a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1]), wrap(a[2] + u * wrap(b[2] - a[2])))

    def path_length(self, t_from, t_to):
        d, prev = 0.0, None
        for t, p in zip(self.t, self.p):
            if t < t_from - 1e-9:
                continue
            if t > t_to + 1e-9:
                break
            if prev is not None:
                d += math.hypot(p[0] - prev[0], p[1] - prev[1])
            prev = p
        return d


# ---------------------------------------------------------------------------------------------
# MRPT tools
def run(cmd, cwd=None, timeout=600):
    p = subprocess.run(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=timeout)
    out = p.stdout.decode(errors="replace")
    if p.returncode != 0:
        raise DriveError("%s failed (exit %d): %s" % (os.path.basename(cmd[0]), p.returncode,
                                                     out.strip()[-400:]))
    return out


def list_timestamps(rawlog, workdir):
    txt = os.path.join(workdir, os.path.basename(rawlog) + ".timestamps.txt")
    run(["rawlog-edit", "-q", "--list-timestamps", "-i", rawlog, "--text-file-output", txt])
    out = []
    for line in open(txt):
        f = line.split()
        if len(f) >= 2:
            out.append((float(f[0]), f[1]))
    return out


def carmen_to_rawlog(scans, out_rawlog, workdir, max_range, ts_scale):
    """carmen2rawlog on the given FLASER scans with their times relative to the first scan,
    written as (t - t0) * ts_scale. Returns the relative times (microsecond-rounded)."""
    n = len(scans[0]["ranges"])
    # MRPT: aperture = resolution * n, beam i at -aperture/2 + i * aperture / (n - 1). The
    # contract's beams cover -90..+90 deg inclusive, so aperture must be 180 deg exactly.
    res_deg = 180.0 / n
    t0 = scans[0]["t"]
    rel = []
    lines = ["PARAM robot_front_laser_max %.4f" % max_range,
             "PARAM laser_front_laser_resolution %.12f" % res_deg]
    for s in scans:
        if len(s["ranges"]) != n:
            raise DriveError("FLASER with %d beams after %d" % (len(s["ranges"]), n))
        us = int(round((s["t"] - t0) * 1e6))
        rel.append(us * 1e-6)
        stamp = "%.1f" % ((us + 0.5) * 1e-6 * ts_scale) if ts_scale != 1.0 else "%.6f" % (us * 1e-6)
        lines.append("FLASER %d %s %.6f %.6f %.6f %.6f %.6f %.6f %s %s %s" % (
            (n, " ".join(s["ranges"])) + s["laser"] + s["odom"] + (stamp, s["host"], stamp)))
    src = re.sub(r"\.rawlog$", "", out_rawlog) + ".carmen2rawlog.log"
    with open(src, "w") as f:
        f.write("\n".join(lines) + "\n")
    run(["carmen2rawlog", "-q", "-w", "-z", "1", "-i", src, "-o", out_rawlog])
    # carmen2rawlog also writes <out>.gt.txt ("ground truth" = the odometry here): not needed
    gt = re.sub(r"\.rawlog$", "", out_rawlog) + ".gt.txt"
    if os.path.exists(gt):
        os.remove(gt)
    return rel


def carmen2rawlog_timestamp_scale(workdir):
    """carmen2rawlog 2.5.x computes an observation's time as now() + microseconds(1e-6 * t)
    (a 1e12 unit slip), so every observation gets the wall time of the conversion. Probe with
    two scans one second apart: if they come out 1 s apart the tool is fixed (scale 1), if they
    come out equal, writing the times as t * 1e12 makes it produce now() + t (scale 1e12)."""
    probe = [{"t": 0.0, "ranges": ["1.0"] * 181, "laser": (0.12, 0, 0), "odom": (0, 0, 0),
              "host": "probe"},
             {"t": 1.0, "ranges": ["1.0"] * 181, "laser": (0.12, 0, 0), "odom": (0, 0, 0),
              "host": "probe"}]
    path = os.path.join(workdir, "probe.rawlog")
    for scale in (1.0, 1e12):
        carmen_to_rawlog(probe, path, workdir, 8.18, scale)
        ts = [t for t, label in list_timestamps(path, workdir) if label == "FLASER"]
        if len(ts) == 2 and abs((ts[1] - ts[0]) - 1.0) < 1e-3:
            return scale
    raise DriveError("carmen2rawlog: cannot make it keep the log's timestamps (probe failed)")


def make_rawlog(scans, rawlog, workdir, max_range, scale):
    """Observations-only rawlog (per scan: CObservationOdometry then CObservation2DRangeScan)
    whose every observation carries the CARMEN log's own timestamp; verified."""
    tmp = re.sub(r"\.rawlog$", "", rawlog) + ".wallclock.rawlog"
    rel = carmen_to_rawlog(scans, tmp, workdir, max_range, scale)
    got = list_timestamps(tmp, workdir)
    flaser = [t for t, label in got if label == "FLASER"]
    if len(flaser) != len(scans):
        raise DriveError("rawlog has %d scans, expected %d" % (len(flaser), len(scans)))
    base = flaser[0]
    for k, (t, r) in enumerate(zip(flaser, rel)):
        if abs((t - base) - r) > 1e-4:
            raise DriveError("carmen2rawlog time of scan %d is +%.6f s, log says +%.6f s" % (k, t - base, r))
    # shift to the log's own absolute times
    b = scans[0]["t"] - base
    run(["rawlog-edit", "-q", "-w", "--remap-timestamps", "1;%.6f" % b, "-i", tmp, "-o", rawlog])
    got = list_timestamps(rawlog, workdir)
    if len(got) != 2 * len(scans):
        raise DriveError("rawlog has %d observations, expected %d" % (len(got), 2 * len(scans)))
    # carmen2rawlog writes ODOMETRY then FLASER per scan, both with the scan's time
    want = [lbl for _ in scans for lbl in ("ODOMETRY", "FLASER")]
    if [label for _, label in got] != want:
        raise DriveError("rawlog observations are not ODOMETRY, FLASER per scan")
    worst = max(abs(t - scans[i // 2]["t"]) for i, (t, _) in enumerate(got))
    if worst > 1e-4:
        raise DriveError("rawlog timestamps off the log's by up to %.6f s" % worst)
    os.remove(tmp)
    return worst


GRID_CLASS = b"mrpt::maps::COccupancyGridMap2D"


def parse_gridmap(data):
    """Header of a serialized COccupancyGridMap2D (v6, 8-bit cells) and the offset of the
    options that follow the cells."""
    if data[0] != (0x80 | len(GRID_CLASS)) or data[1:1 + len(GRID_CLASS)] != GRID_CLASS:
        raise DriveError("not a COccupancyGridMap2D file")
    i = 1 + len(GRID_CLASS)
    version, bits = data[i], data[i + 1]
    if version != 6 or bits != 8:
        raise DriveError("gridmap serialization version %d / %d bits not supported" % (version, bits))
    sx, sy = struct.unpack_from("<II", data, i + 2)
    x_min, x_max, y_min, y_max, res = struct.unpack_from("<5f", data, i + 10)
    cells = i + 30
    opts = cells + sx * sy
    return {"size_x": sx, "size_y": sy, "x_min": x_min, "x_max": x_max, "y_min": y_min,
            "y_max": y_max, "resolution": res, "cells": cells, "opts": opts}


LIKELIHOOD_FIELDS = [  # serialized order after the insertion options (COccupancyGridMap2D v6)
    ("likelihoodMethod", "i"), ("LF_stdHit", "f"), ("LF_zHit", "f"), ("LF_zRandom", "f"),
    ("LF_maxRange", "f"), ("LF_decimation", "I"), ("LF_maxCorrsDistance", "f"),
    ("LF_alternateAverageMethod", "?"), ("MI_exponent", "f"), ("MI_skip_rays", "I"),
    ("MI_ratio_max_distance", "f"), ("rayTracing_useDistanceFilter", "?"),
    ("rayTracing_decimation", "i"), ("rayTracing_stdHit", "f"),
    ("consensus_takeEachRange", "i"), ("consensus_pow", "f")]


def patch_gridmap_options(data, g, ini):
    """Write [MetricMap_occupancyGrid_00_likelihoodOpts] into the serialized grid. v6 layout
    after the cells: insertionOptions (float mapAltitude, bool useMapAltitude, float
    maxDistanceInsertion, float maxOccupancyUpdateCertainty, bool
    considerInvalidRangesAsFreeSpace, uint16 decimation, float horizontalTolerance), then the
    likelihood options of LIKELIHOOD_FIELDS, vector<float> OWA_weights (uint32 n + n floats),
    bool enableLikelihoodCache, then genericMapParams etc. (left alone)."""
    sec = "MetricMap_occupancyGrid_00_likelihoodOpts"
    b = bytearray(data)
    o = g["opts"] + 4 + 1 + 4 + 4 + 1 + 2 + 4
    fmt = "<" + "".join(t for _, t in LIKELIHOOD_FIELDS)
    cur = list(struct.unpack_from(fmt, b, o))
    used = {}
    for k, (name, t) in enumerate(LIKELIHOOD_FIELDS):
        v = ini.get(sec, name)
        if v is not None and v != "":
            if t == "f":
                cur[k] = float(v)
            elif t == "?":
                cur[k] = v.lower() in ("1", "true", "yes", "y")
            else:
                cur[k] = int(float(v))
        used[name] = rnd(cur[k]) if t == "f" else (bool(cur[k]) if t == "?" else int(cur[k]))
    if not 0 <= cur[0] <= 6:
        raise DriveError("likelihoodMethod %d out of range" % cur[0])
    struct.pack_into(fmt, b, o, *cur)
    p = o + struct.calcsize(fmt)
    (n_owa,) = struct.unpack_from("<I", b, p)
    if n_owa > 100000:
        raise DriveError("unexpected gridmap options layout (OWA_weights size %d)" % n_owa)
    p += 4 + 4 * n_owa
    if b[p] not in (0, 1):
        raise DriveError("unexpected gridmap options layout (enableLikelihoodCache byte %d)" % b[p])
    v = ini.get(sec, "enableLikelihoodCache")
    if v is not None and v != "":
        b[p] = 1 if v.lower() in ("1", "true", "yes", "y") else 0
    used["enableLikelihoodCache"] = bool(b[p])
    return bytes(b), used


def hollow_walls(data, g):
    """Occupied cells (log-odds < 0) with no free cell (log-odds > 0) among their 8 neighbours
    become unknown (0): MRPT's likelihood field scores an end point by the distance to the
    nearest occupied cell, so inside a solid wall every end point scores as a perfect hit."""
    sx, sy, c0 = g["size_x"], g["size_y"], g["cells"]
    cells = data[c0:c0 + sx * sy]
    occ = [v >= 128 for v in cells]
    free = [0 < v < 128 for v in cells]
    out = bytearray(cells)
    n = 0
    for y in range(sy):
        for x in range(sx):
            i = x + y * sx
            if not occ[i]:
                continue
            touch = False
            for dy in (-1, 0, 1):
                yy = y + dy
                if 0 <= yy < sy:
                    for dx in (-1, 0, 1):
                        xx = x + dx
                        if 0 <= xx < sx and free[xx + yy * sx]:
                            touch = True
            if not touch:
                out[i] = 0
                n += 1
    return data[:c0] + bytes(out) + data[c0 + sx * sy:], n


def make_gridmap(world, workdir, ini, hollow=False):
    """map.yaml -> workdir/map.gridmap.gz (ros-map-yaml2mrpt + likelihood options) and the
    shift delta from the map frame to MRPT's frame."""
    res, ox, oy = read_map_yaml(os.path.join(world, "map.yaml"))
    # ros-map-yaml2mrpt writes <yaml name>.gridmap.gz next to -d; work on a copy of the yaml so
    # the image path stays valid (absolute).
    yaml_src = os.path.join(world, "map.yaml")
    yaml_copy = os.path.join(workdir, "map.yaml")
    lines = []
    for line in open(yaml_src):
        if line.strip().startswith("image:"):
            img = line.split(":", 1)[1].strip().strip("'\"")
            if not os.path.isabs(img):
                img = os.path.abspath(os.path.join(world, img))
            line = "image: %s\n" % img
        lines.append(line)
    open(yaml_copy, "w").write("".join(lines))
    run(["ros-map-yaml2mrpt", "-q", "-w", "-i", yaml_copy, "-d", workdir])
    path = os.path.join(workdir, "map.gridmap.gz")
    data = gzip.open(path, "rb").read()
    g = parse_gridmap(data)
    if abs(g["resolution"] - res) > 1e-6:
        raise DriveError("gridmap resolution %g != yaml %g" % (g["resolution"], res))
    data, opts = patch_gridmap_options(data, g, ini)
    if hollow:
        data, opts["hollowed_cells"] = hollow_walls(data, g)
    with gzip.open(path, "wb", compresslevel=1) as f:
        f.write(data)
    # verify the patch round-trips
    g2 = parse_gridmap(gzip.open(path, "rb").read())
    delta = (g2["x_min"] - ox, g2["y_min"] - oy)
    if max(abs(delta[0]), abs(delta[1])) > res / 2 + 1e-6:
        raise DriveError("MRPT grid origin (%g, %g) is more than half a cell from the yaml's "
                         "(%g, %g)" % (g2["x_min"], g2["y_min"], ox, oy))
    return path, g2, delta, opts


# ---------------------------------------------------------------------------------------------
# pf-localization
EST_RE = re.compile(r"PDF estimation:\s*\(\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*deg\s*\)")
ODO_RE = re.compile(r"Odometry estimation:\s*\(\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*deg\s*\)")
NPART_RE = re.compile(r"Executing ParticleFilter on\s+(\d+)\s+particles")
VERSION_RE = re.compile(r"MRPT\s+([0-9]+\.[0-9]+\.[0-9]+)")


def run_pf_localization(ini_path, cwd, log_path, timeout_s):
    """pf-localization INI; returns (exit code or None if killed, cpu seconds, wall seconds,
    peak resident memory in MB)."""
    t0 = time.time()
    with open(log_path, "wb") as log:
        p = subprocess.Popen(["pf-localization", ini_path], cwd=cwd, stdin=subprocess.DEVNULL,
                             stdout=log, stderr=subprocess.STDOUT)
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid == p.pid:
                break
            if time.time() - t0 > timeout_s:
                p.kill()
                pid, status, ru = os.wait4(p.pid, 0)
                p.returncode = -9
                return None, ru.ru_utime + ru.ru_stime, time.time() - t0, ru.ru_maxrss / 1024.0
            time.sleep(0.05)
    p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, ru.ru_utime + ru.ru_stime, time.time() - t0, ru.ru_maxrss / 1024.0


def parse_pf_log(log_path):
    est, odo, npart, version = [], [], [], None
    for line in open(log_path, errors="replace"):
        m = EST_RE.search(line)
        if m:
            est.append((float(m.group(1)), float(m.group(2)), math.radians(float(m.group(3)))))
            continue
        m = ODO_RE.search(line)
        if m:
            odo.append((float(m.group(1)), float(m.group(2)), math.radians(float(m.group(3)))))
            continue
        m = NPART_RE.search(line)
        if m:
            npart.append(int(m.group(1)))
            continue
        if version is None:
            m = VERSION_RE.search(line)
            if m:
                version = m.group(1)
    return est, odo, npart, version


# ---------------------------------------------------------------------------------------------
def select_scans(scans, period):
    out = []
    for s in scans:
        if not out or s["t"] - out[-1]["t"] >= period - 1e-6:
            out.append(s)
    return out


def run_drive(world, drive, work_root, tmpl_path, gridmap, delta, ts_scale):
    ddir = os.path.join(world, drive)
    wdir = os.path.join(work_root, drive)
    if os.path.isdir(wdir):
        shutil.rmtree(wdir)
    os.makedirs(wdir)
    result = {"status": "failed"}
    try:
        ini = Ini(tmpl_path)
        apply_sets(ini)      # first so that --set can change the [rgnav] mode settings too
        mode, start = read_start(os.path.join(ddir, "start.txt"))
        result["mode"] = mode
        # [rgnav] "<mode>.<Section>.<key> = value": MRPT settings for this kind of drive only
        mode_overrides = {}
        for k, v in ini.items("rgnav"):
            parts = k.split(".", 2)
            if len(parts) == 3 and parts[0] == mode:
                ini.set(parts[1], parts[2], v)
                mode_overrides["%s.%s" % (parts[1], parts[2])] = v
        apply_sets(ini)      # --set wins over everything
        if mode_overrides:
            result["mode_overrides"] = mode_overrides
        odom, scans = read_carmen(os.path.join(ddir, "drive.carmen"))
        truth = read_truth(os.path.join(ddir, "truth.txt"))
        if not scans:
            raise DriveError("drive.carmen has no FLASER lines")
        if not truth:
            raise DriveError("truth.txt is empty")
        period = ini.getf("rgnav", "scan_period_s", 0.2)
        if OPTS.scan_period is not None:
            period = OPTS.scan_period
        used = select_scans(scans, period)
        rawlog = os.path.join(wdir, "drive.rawlog")
        ts_err = make_rawlog(used, rawlog, wdir, OPTS.max_range, ts_scale)

        # per-drive ini
        sec = "LocalizationExperiment"
        ini.set(sec, "map_file", gridmap)
        ini.set(sec, "rawlog_file", rawlog)
        ini.set(sec, "logOutput_dir", os.path.join(wdir, "out"))
        ini.set(sec, "SHOW_PROGRESS_3D_REAL_TIME", "false")
        ini.set(sec, "3DSceneFrequency", "-1")
        ini.set(sec, "SAVE_STATS_ONLY", "false")
        if mode == "tracking":
            n = int(ini.getf("rgnav", "tracking_particles_count", 2000))
            hxy = math.sqrt(3) * ini.getf("rgnav", "tracking_init_std_xy", 0.1)
            hdeg = math.sqrt(3) * ini.getf("rgnav", "tracking_init_std_deg", 5.0)
            cx, cy = start[0] + delta[0], start[1] + delta[1]
            cdeg = math.degrees(start[2])
            ini.set(sec, "init_PDF_mode", "1")
            box = (cx - hxy, cx + hxy, cy - hxy, cy + hxy, cdeg - hdeg, cdeg + hdeg)
        else:
            n = int(ini.getf("rgnav", "global_particles_count", 200000))
            ini.set(sec, "init_PDF_mode", "0")
            box = (gridmap_info["x_min"], gridmap_info["x_max"], gridmap_info["y_min"],
                   gridmap_info["y_max"], -180.0, 180.0)
        for k, v in zip(("init_PDF_min_x", "init_PDF_max_x", "init_PDF_min_y", "init_PDF_max_y",
                         "init_PDF_min_yaw_deg", "init_PDF_max_yaw_deg"), box):
            ini.set(sec, k, "%.6f" % v)
        ini.set(sec, "particles_count", str(n))
        ini_path = os.path.join(wdir, "pf-localization.ini")
        ini.write(ini_path)
        result.update({"particles_init": n, "scans": len(scans), "updates": len(used),
                       "scan_period_s": period, "rawlog_timestamp_error_s": ts_err,
                       "ini": ini_path})

        timeout = ini.getf("rgnav", "timeout_s", 1800)
        log_path = os.path.join(wdir, "pf-localization.log")
        code, cpu, wall, rss = run_pf_localization(ini_path, wdir, log_path, timeout)
        result.update({"cpu_s": round(cpu, 2), "wall_s": round(wall, 2),
                       "max_rss_mb": round(rss, 1), "log": log_path})
        est, odo, npart, version = parse_pf_log(log_path)
        result["mrpt_version"] = version
        if code is None:
            raise DriveError("pf-localization killed after %.0f s" % timeout)
        if code != 0:
            text = open(log_path, errors="replace").read()
            m = re.search(r"Message:\s*(.*?)(?:\nLocation:|\nCall stack|$)", text, re.S)
            why = m.group(1).strip() if m else text.strip()[-400:]
            raise DriveError("pf-localization exit %d: %s" % (code, why[:600]))
        if len(est) != len(used):
            raise DriveError("pf-localization printed %d estimates for %d scans" % (len(est), len(used)))
        # the step <-> scan pairing, checked with MRPT's own odometry integration
        if len(odo) != len(used):
            raise DriveError("pf-localization printed %d odometry lines for %d scans" % (len(odo), len(used)))
        worst = 0.0
        o0 = used[0]["odom"]
        for s, o in zip(used, odo):
            rel = compose(inverse(o0), s["odom"])
            worst = max(worst, math.hypot(rel[0] - o[0], rel[1] - o[1]))
        result["odometry_pairing_error_m"] = rnd(worst, 5)
        if worst > 0.01:
            raise DriveError("MRPT's odometry disagrees with the log's by %.3f m" % worst)
        if npart:
            result["particles_final"] = npart[-1]
            result["particles_mean"] = round(sum(npart) / len(npart))
        # estimates in the map frame
        est_map = [(e[0] - delta[0], e[1] - delta[1], e[2]) for e in est]
        result.update(evaluate(mode, used, est_map, truth, OdomLookup(odom, scans), wdir))
        result["status"] = "ok"
    except DriveError as e:
        result["reason"] = str(e)
    except Exception as e:      # anything else: still reported, never dropped
        result["reason"] = "%s: %s" % (type(e).__name__, e)
    return drive, result


def evaluate(mode, used, est_map, truth, odo, wdir):
    ut = [s["t"] for s in used]
    rows, terr, rerr = [], [], []
    for t, tp in truth:
        k = bisect.bisect_right(ut, t + 1e-6) - 1
        if k < 0:
            continue          # before the first scan MRPT saw
        e = compose(est_map[k], compose(inverse(odo.at(ut[k])), odo.at(t)))
        dt = math.hypot(e[0] - tp[0], e[1] - tp[1])
        dr = abs(math.degrees(wrap(e[2] - tp[2])))
        rows.append((t, e, tp, dt, dr))
        terr.append(dt)
        rerr.append(dr)
    if not rows:
        raise DriveError("no truth sample at or after the first scan")
    with open(os.path.join(wdir, "estimate.txt"), "w") as f:
        f.write("# t est_x est_y est_theta truth_x truth_y truth_theta err_m err_deg (map frame)\n")
        for t, e, tp, dt, dr in rows:
            f.write("%.6f %.4f %.4f %.5f %.4f %.4f %.5f %.4f %.3f\n" % ((t,) + e + tp + (dt, dr)))
    # mean error in the robot frame (a pipeline error shows up here: a wrong laser mount as a
    # forward bias, a wrong map origin as a constant map-frame bias) and in the map frame
    fwd = [math.cos(tp[2]) * (e[0] - tp[0]) + math.sin(tp[2]) * (e[1] - tp[1]) for _, e, tp, _, _ in rows]
    lat = [-math.sin(tp[2]) * (e[0] - tp[0]) + math.cos(tp[2]) * (e[1] - tp[1]) for _, e, tp, _, _ in rows]
    mx = sum(e[0] - tp[0] for _, e, tp, _, _ in rows) / len(rows)
    my = sum(e[1] - tp[1] for _, e, tp, _, _ in rows) / len(rows)
    mth = sum(wrap(e[2] - tp[2]) for _, e, tp, _, _ in rows) / len(rows)
    est_path = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(est_map, est_map[1:]))
    tru_path = sum(math.hypot(b[1][0] - a[1][0], b[1][1] - a[1][1]) for a, b in zip(truth, truth[1:]))
    out = {"steps": len(rows), "estimate": os.path.join(wdir, "estimate.txt"),
           "bias_forward_m": rnd(sum(fwd) / len(fwd)), "bias_left_m": rnd(sum(lat) / len(lat)),
           "bias_map_m": [rnd(mx), rnd(my)], "bias_deg": rnd(math.degrees(mth), 3),
           "estimate_path_m": rnd(est_path, 3), "truth_path_m": rnd(tru_path, 3),
           "estimate_frozen": tru_path > 0.5 and est_path < 0.1 * tru_path,
           "rmse_m": rnd(math.sqrt(sum(x * x for x in terr) / len(terr))),
           "rmse_deg": rnd(math.sqrt(sum(x * x for x in rerr) / len(rerr)), 3),
           "p95_m": rnd(percentile(terr, 95)), "max_m": rnd(max(terr)),
           "final_m": rnd(terr[-1]), "final_deg": rnd(rerr[-1], 3),
           "_terr": terr, "_rerr": rerr}
    if mode == "tracking":
        over = sum(1 for x in terr if x > TRACK_DIVERGED_M)
        out.update({"steps_over_0_5m": over, "diverged": over > 0})
    else:
        t0 = truth[0][0]
        last_bad = None
        for i, (t, e, tp, dt, dr) in enumerate(rows):
            if dt > GLOBAL_OK_M or dr > GLOBAL_OK_DEG:
                last_bad = i
        if last_bad is None:
            i_star = 0
        elif last_bad + 1 < len(rows):
            i_star = last_bad + 1
        else:
            i_star = None
        if i_star is None:
            out.update({"converged": False, "success": False, "time_s": None, "travel_m": None})
        else:
            t_star = rows[i_star][0]
            out.update({"converged": True, "time_s": rnd(t_star - t0, 3),
                        "travel_m": rnd(odo.path_length(t0, t_star), 3),
                        "success": t_star - t0 <= GLOBAL_MAX_S + 1e-9})
    return out


def aggregate(per_drive):
    trk = [r for r in per_drive.values() if r.get("mode") == "tracking"]
    glb = [r for r in per_drive.values() if r.get("mode") == "global"]
    ok_trk = [r for r in trk if r["status"] == "ok"]
    terr = [x for r in ok_trk for x in r["_terr"]]
    rerr = [x for r in ok_trk for x in r["_rerr"]]
    tracking = {"drives": len(trk), "failed": len(trk) - len(ok_trk),
                "steps": len(terr),
                "rmse_m": rnd(math.sqrt(sum(x * x for x in terr) / len(terr))) if terr else None,
                "rmse_deg": rnd(math.sqrt(sum(x * x for x in rerr) / len(rerr)), 3) if rerr else None,
                "p95_m": rnd(percentile(terr, 95)) if terr else None,
                "max_m": rnd(max(terr)) if terr else None,
                "divergences": sum(1 for r in ok_trk if r["diverged"]),
                "cpu_s_total": round(sum(r.get("cpu_s", 0) for r in trk), 2)}
    succ = [r for r in glb if r["status"] == "ok" and r["success"]]
    glob = {"trials": len(glb), "failed": sum(1 for r in glb if r["status"] != "ok"),
            "successes": len(succ),
            "success_ratio": rnd(len(succ) / len(glb), 4) if glb else None,
            "time_s_p50": rnd(percentile([r["time_s"] for r in succ], 50), 3) if succ else None,
            "travel_m_p50": rnd(percentile([r["travel_m"] for r in succ], 50), 3) if succ else None,
            "cpu_s_total": round(sum(r.get("cpu_s", 0) for r in glb), 2)}
    unknown = [d for d, r in per_drive.items() if r.get("mode") not in ("tracking", "global")]
    return tracking, glob, unknown


def apply_sets(ini):
    for s in OPTS.set:
        m = re.match(r"^([^.=]+)\.([^=]+)=(.*)$", s)
        if not m:
            sys.exit("mrpt_localize.py: --set wants SECTION.KEY=VALUE, got %r" % s)
        ini.set(m.group(1).strip(), m.group(2).strip(), m.group(3).strip())


def mrpt_version_from_dpkg():
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", "mrpt-apps"],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout.decode()
        return out.strip() or None
    except OSError:
        return None


OPTS = None
gridmap_info = None


def main():
    global OPTS, gridmap_info
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("world")
    ap.add_argument("--drives", nargs="+")
    ap.add_argument("--out")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--ini", default=DEFAULT_INI)
    ap.add_argument("--work", help="work folder (default W/mrpt_work)")
    ap.add_argument("--scan-period", type=float, help="override [rgnav] scan_period_s")
    ap.add_argument("--max-range", type=float, default=8.18, help="no-return range of the laser")
    ap.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                    help="override an ini value (repeatable), e.g. "
                         "MetricMap_occupancyGrid_00_likelihoodOpts.likelihoodMethod=1")
    ap.add_argument("--solid-walls", action="store_true",
                    help="give MRPT the map exactly as rendered; by default the occupied cells "
                         "that touch no free cell are set to unknown (wall interiors; see README: "
                         "MRPT's likelihood field is flat inside thick walls)")
    OPTS = ap.parse_args()
    world = os.path.abspath(OPTS.world)
    out = OPTS.out or os.path.join(world, "mrpt.json")
    work = os.path.abspath(OPTS.work or os.path.join(world, "mrpt_work"))
    for tool in ("pf-localization", "carmen2rawlog", "rawlog-edit", "ros-map-yaml2mrpt"):
        if shutil.which(tool) is None:
            sys.exit("mrpt_localize.py: %s not found (Debian package mrpt-apps)" % tool)
    drives = OPTS.drives or sorted(d for d in os.listdir(world)
                                   if os.path.isfile(os.path.join(world, d, "drive.carmen")))
    if not drives:
        sys.exit("mrpt_localize.py: no drive folders (with drive.carmen) in %s" % world)
    os.makedirs(work, exist_ok=True)
    ini = Ini(OPTS.ini)
    apply_sets(ini)
    t_start = time.time()
    per_drive = {}
    try:
        gridmap, gridmap_info, delta, opts = make_gridmap(world, work, ini, not OPTS.solid_walls)
        ts_scale = carmen2rawlog_timestamp_scale(work)
    except Exception as e:      # every drive is then reported failed with this reason
        gridmap = None
        for d in drives:
            per_drive[d] = {"status": "failed", "reason": "map: %s" % e}
            try:
                per_drive[d]["mode"] = read_start(os.path.join(world, d, "start.txt"))[0]
            except Exception:
                pass
    if gridmap:
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, OPTS.jobs)) as ex:
            futs = [ex.submit(run_drive, world, d, work, OPTS.ini, gridmap, delta, ts_scale)
                    for d in drives]
            for f in futs:
                d, r = f.result()
                per_drive[d] = r
                show = {k: v for k, v in r.items() if not k.startswith("_") and k in (
                    "mode", "status", "reason", "rmse_m", "max_m", "diverged", "success",
                    "time_s", "cpu_s", "updates")}
                print("%s: %s" % (d, json.dumps(show)), flush=True)
    tracking, glob, unknown = aggregate(per_drive)
    versions = {r.get("mrpt_version") for r in per_drive.values() if r.get("mrpt_version")}
    result = {"tracking": tracking, "global": glob,
              "per_drive": {d: {k: v for k, v in r.items() if not k.startswith("_")}
                            for d, r in per_drive.items()},
              "mrpt_version": sorted(versions)[0] if len(versions) == 1 else (
                  sorted(versions) if versions else None),
              "mrpt_apps_package": mrpt_version_from_dpkg(),
              "ini": os.path.abspath(OPTS.ini),
              "ini_overrides": OPTS.set, "hollow_walls": not OPTS.solid_walls,
              "failed_drives": sorted(d for d, r in per_drive.items() if r["status"] != "ok"),
              "wall_s": round(time.time() - t_start, 1)}
    if gridmap:
        result["map"] = {"gridmap": gridmap, "mrpt_frame_shift_m": [rnd(delta[0], 5), rnd(delta[1], 5)],
                         "likelihood_options": opts}
    if unknown:
        result["drives_without_mode"] = unknown
    with open(out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    try:
        print(json.dumps({"tracking": tracking, "global": glob}, indent=1))
        print("wrote %s" % out)
    except BrokenPipeError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())

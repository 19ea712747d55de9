#!/usr/bin/env bash
# ./rgnav map <log.lcmlog> --out DIR [--config FILE] [--base-from-laser X Y THETA]
# Runs the scan mapper offline over an LCM log (LASER_FRONT + ODOMETRY), deterministically and
# as fast as the CPU allows; writes DIR/trajectory.txt, DIR/aligned_scans.lcmlog, DIR/map.png.
# --base-from-laser: the laser mounting pose of the robot that recorded the log (default: config).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,5s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_map" --config "$ROOT/config/scan_mapper.yaml" "$@"

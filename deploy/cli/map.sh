#!/usr/bin/env bash
# ./rgnav map <log.lcmlog> --out DIR [--config FILE] [--gateway-config FILE] [--rg-config FILE]
#             [--base-from-laser X Y THETA] [--poses-as-given] [--pixels-per-metre N]
#             [--export-resolution M] [--no-pictures] [--verbose]
# Runs scan mapper + gateway detector + RG kernel (their libraries, one thread, message time) over
# an LCM log (LASER_FRONT + ODOMETRY), deterministically and as fast as the CPU allows. Writes in
# DIR: trajectory.txt, aligned_scans.lcmlog, map.png (scan mapper), rgmap.json (RG map, the RG
# kernel's checkpoint format: ./rgnav render reads it), rgmap.svg + rgmap.png (pictures),
# rgmap_global.pgm + rgmap_global.yaml (ROS map_server export), summary.json (counts).
# Configs default to config/scan_mapper.yaml, config/gateway_detector_aligned.yaml (the detector
# on aligned scans, as in the demo) and config/rg_kernel.yaml.
# --base-from-laser: the laser mounting pose of the robot that recorded the log (default: config).
# --poses-as-given: the log's odometry is already corrected (e.g. laser/corrected): no scan matching.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,14s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_rgmap_offline" --config "$ROOT/config/scan_mapper.yaml" \
  --gateway-config "$ROOT/config/gateway_detector_aligned.yaml" --rg-config "$ROOT/config/rg_kernel.yaml" "$@"

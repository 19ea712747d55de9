#!/usr/bin/env bash
# ./rgnav import <in> <out.lcmlog> [--format auto|carmen|mines] [--reference] [--reference-from CORRECTED.log.gz]
# Converts a CARMEN log (FLASER, RLASER, ODOM, ROBOTLASER1; gzip or plain) or a Mines .dat log
# into an LCM log (LASER_FRONT, LASER_REAR, ODOMETRY, REFERENCE_POSE) with the original times.
# --reference: the log's poses are corrected (laser/corrected/): also write them as REFERENCE_POSE.
# --reference-from: reference poses for raw scans identical to the scans of a corrected log.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
if [[ $# -lt 2 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,6s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_import" "$@"

#!/usr/bin/env bash
# ./rgnav localize --region NAME|ID --pose X Y THETA_DEG | --global: tell the localizer the robot's pose, or to localize globally
# The pose is in the region's frame (x, y in metres, theta in degrees). --sigma-xy M and
# --sigma-theta DEG give its spread (default: the localizer's initial_xy_m, initial_theta_deg);
# --global forgets the pose; --lcm-url U as for every tool. The localizer's log and heartbeat
# status (./rgnav status) say what it made of the request.
set -euo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,6s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_localize" "$@"

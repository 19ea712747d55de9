#!/usr/bin/env bash
# ./rgnav goto NAME|ID [X Y THETA_DEG] [--tolerance M] [--timeout S]: send the robot to a region (or a pose in it) and follow it
# The pose is in the region's frame (x, y in metres, theta in degrees); without one the planner
# picks a roomy place near its middle. Prints progress from the planner's GLOBAL_PATH until
# the goal is reached (exit 0), cancelled (exit 3: Ctrl-C and --timeout cancel it) or has no
# path (exit 4; the goal is cancelled unless --keep-trying; behind a gateway held closed or a
# blocked place it is waited for, as the planner tries again). --no-wait returns once the planner
# has the goal; --lcm-url U as for every tool. Exit 2: bad arguments; 1: no planner answered.
set -euo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,9s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_goto" "$@"

#!/usr/bin/env bash
# ./rgnav name-region ID NAME [--map DIR]: name a region of the RG map (goals by name: ./rgnav goto NAME)
# Sends the name on REGION_NAME: the RG kernel keeps it in its map (journaled, in every picture
# and export from then on), a running planner takes goals by it at once. --map DIR (an
# rgmap.json or its folder) also writes it into that saved map, for a robot running on a saved
# map with no RG kernel (./rgnav launch nav --map DIR). A name is 1-64 printable ASCII
# characters, not only digits, and no other region's. Exit 2: refused; 1: a bus or file failure.
set -euo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,7s/^# \{0,1\}//p' "$0" >&2
  exit 2
fi
exec "$BUILD/bin/rgnav_name_region" "$@"

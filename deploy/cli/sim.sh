#!/usr/bin/env bash
# ./rgnav sim <world> [rgnav_sim flags...]: runs the simulated B21r on a world (a name under
# config/worlds/, e.g. office or hallways_2m_strongly_cluttered, or a world file: rgnav
# YAML, ROS map_server YAML, or an occupancy PNG such as the IPA maps).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  echo "usage: ./rgnav sim <world> [--config FILE] [--lcm-url URL] [...]" >&2
  echo "worlds: $(cd "$ROOT/config/worlds" && ls *.yaml | sed 's/\.yaml$//' | tr '\n' ' ')" >&2
  exit 2
fi
WORLD="$1"; shift
exec "$BUILD/bin/rgnav_sim" --config "$ROOT/config/sim.yaml" --world "$WORLD" "$@"

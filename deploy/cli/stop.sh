#!/usr/bin/env bash
# ./rgnav stop <process|group|everything> [--host H] [--wait]: stop through the deputies
set -euo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}"
host=(); rest=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --host|--lcm-url) host+=("$1" "$2"); shift ;;
    *) rest+=("$1") ;;
  esac
  shift
done
exec "$BUILD/bin/rgnav_ctl" "${host[@]}" stop "${rest[@]}"

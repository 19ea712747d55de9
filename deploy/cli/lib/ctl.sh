#!/usr/bin/env bash
# The deputies' control client for ./rgnav start|stop|restart|shutdown|status:
#   lib/ctl.sh <verb> [args...]  runs rgnav_ctl [--host H | --lcm-url U] <verb> [args...]
# (rgnav_ctl wants its host options before the verb; the user may give them anywhere).
set -euo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../../.." && pwd)/build}"
verb="$1"
shift
host=(); rest=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --host|--lcm-url) host+=("$1" "$2"); shift ;;
    *) rest+=("$1") ;;
  esac
  shift
done
exec "$BUILD/bin/rgnav_ctl" "${host[@]}" "$verb" "${rest[@]}"

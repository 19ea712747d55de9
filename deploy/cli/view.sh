#!/usr/bin/env bash
# ./rgnav view [--port N] [--address IP] [--lcm-url URL]: the live viewer beside a running stack.
# Starts procs/viewer (config/viewer.yaml: loopback, port 8036 by default) and prints the
# address to open in a browser: the RG map, the robot, its scan, plans and processes, live or
# from ./rgnav replay LOG; a click on a region sends the robot there after confirmation.
# Runs until Ctrl-C. Extra arguments go to the viewer (--config FILE, --lcm-url URL, ...).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
case "${1:-}" in
  -h|--help) sed -n '2,6s/^# \{0,1\}//p' "$0"; exit 0 ;;
esac
bin="$BUILD/bin/viewer"
[[ -x $bin ]] || { echo "view: $bin missing (./rgnav setup builds it)" >&2; exit 1; }
# The viewer prints "viewer: http://ADDRESS:PORT/" once it listens; say it plainly.
say_address() {
  local line
  while IFS= read -r line; do
    if [[ $line == "viewer: http://"* ]]; then
      echo "view: open ${line#viewer: } in a browser (Ctrl-C stops the viewer)"
    else
      echo "$line"
    fi
  done
}
"$bin" "$@" > >(say_address) &
viewer=$!
trap 'kill -TERM "$viewer" 2>/dev/null || true' INT TERM
wait "$viewer" || wait "$viewer"

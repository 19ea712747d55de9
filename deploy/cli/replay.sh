#!/usr/bin/env bash
# ./rgnav replay <log> [--speed X] [--launch CONFIG] [--skip-missing]: play a log into the algorithm stack
# Launches deploy/launch/replay.pmd (no drivers, no simulator) under its own deputy, waits
# until it runs, plays the log with the real lcm-logplayer (-s X), then stops the stack.
# <log> is an .lcmlog file or a folder from ./rgnav launch --record (files played in order).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
export RGNAV_ROOT="$ROOT" RGNAV_BUILD="$BUILD"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then sed -n '2,5s/^# \{0,1\}//p' "$0" >&2; exit 2; fi
log="$1"; shift
state_dir=""; speed=1.0; launch="$ROOT/deploy/launch/replay.pmd"; extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --speed) speed="$2"; shift ;;
    --launch) launch="$2"; shift ;;
    --state-dir) state_dir="$2"; shift ;;
    *) extra+=("$1") ;;
  esac
  shift
done
if [[ -d "$log" ]]; then mapfile -t files < <(ls -1 "$log"/*.lcmlog* | sort); else files=("$log"); fi
[[ ${#files[@]} -gt 0 && -f "${files[0]}" ]] || { echo "replay: no log at $log" >&2; exit 2; }
# A file that is no LCM log is refused here, naming it, before anything starts (lcm-logplayer
# would play nothing); a cut-off one gets a warning and is played up to the damage.
"$BUILD/bin/rgnav_log_check" "${files[@]}" >/dev/null || { echo "replay: refused (see above); nothing was started" >&2; exit 1; }
host="replay-$$"
state=${state_dir:-$(mktemp -d /tmp/rgnav-replay.XXXXXX)}
"$BUILD/bin/supervisor" --launch "$launch" --host "$host" --state-dir "$state" "${extra[@]}" &
sup=$!
cleanup() { kill -TERM "$sup" 2>/dev/null || true; wait "$sup" 2>/dev/null || true; if [[ -z "$state_dir" ]]; then rm -rf "$state"; fi; }
trap cleanup EXIT INT TERM
if ! "$BUILD/bin/rgnav_ctl" --host "$host" start everything --wait --timeout-ms 30000; then
  echo "replay: the replay stack did not come up" >&2; exit 1
fi
for f in "${files[@]}"; do
  echo "replay: playing $f at ${speed}x" >&2
  # Everything but the recorded run's own supervision traffic (its heartbeats, status and
  # orders would mix with those of the replay stack).
  lcm-logplayer -s "$speed" -e '^(?!HEARTBEAT$|SUPERVISOR_STATUS$|SUPERVISOR_ORDERS$).*$' "$f"
done
# Let the last messages work through the stack before stopping it.
sleep 1

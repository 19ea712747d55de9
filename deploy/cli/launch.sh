#!/usr/bin/env bash
# ./rgnav launch <config> [--host H] [--record [DIR]] [--split-mb N] [...]: a supervisor (procman deputy) for this host
# <config> is a launch file or a name under deploy/launch/ (sim, nav, b21r, replay). The deputy
# runs in the foreground; Ctrl-C stops every process it started. --record records the whole
# bus with lcm-logger into logs/<run>/ (or DIR), a new file every --split-mb MB (default 256).
# --map DIR (an rgmap.json or its folder) is the saved map a config like nav localizes in
# (exported as RGNAV_MAP). Other flags go to the supervisor (--skip-missing, --state-dir, ...).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
export RGNAV_ROOT="$ROOT" RGNAV_BUILD="$BUILD"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,8s/^# \{0,1\}//p' "$0" >&2
  echo "configs: $(cd "$ROOT/deploy/launch" && ls *.pmd | sed 's/\.pmd$//' | tr '\n' ' ')" >&2
  exit 2
fi
config="$1"; shift
[[ -f "$config" ]] || config="$ROOT/deploy/launch/$config.pmd"
[[ -f "$config" ]] || { echo "launch: no launch config '$1'" >&2; exit 2; }
args=()
split_mb=256
while [[ $# -gt 0 ]]; do
  case "$1" in
    --record)
      if [[ $# -gt 1 && "$2" != --* ]]; then dir="$2"; shift; else dir="$ROOT/logs/$(date +%Y%m%d-%H%M%S)"; fi
      args+=(--record "$dir"); echo "launch: recording into $dir" >&2 ;;
    --split-mb) split_mb="$2"; shift ;;
    --map)
      [[ $# -gt 1 ]] || { echo "launch: --map needs a folder or an rgmap.json" >&2; exit 2; }
      map="$2"; shift
      [[ -f "$map" || -f "$map/rgmap.json" ]] || { echo "launch: no rgmap.json at '$map'" >&2; exit 2; }
      RGNAV_MAP="$(cd "$(dirname "$map")" && pwd)/$(basename "$map")"; export RGNAV_MAP ;;
    *) args+=("$1") ;;
  esac
  shift
done
if grep -q '${RGNAV_MAP}' "$config" && [[ -z "${RGNAV_MAP:-}" ]]; then
  echo "launch: $(basename "$config" .pmd) runs on a saved map: give --map DIR (an rgmap.json or its folder)" >&2
  exit 2
fi
for a in "${args[@]}"; do [[ "$a" == --record ]] && args+=(--record-split-mb "$split_mb") && break; done
exec "$BUILD/bin/supervisor" --launch "$config" "${args[@]}"

#!/usr/bin/env bash
# ./rgnav launch <config> [--host H] [--record [DIR]] [--split-mb N] [...]: a supervisor (procman deputy) for this host
# <config> is a launch file or a name under deploy/launch/ (sim, b21r, replay). The deputy
# runs in the foreground; Ctrl-C stops every process it started. --record records the whole
# bus with lcm-logger into logs/<run>/ (or DIR), a new file every --split-mb MB (default 256).
# Other flags go to the supervisor (--skip-missing, --state-dir, --lcm-url, --config ...).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
export RGNAV_ROOT="$ROOT" RGNAV_BUILD="$BUILD"
if [[ $# -lt 1 || "$1" == -h || "$1" == --help ]]; then
  sed -n '2,7s/^# \{0,1\}//p' "$0" >&2
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
    *) args+=("$1") ;;
  esac
  shift
done
for a in "${args[@]}"; do [[ "$a" == --record ]] && args+=(--record-split-mb "$split_mb") && break; done
exec "$BUILD/bin/supervisor" --launch "$config" "${args[@]}"

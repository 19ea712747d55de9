#!/usr/bin/env bash
# ./rgnav visit NAME [NAME...] [--timeout S]: drive to each named region in turn (./rgnav goto); prints which were reached
# Each goal gets --timeout seconds (default 300) and is cancelled after it; a region with no
# path is skipped. Prints "reached K/N" last; exit 0 when every one was reached, 3 otherwise,
# 2 on bad arguments. --lcm-url U as for every tool.
set -uo pipefail
BUILD="${RGNAV_BUILD:-$(cd "$(dirname "$0")/../.." && pwd)/build}"
timeout_s=300 names=() extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --timeout) timeout_s="$2"; shift ;;
    --lcm-url) extra+=(--lcm-url "$2"); shift ;;
    -h|--help) sed -n '2,5s/^# \{0,1\}//p' "$0" >&2; exit 2 ;;
    -*) echo "visit: unknown option '$1'" >&2; exit 2 ;;
    *) names+=("$1") ;;
  esac
  shift
done
if [[ ${#names[@]} -eq 0 ]]; then sed -n '2,5s/^# \{0,1\}//p' "$0" >&2; exit 2; fi
reached=0
for n in "${names[@]}"; do
  start=$(date +%s)
  "$BUILD/bin/rgnav_goto" "$n" --timeout "$timeout_s" "${extra[@]}" >&2
  rc=$?
  case $rc in
    0) result="reached"; reached=$((reached + 1)) ;;
    3) result="not reached (cancelled or timed out)" ;;
    4) result="no path" ;;
    *) result="failed (rgnav_goto exit $rc)" ;;
  esac
  echo "visit: $n: $result in $(( $(date +%s) - start )) s"
done
echo "visit: reached $reached/${#names[@]}"
[[ $reached -eq ${#names[@]} ]] && exit 0 || exit 3

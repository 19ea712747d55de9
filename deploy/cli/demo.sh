#!/usr/bin/env bash
# ./rgnav demo [--world NAME] [--timeout S] [--keep-running]: the simulated B21r drives a tour
# through a world (default: office) under the supervisor while the mapping stack runs; the run
# is recorded with lcm-logger. Ends when the tour is done (or after --timeout seconds) and
# prints where the results are. --keep-running leaves the stack up for ./rgnav status, spy and
# manual goals until Ctrl-C.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
export RGNAV_ROOT="$ROOT" RGNAV_BUILD="$BUILD"

world=office timeout_s=900 keep=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --world) world="$2"; shift ;;
    --timeout) timeout_s="$2"; shift ;;
    --keep-running) keep=1 ;;
    -h|--help) sed -n '2,6s/^# \{0,1\}//p' "$0"; exit 0 ;;
    *) echo "demo: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done

# LCM must not leave this machine. With a multicast route, ttl=0 keeps packets on the host;
# without one (a fresh container), run in a private network namespace (needs root).
if [[ -z "${RGNAV_DEMO_INNER:-}" ]]; then
  if ip route get 239.255.76.67 >/dev/null 2>&1; then
    export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
  elif [[ "$(id -u)" -eq 0 ]] && command -v unshare >/dev/null; then
    echo "demo: no multicast route here: running in a private network namespace" >&2
    exec unshare -n env RGNAV_DEMO_INNER=1 bash -c \
      'ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec bash "$0" "$@"' \
      "$0" --world "$world" --timeout "$timeout_s" $([[ $keep -eq 1 ]] && echo --keep-running)
  else
    echo "demo: no multicast route; add one (sudo ip route add 224.0.0.0/4 dev lo) or run as root" >&2
    exit 1
  fi
fi

run="$ROOT/logs/demo-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$run"
export RGNAV_RUN="$run" RGNAV_TOUR="$run/tour.yaml"
echo "demo: planning a tour through '$world'" >&2
# Waypoints keep 0.15 m beyond the robot radius: collision avoidance keeps 0.10 m (more from
# what may be moving), and a tour hugging corners and door leaves at the planner's default
# 0.08 m puts targets where collision avoidance must refuse them.
"$BUILD/bin/sim_tour" "$world" --worlds-dir "$ROOT/config/worlds" --sim-config "$ROOT/config/sim.yaml" \
  --margin 0.15 --out "$RGNAV_TOUR" >&2

ctl() { "$BUILD/bin/rgnav_ctl" "$@"; }
"$BUILD/bin/supervisor" --launch "$ROOT/deploy/launch/demo.pmd" --host demo --state-dir "$run/supervisor" \
  --record "$run/lcm" >"$run/supervisor.log" 2>&1 &
sup=$!
cleanup() {
  ctl shutdown --wait --timeout-ms 15000 >/dev/null 2>&1 || true
  kill -TERM "$sup" 2>/dev/null || true
  wait "$sup" 2>/dev/null || true
}
trap cleanup EXIT INT TERM

echo "demo: stack launched (log: $run/supervisor.log); driving the tour ..." >&2
start=$(date +%s)
state=""
while :; do
  sleep 5
  if ! kill -0 "$sup" 2>/dev/null; then echo "demo: the supervisor stopped; see $run/supervisor.log" >&2; exit 1; fi
  table=$(ctl status --once 2>/dev/null || true)
  line=$(grep -E '^ +tour_runner ' <<<"$table" || true)
  state=$(grep -oE '\b(stopped|starting|running|HUNG|backoff|FAILED|stopping)\b' <<<"$line" | head -1 || true)
  reached=$(grep -o 'target [0-9]*/[0-9]*' "$run/supervisor.log" 2>/dev/null | tail -1 || true)
  printf 'demo: %4ds  tour_runner %-8s %s\n' "$(( $(date +%s) - start ))" "${state:-?}" "$reached" >&2
  if [[ "$state" == stopped || "$state" == FAILED ]]; then break; fi
  if (( $(date +%s) - start > timeout_s )); then echo "demo: timeout after ${timeout_s}s" >&2; break; fi
done
grep -q "tour complete" "$run/supervisor.log" && result="tour complete" || result="tour NOT complete"
ctl status --once > "$run/status.txt" 2>&1 || true

if [[ $keep -eq 1 ]]; then
  echo "demo: $result; stack kept running (./rgnav status, ./rgnav spy). Ctrl-C to stop." >&2
  wait "$sup" || true
fi
cleanup
trap - EXIT INT TERM

if [[ -f "$run/rg_kernel/rgmap.json" ]]; then
  "$BUILD/bin/rgnav_render" "$run/rg_kernel/rgmap.json" --out "$run/rgmap.png" --out "$run/rgmap.svg" \
    --export-pgm "$run/global_map" >/dev/null
fi
echo
echo "demo: $result"
echo "  run folder:     $run"
echo "  LCM log:        $(ls "$run"/lcm/* 2>/dev/null | head -1 || echo none)  (replay: ./rgnav replay $run/lcm)"
echo "  RG map:         $( [[ -f $run/rgmap.png ]] && echo "$run/rg_kernel/rgmap.json, $run/rgmap.png, $run/rgmap.svg" || echo 'none (no map written)')"
echo "  process status: $run/status.txt"
[[ "$result" == "tour complete" ]]

#!/usr/bin/env bash
# ./rgnav demo [--world NAME] [--timeout S] [--rooms N] [--keep-running]: the simulated B21r
# explores a world it has no map of (default: office) under the supervisor: region by region,
# asking for each finished region's name (a scripted operator answers with the world's room
# names), then drives to N named rooms (default 5) with ./rgnav goto and prints a summary with
# the RG map picture. The run is recorded with lcm-logger. Ends by itself (exploration gives up
# after --timeout seconds, default 2400); --keep-running leaves the stack up for ./rgnav goto,
# visit, status and spy until Ctrl-C.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
export RGNAV_ROOT="$ROOT" RGNAV_BUILD="$BUILD"

args=("$@")
world=office timeout_s=2400 rooms=5 keep=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --world) world="$2"; shift ;;
    --timeout) timeout_s="$2"; shift ;;
    --rooms) rooms="$2"; shift ;;
    --keep-running) keep=1 ;;
    -h|--help) sed -n '2,8s/^# \{0,1\}//p' "$0"; exit 0 ;;
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
      "$0" "${args[@]}"
  else
    echo "demo: no multicast route; add one (sudo ip route add 224.0.0.0/4 dev lo) or run as root" >&2
    exit 1
  fi
fi

run="$ROOT/logs/demo-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$run"
export RGNAV_RUN="$run" RGNAV_WORLD="$world"
op="$run/operator.json"

# A field of the scripted operator's record (operator.json), or "" while there is none.
field() {
  python3 - "$op" "$1" <<'PY' 2>/dev/null || true
import json, sys
try:
    j = json.load(open(sys.argv[1]))
except Exception:
    sys.exit(0)
for k in sys.argv[2].split("."):
    j = j.get(k, "") if isinstance(j, dict) else ""
print(j)
PY
}

ctl() { "$BUILD/bin/rgnav_ctl" "$@"; }
"$BUILD/bin/supervisor" --launch "$ROOT/deploy/launch/demo.pmd" --host demo --state-dir "$run/supervisor" \
  --record "$run/lcm" >"$run/supervisor.log" 2>&1 &
sup=$!
stopped=0
cleanup() {
  [[ $stopped -eq 1 ]] && return
  stopped=1
  ctl status --once > "$run/status.txt" 2>&1 || true
  ctl shutdown --wait --timeout-ms 15000 >/dev/null 2>&1 || true
  kill -TERM "$sup" 2>/dev/null || true
  wait "$sup" 2>/dev/null || true
}
trap cleanup EXIT INT TERM

echo "demo: stack launched on '$world' with no map (log: $run/supervisor.log); exploring ..." >&2
viewer_port=$(awk '/^http:/ {h = 1} h && /^  port:/ {print $2; exit}' "$ROOT/config/viewer.yaml")
echo "demo: live view: open http://127.0.0.1:${viewer_port:-8036}/ in a browser${RGNAV_DEMO_INNER:+ (inside the private network namespace of the demo)}" >&2
start=$(date +%s)
phase=""
while :; do
  sleep 5
  if ! kill -0 "$sup" 2>/dev/null; then echo "demo: the supervisor stopped; see $run/supervisor.log" >&2; exit 1; fi
  line=$(python3 - "$op" <<'PY' 2>/dev/null || echo "starting"
import json, sys
j = json.load(open(sys.argv[1]))
e = j.get("explorer", {})
print(f"{e.get('phase', 'starting'):<9} regions {e.get('regions', 0)} ({e.get('complete_regions', 0)} complete)  "
      f"gateways: {e.get('stack_pending', 0)} to go, {e.get('stack_done', 0)} done, {e.get('stack_set_aside', 0)} set aside  "
      f"goals {e.get('goals_reached', 0)}/{e.get('goals_sent', 0)}  named {len(j.get('names', []))}  {j.get('distance_m', 0):.0f} m")
PY
)
  phase=${line%% *}
  printf 'demo: %5ds  %s\n' "$(( $(date +%s) - start ))" "$line" >&2
  [[ "$phase" == done ]] && break
  if (( $(date +%s) - start > timeout_s )); then echo "demo: exploration not done after ${timeout_s}s" >&2; break; fi
done
explore_s=$(( $(date +%s) - start ))
[[ "$phase" == done ]] && explored="explored" || explored="exploration NOT finished"
# An explorer still exploring would replace the visits' goals with its own (the planner drives to
# one NAV_GOAL at a time, the newest): it stops here (`./rgnav start explorer` resumes it from its
# state file).
if [[ "$phase" != done ]]; then ctl stop explorer --wait --timeout-ms 10000 >/dev/null 2>&1 || echo "demo: could not stop the explorer" >&2; fi

# The explorer asks for every unnamed region once it is done: give the operator a moment.
sleep 8
# Rooms to visit: named after a ground-truth room (not a hallway, not a second piece of one).
mapfile -t targets < <(python3 - "$op" "$rooms" <<'PY' 2>/dev/null || true
import json, sys
names = json.load(open(sys.argv[1]))["names"]
n = int(sys.argv[2])
rooms = [x["name"] for x in names if x["kind"] == "room" and x["name"] == x["room"]]
rest = [x["name"] for x in names if x["name"] not in rooms]
for name in (rooms + rest)[:n]:
    print(name)
PY
)
reached=0
if [[ ${#targets[@]} -gt 0 ]]; then
  echo "demo: $explored; visiting ${targets[*]}" >&2
  bash "$ROOT/deploy/cli/visit.sh" "${targets[@]}" --timeout 300 | tee "$run/visit.txt" >&2 || true
  reached=$(grep -c ': reached in' "$run/visit.txt" || true)
else
  echo "demo: $explored; no named rooms to visit" >&2
fi
total_s=$(( $(date +%s) - start ))

if [[ $keep -eq 1 ]]; then
  echo "demo: stack kept running (./rgnav goto NAME, ./rgnav visit A B C, ./rgnav status, ./rgnav spy). Ctrl-C to stop." >&2
  wait "$sup" || true
fi
cleanup
trap - EXIT INT TERM

if [[ -f "$run/rg_kernel/rgmap.json" ]]; then
  "$BUILD/bin/rgnav_render" "$run/rg_kernel/rgmap.json" --out "$run/rgmap.png" --out "$run/rgmap.svg" \
    --export-pgm "$run/global_map" >/dev/null 2>&1 || true
fi
map_counts=$(python3 - "$run/rg_kernel/rgmap.json" <<'PY' 2>/dev/null || echo "? regions, ? gateways"
import json, sys
text = open(sys.argv[1]).read()
m = json.loads(text)
regions = [r for r in m["regions"] if r["state"] != 3]
gateways = [g for g in m["gateways"] if not g["neutralized"] and g["region_b"]]
named = [r for r in regions if r.get("name")]
print(f"{len(regions)} regions ({len(named)} named), {len(gateways)} gateways")
PY
)
restarts=$(awk '$1 != "NAME" && $1 != "host" && NF >= 6 && $5 ~ /^[0-9]+$/ {s += $5} END {print s + 0}' "$run/status.txt" 2>/dev/null || echo "?")
echo
echo "demo: $explored in ${explore_s} s; rooms reached ${reached}/${#targets[@]}"
echo "  RG map:          $map_counts"
echo "  explorer:        $(field explorer.goals_sent) goals ($(field explorer.goals_reached) reached, $(field explorer.goals_failed) failed), gateways gone through $(field explorer.stack_done), set aside $(field explorer.stack_set_aside)"
echo "  driven:          $(printf '%.0f' "$(field distance_m || echo 0)") m in $(printf '%.0f' "$(field sim_time_s || echo 0)") s simulated ($total_s s in all); path: $run/path.csv"
echo "  restarts:        $restarts (process table: $run/status.txt)"
echo "  RG map picture:  $( [[ -f $run/rgmap.png ]] && echo "$run/rgmap.png, $run/rgmap.svg" || echo 'none (no map written)')"
echo "  run folder:      $run (LCM log: ./rgnav replay $run/lcm)"
[[ "$explored" == explored && $reached -eq ${#targets[@]} && ${#targets[@]} -gt 0 ]]

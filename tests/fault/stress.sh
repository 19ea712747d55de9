#!/usr/bin/env bash
# The `stress` section of ./rgnav bench faults: the demo's stack (deploy/launch/demo.pmd, the
# simulated robot exploring a world it has no map of) with stress-ng loading both cores and
# the disk. Run inside a private network namespace (tests/fault/run_in_netns.sh).
#   soak:   --soak-s seconds with no fault injected. Every restart is a false one; every
#           "controlled stop" of the low-level drive for stale input and every stop of the
#           base for a lost drive heartbeat is a stall-caused stop; collisions are the
#           simulator's. The supervisor's host-stall count is reported beside them.
#   hangs:  then, still under load, each process in turn is stopped with SIGSTOP and the time
#           from the signal to the supervisor's "is hung" is measured (it restarts the
#           process; the next one waits until everything runs again).
# Writes {"stress": {...}} into --out (merged into an existing JSON object).
# Usage: stress.sh --out FILE [--soak-s 300] [--world office] [--load "--cpu 2 --hdd 1"]
set -uo pipefail
root=${RGNAV_ROOT:?} build=${RGNAV_BUILD:?}
out="" soak_s=300 world=office load="--cpu 2 --hdd 1"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out=$2; shift ;;
    --soak-s) soak_s=$2; shift ;;
    --world) world=$2; shift ;;
    --load) load=$2; shift ;;
    *) echo "stress: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
[[ -n "$out" ]] || { echo "stress: --out FILE is required" >&2; exit 2; }
command -v stress-ng >/dev/null || { echo "stress: stress-ng is not installed (deploy/debian-packages-bench.txt)" >&2; exit 2; }

run=$(mktemp -d /tmp/rgnav-stress.XXXXXX)
export RGNAV_RUN=$run RGNAV_WORLD=$world
log=$run/supervisor.log
"$build/bin/supervisor" --launch "$root/deploy/launch/demo.pmd" --host demo --state-dir "$run/supervisor" >"$log" 2>&1 &
sup=$!
stress_pid=""
finish() {
  [[ -n "$stress_pid" ]] && kill -TERM "$stress_pid" 2>/dev/null && wait "$stress_pid" 2>/dev/null
  kill -TERM "$sup" 2>/dev/null
  for _ in $(seq 100); do kill -0 "$sup" 2>/dev/null || break; sleep 0.2; done
  kill -KILL "$sup" 2>/dev/null
}
trap finish EXIT

status() { "$build/bin/rgnav_ctl" status --once 2>/dev/null; }
# "NAME PID" of every running process of the launch.
running() { status | awk '$3 == "running" && $4 ~ /^[0-9]+$/ && $4 > 0 {print $1, $4}'; }
all_running() {  # every command of the launch (but the recorder) running
  local n
  n=$(status | awk '$1 != "NAME" && $1 != "host" && $1 != "alert:" && NF >= 5 && $3 != "running" && $1 != "lcm_logger"' | wc -l)
  [[ $n -eq 0 && $(running | wc -l) -ge 10 ]]
}
wait_all_running() {  # wait_all_running SECONDS
  for _ in $(seq $(( $1 * 2 ))); do all_running && return 0; sleep 0.5; done
  return 1
}

if ! wait_all_running 60; then
  echo "stress: the demo stack did not come up; see $log" >&2
  cp "$log" "$root/logs/bench/faults-stress.log" 2>/dev/null
  exit 1
fi
# shellcheck disable=SC2086
stress-ng $load --timeout $(( soak_s + 600 ))s --quiet >/dev/null 2>&1 &
stress_pid=$!
echo "stress: soaking the demo stack for ${soak_s} s under stress-ng $load" >&2
soak_from=$(wc -l <"$log")
sleep "$soak_s"
tail -n +"$soak_from" "$log" >"$run/soak.log"
restarts=$(status | awk '$1 != "NAME" && $1 != "host" && NF >= 6 && $5 ~ /^[0-9]+$/ {s += $5} END {print s + 0}')

# Hang detection under the same load: SIGSTOP each process, time to "is hung".
declare -A detect_ms
for entry in $(running | tr ' ' ':'); do
  name=${entry%%:*} pid=${entry##*:}
  [[ "$name" == lcm_logger ]] && continue
  wait_all_running 60 || true
  pid=$(running | awk -v n="$name" '$1 == n {print $2}')
  [[ -n "$pid" ]] || continue
  t0=$(date +%s.%N)
  kill -STOP "$pid"
  hit=""
  for _ in $(seq 100); do
    hit=$(grep -m1 "\[supervisor\] $name (pid $pid) is hung" "$log" | cut -d' ' -f1)
    [[ -n "$hit" ]] && break
    sleep 0.1
  done
  kill -CONT "$pid" 2>/dev/null
  if [[ -z "$hit" ]]; then detect_ms[$name]=null; continue; fi
  # The log's clock is HH:MM:SS.mmm of today; t0 the same clock in seconds of the day.
  detect_ms[$name]=$(python3 -c '
import sys, datetime
t0 = float(sys.argv[1]); h, m, s = sys.argv[2].split(":")
d = datetime.datetime.fromtimestamp(t0)
day = d.replace(hour=0, minute=0, second=0, microsecond=0).timestamp()
print(round((day + int(h) * 3600 + int(m) * 60 + float(s) - t0) * 1000.0, 1))' "$t0" "$hit")
done
cp "$log" "$root/logs/bench/faults-stress.log" 2>/dev/null

detect_json=$(for k in "${!detect_ms[@]}"; do printf '%s %s\n' "$k" "${detect_ms[$k]}"; done)
python3 - "$out" "$soak_s" "$load" "$restarts" "$run/soak.log" "$detect_json" <<'PY'
import json, os, re, sys
out, soak_s, load, restarts, soak_log, detect = sys.argv[1:]

def seconds(stamp):  # HH:MM:SS.mmm
    h, m, s = stamp.split(":")
    return int(h) * 3600 + int(m) * 60 + float(s)

def events(lines, gap_s=2.0):
    """Lines within gap_s of the one before are one event (a stop logs a line per drive and state)."""
    n, last = 0, None
    for line in lines:
        t = seconds(line.split()[0])
        if last is None or t - last > gap_s:
            n += 1
        last = t
    return n

lines = [l for l in open(soak_log, errors="replace") if re.match(r"\d\d:\d\d:\d\d\.\d+ ", l)]
grep = lambda pattern: [l for l in lines if re.search(pattern, l)]
stalls = [int(m.group(1)) for l in lines for m in [re.search(r"host stalled for (\d+) ms", l)] if m]
per = {}
for line in detect.splitlines():
    name, v = line.split()
    per[name] = None if v == "null" else float(v)
measured = [v for v in per.values() if v is not None]
doc = {}
if os.path.exists(out):
    try:
        doc = json.load(open(out))
    except ValueError:
        doc = {}
doc["stress"] = {
    "load": "stress-ng " + load,
    "soak_s": int(soak_s),
    "false_restarts": int(restarts),
    "hung_reports": [l.split("] ", 1)[1].strip() for l in grep(r"\[supervisor\] .* is hung: ")],
    "stall_stops": events(grep(r"\[base_driver\] base stopped by a fault")) + events(grep(r"\[lld\] controlled stop: stale")),
    "base_fault_stops": events(grep(r"\[base_driver\] base stopped by a fault")),
    "lld_stale_stops": events(grep(r"\[lld\] controlled stop: stale")),
    "collisions": events(grep(r"\] collision with")),
    "disk_waits": len(grep(r"waiting on the disk")),
    "host_stalls": len(stalls),
    "host_stall_max_ms": max(stalls, default=0),
    "hang_detect_ms_max": max(measured) if measured and len(measured) == len(per) else None,
    "hang_detect_ms": per,
    "hangs_missed": sorted(k for k, v in per.items() if v is None),
}
json.dump(doc, open(out, "w"), indent=2)
s = doc["stress"]
print(f"stress: {s['false_restarts']} false restarts, {s['stall_stops']} stall stops, {s['collisions']} collisions in "
      f"{soak_s} s; hangs detected in <= {s['hang_detect_ms_max']} ms ({len(per)} processes, missed: {s['hangs_missed']})",
      file=sys.stderr)
PY

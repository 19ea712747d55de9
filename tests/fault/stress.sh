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
#           process; the next one waits until everything runs again). Every command of the
#           launch is probed: one not running when its turn comes is named and counted as a
#           failed probe (tests/fault/stress_probes.sh).
# Writes {"stress": {...}} into --out (merged into an existing JSON object, by
# tests/fault/stress_summary.py); exits 1 when a hang probe failed.
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

ctl_status() { "$build/bin/rgnav_ctl" status --once 2>/dev/null; }
# shellcheck source=tests/fault/stress_probes.sh
source "$root/tests/fault/stress_probes.sh"

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
table=$(status) || table=""
if [[ -n "$table" ]]; then
  restarts=$(awk '$1 != "NAME" && $1 != "host" && NF >= 6 && $5 ~ /^[0-9]+$/ {s += $5} END {print s + 0}' <<<"$table")
else
  echo "stress: no supervisor status after the soak: false restarts unknown" >&2
  restarts=null
fi

# Hang detection under the same load: SIGSTOP each process, time to "is hung".
probe_hangs "$root/deploy/launch/demo.pmd" "$log" "$run/probes.txt"
cp "$log" "$root/logs/bench/faults-stress.log" 2>/dev/null
python3 "$root/tests/fault/stress_summary.py" "$out" "$soak_s" "$load" "$restarts" "$run/soak.log" "$run/probes.txt"

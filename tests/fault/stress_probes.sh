# shellcheck shell=bash
# The hang probes of the stress section (tests/fault/stress.sh), sourced by it and by
# stress_probes_test.sh. Every command of the launch config is probed in turn: stopped with
# SIGSTOP, the time from the signal to the supervisor's "is hung" measured. A command that is not
# running when its turn comes is not passed over: it is reported and counted as a failed probe
# (a probe that never ran must not read as a hang detected in time).
#
# The caller defines ctl_status (prints the supervisors' status table, rgnav_ctl status --once;
# non-zero when no deputy answered) and may set probe_wait_s (how long to wait for the whole
# launch to run again before a probe, default 60) and probe_poll_n (tenths of a second to wait
# for "is hung", default 100).

# The status table; a call under load may hear no deputy in its listening time: asked again.
status() {
  local s
  for _ in 1 2 3; do
    s=$(ctl_status) && [[ -n "$s" ]] && { printf '%s\n' "$s"; return 0; }
  done
  return 1
}
# "NAME PID" of every running process of the launch.
running() { status | awk '$3 == "running" && $4 ~ /^[0-9]+$/ && $4 > 0 {print $1, $4}'; }
all_running() {  # every command of the launch (but the recorder) running
  local table n
  table=$(status) || return 1
  n=$(awk '$1 != "NAME" && $1 != "host" && $1 != "alert:" && NF >= 5 && $3 != "running" && $1 != "lcm_logger"' <<<"$table" | wc -l)
  [[ $n -eq 0 && $(awk '$3 == "running" && $4 ~ /^[0-9]+$/ && $4 > 0' <<<"$table" | wc -l) -ge 10 ]]
}
wait_all_running() {  # wait_all_running SECONDS
  for _ in $(seq $(( $1 * 2 ))); do all_running && return 0; sleep 0.5; done
  return 1
}
# Every command the launch config names (the recorder is no process under test).
launch_commands() { sed -n 's/^[[:space:]]*cmd[[:space:]]*"\([^"]*\)".*/\1/p' "$1" | grep -vx lcm_logger; }
# The state the status table gives NAME ("no status" when no deputy answered or it is missing).
state_of() { status | awk -v n="$1" '$1 == n {print $3; found = 1} END {if (!found) print "no status"}' | head -n 1; }

# probe_hangs LAUNCH SUPERVISOR_LOG RESULT_FILE: one line per command into RESULT_FILE,
# "NAME MS" (detected after MS), "NAME missed" (stopped, never reported hung) or
# "NAME not_running:STATE" (never stopped: it was not running when its turn came).
probe_hangs() {
  local launch=$1 log=$2 result=$3 name pid t0 hit state
  : >"$result"
  for name in $(launch_commands "$launch"); do
    wait_all_running "${probe_wait_s:-60}" || true
    pid=$(running | awk -v n="$name" '$1 == n {print $2}')
    if [[ -z "$pid" ]]; then
      state=$(state_of "$name")
      echo "stress: $name is not running ($state) when its hang probe is due: counted as a failed probe" >&2
      echo "$name not_running:${state// /_}" >>"$result"
      continue
    fi
    t0=$(date +%s.%N)
    kill -STOP "$pid"
    hit=""
    for _ in $(seq "${probe_poll_n:-100}"); do
      hit=$(grep -m1 "\[supervisor\] $name (pid $pid) is hung" "$log" | cut -d' ' -f1)
      [[ -n "$hit" ]] && break
      sleep 0.1
    done
    kill -CONT "$pid" 2>/dev/null
    if [[ -z "$hit" ]]; then
      echo "stress: $name (pid $pid) stopped but never reported hung" >&2
      echo "$name missed" >>"$result"
      continue
    fi
    # The log's clock is HH:MM:SS.mmm of today; t0 the same clock in seconds of the day.
    echo "$name $(python3 -c '
import sys, datetime
t0 = float(sys.argv[1]); h, m, s = sys.argv[2].split(":")
d = datetime.datetime.fromtimestamp(t0)
day = d.replace(hour=0, minute=0, second=0, microsecond=0).timestamp()
print(round((day + int(h) * 3600 + int(m) * 60 + float(s) - t0) * 1000.0, 1))' "$t0" "$hit")" >>"$result"
  done
}

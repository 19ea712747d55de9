#!/usr/bin/env bash
# The stress section's hang probes (stress_probes.sh, stress_summary.py) on a made-up status
# table: "alpha" runs (a sleeping child stands in for it; the supervisor's log already reports it
# hung once it is stopped, as the supervisor would) and "beta" is in back-off when its probe is due. beta must be named, counted as a failed
# probe, and leave the section without a worst detection time and with a non-zero exit; alpha's
# probe still measured.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
dir=$(mktemp -d /tmp/rgnav-stress-probes-test.XXXXXX)
sleep 60 &
alpha_pid=$!
trap 'kill -CONT "$alpha_pid" 2>/dev/null; kill "$alpha_pid" 2>/dev/null; rm -rf "$dir"' EXIT

cat >"$dir/demo.pmd" <<'EOF'
group "g" {
    cmd "alpha" {
        exec = "alpha";
    }
    cmd "beta" {
        exec = "beta";
    }
}
EOF
ctl_status() {
  printf 'host demo  (demo.pmd, status 0.1 s old)\n'
  printf '  %-20s %-16s %-9s %7s %4s %8s %6s %8s  %s\n' NAME GROUP STATE PID RST HB_AGE CPU% RSS_MB "LAST EXIT"
  printf '  %-20s %-16s %-9s %7d %4d %8s %6.1f %8.1f  %s\n' alpha g running "$alpha_pid" 0 100ms 1.0 1.0 ""
  printf '  %-20s %-16s %-9s %7d %4d %8s %6.1f %8.1f  %s\n' beta g backoff 0 1 - 0.0 0.0 "signal 9 (Killed)"
}
: >"$dir/supervisor.log"
(while kill -0 "$alpha_pid" 2>/dev/null; do
   if [[ "$(ps -o state= -p "$alpha_pid")" == T* ]]; then
     echo "$(date +%H:%M:%S.%3N) W [supervisor] alpha (pid $alpha_pid) is hung: heartbeat timeout; stopping it" >>"$dir/supervisor.log"
     break
   fi
   sleep 0.05
 done) &
: >"$dir/soak.log"
export probe_wait_s=1 probe_poll_n=5  # read by stress_probes.sh
# shellcheck source=stress_probes.sh
source "$here/stress_probes.sh"

probe_hangs "$dir/demo.pmd" "$dir/supervisor.log" "$dir/probes.txt"
python3 "$here/stress_summary.py" "$dir/out.json" 300 "--cpu 2" 0 "$dir/soak.log" "$dir/probes.txt"
summary_rc=$?
python3 - "$dir/out.json" "$summary_rc" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["stress"]
rc = int(sys.argv[2])
problems = []
if "beta" not in s["hangs_not_probed"]:
    problems.append(f"beta, in back-off when due, is not listed as not probed: {s['hangs_not_probed']}")
if s["hang_probes_failed"] != 1:
    problems.append(f"hang_probes_failed is {s['hang_probes_failed']}, expected 1 (beta)")
if s["hang_detect_ms_max"] is not None:
    problems.append(f"a worst detection time ({s['hang_detect_ms_max']} ms) although beta was never probed")
if not isinstance(s["hang_detect_ms"].get("alpha"), float):
    problems.append(f"alpha's probe not measured: {s['hang_detect_ms']}")
if s["hang_probes"] != 2:
    problems.append(f"{s['hang_probes']} probes reported, the launch has 2 commands")
if rc == 0:
    problems.append("the summary exits 0 with a failed probe")
for p in problems:
    print("FAIL:", p)
print("stress probes:", "FAIL" if problems else "ok", json.dumps(s["hang_detect_ms"]), json.dumps(s["hangs_not_probed"]))
sys.exit(1 if problems else 0)
PY

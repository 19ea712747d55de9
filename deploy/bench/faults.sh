#!/usr/bin/env bash
# ./rgnav bench faults — fault injection over every process of a launch config (SIGKILL,
# SIGSTOP past the heartbeat timeout, crash loop, input flood, malformed inputs, input
# loss/duplication/delay through lcm_relay) and the supervisor itself killed and restarted.
# Two stacks, each in a private network namespace, with the supervisor's real config
# (config/supervisor.yaml):
#   tests/fault/fault_stack.pmd  the harness's own probes (checks the supervisor itself)
#   tests/fault/sim_stack.pmd    the real processes: deploy/launch/sim.pmd's simulated robot
#                                plus the CAN drive chain, relays in front of their inputs
# Stateful processes must come back with their state (RG_MAP, the scan mapper's checkpoint,
# the planner's goal, the explorer's gateway stack); the localizer and the planner run on a
# saved map (the two-room map of their tests) and are restarted on it;
# drive-chain faults must bring commanded and measured velocity to zero. A process not built
# yet is `pending`. Writes logs/bench/faults.json: one row per (process, fault).
set -uo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
export RGNAV_ROOT=$root RGNAV_BUILD=$build
out=$root/logs/bench/faults.json
mkdir -p "$root/logs/bench"
rm -f "$out"
state=$(mktemp -d /tmp/rgnav-faults.XXXXXX)
rc=0
run() {  # run NAME LAUNCH [--prepare SCRIPT] [harness args...]
  local name=$1 launch=$2; shift 2
  local prep=()
  if [[ "${1:-}" == --prepare ]]; then prep=(--prepare "$2"); shift 2; fi
  echo "faults: $launch" >&2
  bash "$root/tests/fault/run_in_netns.sh" "$state/$name" "${prep[@]}" "$build/bin/fault_harness" \
    --launch "$root/$launch" --supervisor "$build/bin/supervisor" \
    --supervisor-config "$root/config/supervisor.yaml" \
    --state-dir "$state/$name" --log "$root/logs/bench/faults-$name.log" \
    --restart-bound-ms 3000 --out "$out" --append "$@" || rc=1
}
run fault_stack tests/fault/fault_stack.pmd
# The relays, the tour planning job and the planner's goal job are instruments of the test, not
# processes under test.
run sim_stack tests/fault/sim_stack.pmd --prepare "$root/tests/fault/sim_stack_configs.sh" \
  --process rgnav_sim --process tour_runner --process vcan_broker --process drive_emulator \
  --process base_driver --process scan_mapper --process rg_kernel --process localizer --process planner --process explorer
rm -rf "$state"
echo "wrote $out (supervisor logs: logs/bench/faults-*.log)" >&2
exit $rc

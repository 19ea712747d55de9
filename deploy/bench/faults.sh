#!/usr/bin/env bash
# ./rgnav bench faults — fault injection over every process of a launch config (SIGKILL,
# SIGSTOP past the heartbeat timeout, a busy loop of its event loop past the work timeout, crash
# loop, input flood, malformed inputs, input loss/duplication/delay through lcm_relay) and the
# supervisor itself killed and restarted.
# Three stacks, each in a private network namespace, with the supervisor's real config
# (config/supervisor.yaml):
#   tests/fault/fault_stack.pmd  the harness's own probes (checks the supervisor itself)
#   tests/fault/sim_stack.pmd    the real processes: deploy/launch/sim.pmd's simulated robot
#                                plus the CAN drive chain, relays in front of their inputs
#   tests/fault/drive_stack.pmd  the demo's drive chain driving (protocol mode: targets ->
#                                collision_avoidance -> lld -> base_driver -> emulated drives),
#                                laser_driver, gateway_detector, stereo_capture, sim_operator
#   tests/fault/vision_stack.pmd the vision and the viewer on the simulated head
# Stateful processes must come back with their state (RG_MAP, the scan mapper's checkpoint,
# the planner's goal, the explorer's gateway stack); the localizer and the planner run on a
# saved map (the two-room map of their tests) and are restarted on it;
# drive-chain faults must bring commanded and measured velocity to zero (measured while the
# robot drives, where the stack drives: braking begun within 200 ms of the fault, at rest within
# 200 ms plus the braking time at the chain's slowest stop deceleration). A process not built
# yet is `pending`. Then the stress section (tests/fault/stress.sh; RGNAV_STRESS_SOAK_S, default
# 300; every demo process gets a hang probe, one not running when it is due is a failed probe).
# Writes logs/bench/faults.json: one row per (process, fault), and "stress". One row alone:
#   RGNAV_ROOT=$PWD RGNAV_BUILD=$PWD/build tests/fault/run_in_netns.sh DIR --prepare \
#     tests/fault/sim_stack_configs.sh build/bin/fault_harness --launch $PWD/tests/fault/sim_stack.pmd \
#     --supervisor build/bin/supervisor --supervisor-config config/supervisor.yaml --state-dir DIR \
#     --log F.log --out F.json --no-supervisor-fault --process scan_mapper --fault busy_loop
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
# The demo's drive chain in protocol mode (the drives emulated inside the simulator, the robot
# driving the office tour through collision avoidance and the lld) and the demo processes the
# stack above does not run; drive-chain faults are measured on the simulator's true motion.
# Twice: hangs first (and host stalls of 60 and 100 ms while driving), then bad input on a fresh
# stack, so a bad input that leaves the robot stopped fails its own row, not every later one.
drive_procs=(--process base_driver --process lld --process collision_avoidance --process laser_driver
  --process gateway_detector --process stereo_capture --process sim_operator)
run drive_stack tests/fault/drive_stack.pmd --prepare "$root/tests/fault/drive_stack_configs.sh" --no-supervisor-fault \
  "${drive_procs[@]}" --fault sigkill --fault sigstop --fault busy_loop --fault crash_loop --host-stall-ms 60 --host-stall-ms 100
run drive_stack_inputs tests/fault/drive_stack.pmd --prepare "$root/tests/fault/drive_stack_configs.sh" --no-supervisor-fault \
  "${drive_procs[@]}" --fault flood --fault malformed --fault loss_dup_delay
# The vision and the viewer on the simulated head (the robot driving the office tour on the tour
# runner's follower), their inputs behind relays; the flood paced at 60 Hz per input, as stereo
# pairs are ~100 kB each.
run vision_stack tests/fault/vision_stack.pmd --prepare "$root/tests/fault/vision_stack_configs.sh" --no-supervisor-fault \
  --process vision --process viewer --flood 600 --flood-rate 60
# The demo's stack under stress-ng (both cores and the disk): false restarts, stall-caused stops,
# collisions, and the time to detect a SIGSTOP of each process under that load.
echo "faults: stress (demo stack, ${RGNAV_STRESS_SOAK_S:-300} s soak)" >&2
bash "$root/tests/fault/run_in_netns.sh" "$state/stress" bash "$root/tests/fault/stress.sh" --out "$out" \
  --soak-s "${RGNAV_STRESS_SOAK_S:-300}" || rc=1
rm -rf "$state"
echo "wrote $out (supervisor logs: logs/bench/faults-*.log)" >&2
exit $rc

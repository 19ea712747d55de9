#!/usr/bin/env bash
# Simulator benchmark: ray casting (181-beam scans per second, office world, one core) and
# the whole simulator in lock-step at 75 Hz (simulated seconds per wall second).
# Writes logs/bench/sim.json.
# The benchmark itself: tests/eval/sim (sim_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
bench_binary sim_bench sim "ninja -C $BUILD sim_bench"
mkdir -p "$ROOT/logs/bench"
# One core: the figure is per core, and other work on the machine should not inflate it.
exec taskset -c 0 "$bin" --world "$ROOT/config/worlds/office.yaml" --seconds "${SIM_BENCH_SECONDS:-3}" \
  --out "$ROOT/logs/bench/sim.json"

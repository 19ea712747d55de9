#!/usr/bin/env bash
# Simulator benchmark: ray casting (181-beam scans per second, office world, one core) and
# the whole simulator in lock-step at 75 Hz (simulated seconds per wall second).
# Writes logs/bench/sim.json.
# The benchmark itself: tests/eval/sim (sim_bench).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
BIN="$BUILD/bin/sim_bench"
[[ -x "$BIN" ]] || { echo "sim.sh: $BIN not built (ninja -C $BUILD sim_bench)" >&2; exit 1; }
mkdir -p "$ROOT/logs/bench"
# One core: the figure is per core, and other work on the machine should not inflate it.
exec taskset -c 0 "$BIN" --world "$ROOT/config/worlds/office.yaml" --seconds "${SIM_BENCH_SECONDS:-3}" \
  --out "$ROOT/logs/bench/sim.json"

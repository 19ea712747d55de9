#!/usr/bin/env bash
# ./rgnav bench gateways [--repetitions N] [--only WORLD ...] [--skip-doors]
# Gateway detection on the simulated worlds: per hallway environment and class the
# recognition rate of SOC-last, SOC-last-but-one, ASC and HMM (even runs train, odd runs
# test) next to dissertation tables 4.2/4.3; door precision/recall on the office world with
# the laser alone; time per scan. Writes logs/bench/gateways.json.
# The benchmark itself: tests/eval/gateways (gateway_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
bench_binary gateway_bench gateways "it needs drivers/sim; run ./rgnav build"
mkdir -p "$ROOT/logs/bench"
exec "$bin" --config-dir "$ROOT/config" --out "$ROOT/logs/bench/gateways.json" "$@"

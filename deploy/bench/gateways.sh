#!/usr/bin/env bash
# ./rgnav bench gateways [--repetitions N] [--only WORLD ...] [--skip-doors]
# Gateway detection on the simulated worlds: per hallway environment and class the
# recognition rate of SOC-last, SOC-last-but-one, ASC and HMM (even runs train, odd runs
# test) next to dissertation tables 4.2/4.3; door precision/recall on the office world with
# the laser alone; time per scan. Writes logs/bench/gateways.json.
# The benchmark itself: tests/eval/gateways (gateway_bench).
set -euo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
bin=$build/bin/gateway_bench
if [ ! -x "$bin" ]; then
  echo "bench gateways: $bin is not built (it needs drivers/sim; run ./rgnav build)" >&2
  exit 1
fi
mkdir -p "$root/logs/bench"
exec "$bin" --config-dir "$root/config" --out "$root/logs/bench/gateways.json" "$@"

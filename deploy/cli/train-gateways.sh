#!/usr/bin/env bash
# ./rgnav train-gateways [--repetitions N] [--only WORLD ...]
# Records labelled gateway observation sequences in the simulated hallway worlds
# (config/worlds/hallways_*; labels from their ground-truth gateways) and trains the gateway
# HMMs (diss. 4.1.3.3): writes config/gateway_models/hallways_<w>m.yaml per hallway width and
# default.yaml for the width in config/gateway_detector.yaml, which gateway_detector loads.
# Options: config/gateway_models/training.yaml. The trainer runs the simulator: tests/eval/gateways.
set -euo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
bin=$build/bin/gateway_trainer
if [ ! -x "$bin" ]; then
  echo "train-gateways: $bin is not built (it needs drivers/sim; run ./rgnav build)" >&2
  exit 1
fi
exec "$bin" --config-dir "$root/config" "$@"

#!/usr/bin/env bash
# ./rgnav bench lcm — publish->receive latency over udpm on loopback, rgnav runtime vs bare
# liblcm, for a 181-beam laser_scan_t and a ~1 MB stereo_images_t, inside a private network
# namespace (tests/support/in_netns.sh). Writes logs/bench/lcm.json. Extra arguments go to
# `rgnav_lcm_bench run` (e.g. --lasers 5000 --images 200).
# The benchmark itself: tests/eval/lcm (rgnav_lcm_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
bench_binary_or_build rgnav_lcm_bench lcm
mkdir -p "$ROOT/logs/bench"
run_in_netns lcm "$ROOT/logs/bench/lcm.json" "$bin" run --out "$ROOT/logs/bench/lcm.json" "$@"

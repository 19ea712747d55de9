#!/usr/bin/env bash
# ./rgnav bench viewer — the live viewer (procs/viewer) under load: SLAM_POSE and LASER_FRONT at
# 10 Hz and the RG map once a second over udpm, three WebSocket clients reading its stream.
# Writes logs/bench/viewer.json: latency_ms_p95 (pose published -> frame read by a client),
# cpu_core_share, clients, rss_growth_mb_30min (extrapolated from a shorter window unless
# --duration 1800; rss_window_s says how long). Runs in a private network namespace
# (tests/support/in_netns.sh). Extra arguments go to rgnav_viewer_bench (--duration S, ...).
# The benchmark itself: tests/eval/viewer (rgnav_viewer_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
bench_binary_or_build rgnav_viewer_bench viewer
mkdir -p "$ROOT/logs/bench"
run_in_netns viewer "$ROOT/logs/bench/viewer.json" "$bin" --out "$ROOT/logs/bench/viewer.json" "$@"

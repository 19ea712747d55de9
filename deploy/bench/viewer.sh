#!/usr/bin/env bash
# ./rgnav bench viewer — the live viewer (procs/viewer) under load: SLAM_POSE and LASER_FRONT at
# 10 Hz and the RG map once a second over udpm, three WebSocket clients reading its stream.
# Writes logs/bench/viewer.json: latency_ms_p95 (pose published -> frame read by a client),
# cpu_core_share, clients, rss_growth_mb_30min (extrapolated from a shorter window unless
# --duration 1800; rss_window_s says how long). Runs in a private network namespace
# (tests/support/in_netns.sh). Extra arguments go to rgnav_viewer_bench (--duration S, ...).
# The benchmark itself: tests/eval/viewer (rgnav_viewer_bench).
set -euo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
bin=$build/bin/rgnav_viewer_bench
if [[ ! -x $bin ]]; then
  echo "viewer bench: building rgnav_viewer_bench in $build" >&2
  cmake --build "$build" --target rgnav_viewer_bench
fi
out_dir=$root/logs/bench
mkdir -p "$out_dir"
set +e
bash "$root/tests/support/in_netns.sh" "$bin" --out "$out_dir/viewer.json" "$@"
rc=$?
set -e
if [[ $rc -eq 77 ]]; then
  echo "viewer bench: needs a private network namespace (root or user namespaces) so that multicast" \
       "stays on this machine; none could be made here" >&2
  exit 1
fi
[[ $rc -eq 0 ]] && echo "wrote $out_dir/viewer.json" >&2
exit $rc

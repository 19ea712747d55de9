#!/usr/bin/env bash
# ./rgnav bench lcm — publish->receive latency over udpm on loopback, rgnav runtime vs bare
# liblcm, for a 181-beam laser_scan_t and a ~1 MB stereo_images_t, inside a private network
# namespace (tests/support/in_netns.sh). Writes logs/bench/lcm.json. Extra arguments go to
# `rgnav_lcm_bench run` (e.g. --lasers 5000 --images 200).
# The benchmark itself: tests/eval/lcm (rgnav_lcm_bench).
set -euo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
bin=$build/bin/rgnav_lcm_bench
if [[ ! -x $bin ]]; then
  echo "lcm bench: building rgnav_lcm_bench in $build" >&2
  cmake --build "$build" --target rgnav_lcm_bench
fi
out_dir=$root/logs/bench
mkdir -p "$out_dir"
set +e
bash "$root/tests/support/in_netns.sh" "$bin" run --out "$out_dir/lcm.json" "$@"
rc=$?
set -e
if [[ $rc -eq 77 ]]; then
  echo "lcm bench: needs a private network namespace (root or user namespaces) so that multicast" \
       "stays on this machine; none could be made here" >&2
  exit 1
fi
[[ $rc -eq 0 ]] && echo "wrote $out_dir/lcm.json" >&2
exit $rc

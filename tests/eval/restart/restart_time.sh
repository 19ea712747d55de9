#!/bin/bash
# Seconds a real rg_kernel process takes to restore a state folder (until it logs the restored
# map), e.g. on the folders rg_kernel_restart_bench leaves (DIR/snapshots_at_stop,
# DIR/journal_only_at_stop). The folder is copied first, so it can be measured again.
#   tests/eval/restart/restart_time.sh build-rgk/bin/rg_kernel config/rg_kernel.yaml /tmp/rgk_bench/snapshots_at_stop
set -euo pipefail
bin=$1; config=$2; src=$3
dir=$(mktemp -d /tmp/rgk_restart.XXXXXX)
log=$dir.log
cp -r "$src"/. "$dir"/
start=$(date +%s.%N)
"$bin" --config "$config" --state-dir "$dir" --lcm-url memq:// > "$log" 2>&1 &
pid=$!
until grep -q "resumed from\|starting a fresh" "$log"; do
  sleep 0.2   # polling sparsely: a busy loop would slow the process measured
  kill -0 $pid 2>/dev/null || break
done
end=$(date +%s.%N)
kill -TERM $pid 2>/dev/null || true
wait $pid 2>/dev/null || true
grep -o "resumed from.*" "$log" | head -1 || cat "$log"
echo "restart seconds (process start to restored map, 0.2 s polling): $(echo "$end - $start" | bc)"
rm -rf "$dir" "$log"

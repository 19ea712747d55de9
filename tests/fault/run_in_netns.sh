#!/bin/sh
# Runs a command in a private network namespace with multicast routed on lo, so the test's
# LCM traffic never leaves it; afterwards stops any process the test left (by the pids in
# its lock files). Usage: run_in_netns.sh STATE_DIR [--prepare SCRIPT] command args...
# SCRIPT runs first (with RGNAV_FAULT_STATE set), e.g. to write the stack's configs.
set -u
state=$1; shift
rm -rf "$state"; mkdir -p "$state/probe"
export RGNAV_FAULT_STATE="$state/probe"
if [ "${1:-}" = "--prepare" ]; then
  sh "$2" || exit 2
  shift 2
fi
unshare -n sh -c 'ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec "$@"' sh "$@"
rc=$?
for f in "$state"/*/*.lock; do
  [ -f "$f" ] || continue
  pid=$(cut -d" " -f1 "$f")
  [ -n "$pid" ] && kill -9 "$pid" 2>/dev/null
done
exit $rc

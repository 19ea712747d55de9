#!/usr/bin/env bash
# Several hosts: two robot computers and a laptop, each a network (and UTS) namespace, joined
# by veth pairs to a bridge in a fourth "switch" namespace; 192.0.2.0/24 (documentation
# range) only inside these namespaces; multicast routed over the link and LCM with ttl=1.
# One deputy per robot (--host b21r-main / b21r-vision), the controller on the laptop. Checks:
# status from both deputies reaches the laptop, a cross-host dependency starts, start/stop
# orders reach the right host only, an order signed with another key is refused, shutdown
# stops both deputies. Namespaces are removed on
# any exit. Usage: multihost_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1; root=$2
export RGNAV_BUILD=$build RGNAV_ROOT=$root
tag="rgmh$$"
work=$(mktemp -d /tmp/rgnav-multihost.XXXXXX)
export MH_STATE=$work
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=1"
# Orders are signed: a key of this test's own, the same file for the deputies and the laptop
# (on a real network each host holds a copy).
export RGNAV_ORDERS_KEY=$work/orders.key
"$build/bin/rgnav_ctl" keygen >/dev/null
hosts=(r1 r2 lap)
declare -A addr=([r1]=192.0.2.11 [r2]=192.0.2.12 [lap]=192.0.2.20)
declare -A hname=([r1]=b21r-main [r2]=b21r-vision [lap]=laptop)
pids=()

cleanup() {
  local rc=$?
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  sleep 1
  for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null || true; done
  # Children the deputies left (their lock files name them).
  for f in "$work"/*/*/*.lock; do
    [[ -f "$f" ]] || continue
    pid=$(cut -d" " -f1 "$f"); [[ -n "$pid" ]] && kill -KILL "$pid" 2>/dev/null || true
  done
  for h in "${hosts[@]}" sw; do ip netns del "$tag-$h" 2>/dev/null || true; done
  if [[ $rc -ne 0 ]]; then
    echo "--- deputy logs" >&2
    tail -n 30 "$work"/*.log >&2 || true
  fi
  rm -rf "$work"
  exit $rc
}
trap cleanup EXIT INT TERM

in_ns() { local h=$1; shift; ip netns exec "$tag-$h" "$@"; }
# Runs a command as host $1: its own network namespace and its own hostname (heartbeats carry it).
as_host() { local h=$1; shift; ip netns exec "$tag-$h" unshare -u sh -c 'hostname "$0" && exec "$@"' "${hname[$h]}" "$@"; }

ip netns add "$tag-sw"
in_ns sw ip link set lo up
in_ns sw ip link add br0 type bridge
# Flood multicast to every port (no IGMP querier on this little switch).
in_ns sw ip link set br0 type bridge mcast_snooping 0
in_ns sw ip link set br0 up
for h in "${hosts[@]}"; do
  ip netns add "$tag-$h"
  # The pair is made inside the namespaces: its names never exist in the machine's own.
  ip -n "$tag-$h" link add eth0 type veth peer name "port-$h" netns "$tag-sw"
  in_ns sw ip link set "port-$h" master br0
  in_ns sw ip link set "port-$h" up
  in_ns "$h" ip link set lo up
  in_ns "$h" ip addr add "${addr[$h]}/24" dev eth0
  in_ns "$h" ip link set eth0 up
  in_ns "$h" ip link set eth0 multicast on
  in_ns "$h" ip route add 224.0.0.0/4 dev eth0
done
# Each host sees the others on the link (neighbour table fills on the first multicast anyway).
in_ns lap ip -br addr show dev eth0 | grep -q "${addr[lap]}/24"

launch=$root/tests/procs/supervisor/multihost.pmd
for h in r1 r2; do
  as_host "$h" "$build/bin/supervisor" --launch "$launch" --host "${hname[$h]}" --state-dir "$work/$h" \
    >"$work/$h.log" 2>&1 &
  pids+=($!)
done
ctl() { as_host lap "$build/bin/rgnav_ctl" "$@"; }
state_of() {  # state_of HOST PROCESS -> the word in the STATE column of the laptop's view
  ctl status --once --listen 1.5 | awk -v host="$1" -v p="$2" '
    $1 == "host" { cur = $2 } cur == host && $1 == p { print $3 }'
}
fail() { echo "multihost: FAIL: $*" >&2; ctl status --once --listen 1.5 >&2 || true; exit 1; }

# Everything (both hosts; mh_sink waits for mh_source's heartbeats from the other robot).
ctl start everything --wait --timeout-ms 30000 || fail "the stack did not come up on both hosts"
view=$(ctl status --once --listen 1.5)
echo "$view"
grep -q "^host b21r-main " <<<"$view" || fail "no status from b21r-main"
grep -q "^host b21r-vision " <<<"$view" || fail "no status from b21r-vision"
[[ $(state_of b21r-main mh_source) == running ]] || fail "mh_source not running on b21r-main"
[[ $(state_of b21r-vision mh_sink) == running ]] || fail "mh_sink not running on b21r-vision"
# Each deputy lists only its own processes.
[[ -z $(state_of b21r-vision mh_source) ]] || fail "b21r-vision lists mh_source"
[[ -z $(state_of b21r-main mh_sink) ]] || fail "b21r-main lists mh_sink"

# An order for the wrong host is not executed anywhere.
ctl --host b21r-main stop mh_sink || true
sleep 1.5
[[ $(state_of b21r-vision mh_sink) == running ]] || fail "a stop addressed to b21r-main stopped mh_sink on b21r-vision"

# An order signed with another key is refused (the deputy keeps mh_sink running).
RGNAV_ORDERS_KEY=$work/other.key "$build/bin/rgnav_ctl" keygen >/dev/null
RGNAV_ORDERS_KEY=$work/other.key ctl --host b21r-vision stop mh_sink || true
sleep 1.5
[[ $(state_of b21r-vision mh_sink) == running ]] || fail "an order signed with another key stopped mh_sink"
grep -q "refused: signed with another key" "$work/r2.log" || fail "b21r-vision did not log the refused order"

# Orders to the right host.
ctl --host b21r-vision stop mh_sink --wait --timeout-ms 10000 || fail "stop mh_sink on b21r-vision"
[[ $(state_of b21r-vision mh_sink) == stopped ]] || fail "mh_sink not stopped"
[[ $(state_of b21r-main mh_source) == running ]] || fail "mh_source disturbed by a stop on the other host"
ctl --host b21r-main stop mh_main_only --wait --timeout-ms 10000 || fail "stop mh_main_only on b21r-main"
[[ $(state_of b21r-main mh_main_only) == stopped ]] || fail "mh_main_only not stopped"
ctl --host b21r-vision start mh_sink --wait --timeout-ms 15000 || fail "start mh_sink on b21r-vision"
ctl --host b21r-main start mh_main_only --wait --timeout-ms 15000 || fail "start mh_main_only on b21r-main"
ctl start everything --wait --timeout-ms 15000 || fail "not everything running again"

# Shutdown from the laptop: both deputies stop their processes and exit.
ctl shutdown --wait --timeout-ms 20000 || fail "shutdown"
for p in "${pids[@]}"; do
  for _ in $(seq 100); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$p" 2>/dev/null && fail "deputy $p still running after shutdown"
done
pids=()
echo "multihost: PASS"

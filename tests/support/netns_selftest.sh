#!/usr/bin/env bash
# Checks what in_netns.sh promises (run through it by ctest): a private namespace with only
# loopback, up, multicast-capable, with the multicast route, and the receive-buffer limit the
# namespace ended up with.
set -euo pipefail
fail() { echo "FAIL: $*" >&2; exit 1; }
[[ ${RGNAV_NETNS:-} == 1 ]] || fail "RGNAV_NETNS not set"
links=$(ip -o link show | awk -F': ' '{print $2}')
[[ $links == lo ]] || fail "expected only lo in the namespace, found: $links"
ip link show lo | grep -q 'UP' || fail "lo is down"
ip link show lo | grep -q 'MULTICAST' || fail "lo has no MULTICAST flag"
ip route show | grep -q '^224.0.0.0/4 dev lo' || fail "no multicast route on lo"
echo "ok: private namespace, lo up with multicast route; net.core.rmem_max=$(cat /proc/sys/net/core/rmem_max)"

#!/usr/bin/env bash
# Runs CMD in a private network namespace with multicast routed on loopback, so multi-process
# LCM tests (udpm://) never send traffic off the machine and never see another test's traffic.
#
#   in_netns.sh CMD [ARGS...]
#
# Exit status: CMD's, or 77 (ctest SKIP_RETURN_CODE) when no namespace can be made here (not
# root and no unprivileged user namespaces, or unshare forbidden by a container's seccomp).
#
# Receive buffers: since Linux 6.x net.core.rmem_max/rmem_default are per network namespace,
# but read-only inside a non-initial namespace; a new namespace copies the initial namespace's
# values. So we try to raise them (works on older kernels, where they are global and root may
# write them) and otherwise report what the namespace got. LCM's udpm `recv_buf_size` is capped
# at rmem_max (the kernel then doubles it), so a 1 MB message needs rmem_max >= ~2 MB.
#
# `--gtest_list_tests` runs outside any namespace: listing tests needs no network, and ctest's
# gtest discovery calls this script as the test binary's CROSSCOMPILING_EMULATOR.
set -euo pipefail

want_rmem=${RGNAV_NETNS_RMEM:-8388608}

if [[ $# -eq 0 ]]; then
  echo "usage: in_netns.sh CMD [ARGS...]" >&2
  exit 2
fi

for arg in "$@"; do
  if [[ "$arg" == --gtest_list_tests ]]; then exec "$@"; fi
done

if [[ "${1:-}" == --inside ]]; then
  shift
  ip link set lo up
  ip link set lo multicast on
  ip route add 224.0.0.0/4 dev lo
  for key in rmem_max rmem_default; do
    current=$(cat /proc/sys/net/core/$key)
    if (( current < want_rmem )); then
      if ! (echo "$want_rmem" > /proc/sys/net/core/$key) 2>/dev/null; then
        # Read-only in this namespace (per-netns sysctl): keep what it inherited.
        if [[ $key == rmem_max ]] && (( current < 2097152 )); then
          echo "in_netns.sh: warning: net.core.rmem_max=$current in the namespace (read-only);" \
               "messages near 1 MB may be dropped. Raise it in the initial namespace." >&2
        fi
      fi
    fi
  done
  export RGNAV_NETNS=1
  exec "$@"
fi

self=$(readlink -f "${BASH_SOURCE[0]}")
if [[ $(id -u) -eq 0 ]] && unshare -n true 2>/dev/null; then
  exec unshare -n -- bash "$self" --inside "$@"
fi
# Not root (or root without CAP_SYS_ADMIN): an unprivileged user namespace maps us to root
# inside it, which is enough to configure a private network namespace.
if unshare -r -n true 2>/dev/null; then
  exec unshare -r -n -- bash "$self" --inside "$@"
fi
echo "SKIP: cannot create a network namespace here (unshare -n and unshare -rn both refused);" \
     "multicast tests need one so they never send traffic off the machine" >&2
exit 77

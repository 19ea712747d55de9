# Sourced (sh) by tests/fault/*_stack_configs.sh, which write a stack's configs into
# $RGNAV_FAULT_STATE/config. Sets
#   c    the tree's config folder     out  the folder the stack's configs go to
#   s    the run's state folder       ov   build/bin/config_overlay (BASE OUT key=value...)
# and defines
#   check_configs SCRIPT BIN:CONFIG...  validates each written CONFIG.yaml with its process BIN
#       (--check-config) when BIN is built, so a stale key fails here, not mid-test; a rejected
#       config ends the script (status 2) with "SCRIPT: CONFIG.yaml rejected".
set -eu
: "${RGNAV_ROOT:?}" "${RGNAV_BUILD:?}" "${RGNAV_FAULT_STATE:?}"
c=$RGNAV_ROOT/config
out=$RGNAV_FAULT_STATE/config
s=$RGNAV_FAULT_STATE
ov=$RGNAV_BUILD/bin/config_overlay
mkdir -p "$out"

check_configs() {
  script=$1
  shift
  for p in "$@"; do
    bin=${p%%:*}; cfg=${p#*:}
    if [ -x "$RGNAV_BUILD/bin/$bin" ]; then
      "$RGNAV_BUILD/bin/$bin" --config "$out/$cfg.yaml" --check-config >/dev/null \
        || { echo "$script: $cfg.yaml rejected" >&2; exit 2; }
    fi
  done
}

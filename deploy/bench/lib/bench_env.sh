# shellcheck shell=bash
# Sourced first by the bench wrappers in deploy/bench (one preamble instead of one a script).
# Sets strict mode and
#   ROOT    the tree (RGNAV_ROOT overrides it)
#   BUILD   the build folder (RGNAV_BUILD; default $ROOT/build)
#   SHARED  the shared data, ../shared/data (RGNAV_DATA)
# and defines
#   bench_binary NAME LABEL [WHY]   sets `bin` to $BUILD/bin/NAME; when it is not built, says so
#                                   ("bench LABEL: ... is not built (WHY)") and exits 1
#   bench_binary_or_build NAME LABEL  the same, but builds the target NAME when it is missing
#   run_in_netns LABEL OUT CMD...   runs CMD in a private network namespace
#                                   (tests/support/in_netns.sh), says "wrote OUT" when it passed,
#                                   and exits with its status (1 when no namespace can be made)
#   add_random_buildings ARRAY DIR VARIANTS ONLY
#                                   appends --sim-random NAME=MAP to the array named ARRAY for the
#                                   generated buildings (tests/eval/buildings; RANDOM_BUILDINGS of
#                                   them, default 50, seeds from RANDOM_SEED, default 1) written to
#                                   DIR, of VARIANTS ("plain", "furnished"), named in ONLY
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
# shellcheck disable=SC2034  # for the scripts that source this
SHARED="${RGNAV_DATA:-$ROOT/../shared/data}"

bench_binary() {
  bin="$BUILD/bin/$1"
  if [ ! -x "$bin" ]; then
    echo "bench $2: $bin is not built${3:+ ($3)}" >&2
    exit 1
  fi
}

bench_binary_or_build() {
  bin="$BUILD/bin/$1"
  if [ ! -x "$bin" ]; then
    echo "bench $2: building $1 in $BUILD" >&2
    cmake --build "$BUILD" --target "$1"
  fi
}

run_in_netns() {
  local label=$1 out=$2 rc
  shift 2
  set +e
  bash "$ROOT/tests/support/in_netns.sh" "$@"
  rc=$?
  set -e
  if [[ $rc -eq 77 ]]; then
    echo "bench $label: needs a private network namespace (root or user namespaces) so that multicast" \
         "stays on this machine; none could be made here" >&2
    exit 1
  fi
  [[ $rc -eq 0 ]] && echo "wrote $out" >&2
  exit $rc
}

add_random_buildings() {
  local -n into=$1
  local spec random
  # shellcheck source=../../../tests/eval/buildings/random_building_specs.sh
  source "$ROOT/tests/eval/buildings/random_building_specs.sh"
  random=$(random_building_specs "$BUILD/bin/rgnav_building_gen" "$2" "${RANDOM_BUILDINGS:-50}" "${RANDOM_SEED:-1}" \
    "$3" "$4")
  while read -r spec; do [ -z "$spec" ] || into+=(--sim-random "$spec"); done <<< "$random"
}

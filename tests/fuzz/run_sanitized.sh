#!/usr/bin/env bash
# The decode fuzz tests under ASan+UBSan, and the libFuzzer target, in a nested build of just
# those targets (tests/fuzz/CMakeLists.txt registers the three steps as ctests).
#
#   run_sanitized.sh build  SOURCE_DIR BUILD_DIR   configure + build (clang if present)
#   run_sanitized.sh gtest  SOURCE_DIR BUILD_DIR   run rgnav_decode_fuzz_test
#   run_sanitized.sh fuzz   SOURCE_DIR BUILD_DIR   run decode_fuzzer for RGNAV_FUZZ_RUNS runs
#
# The nested build is incremental: only the first run pays for compiling (see the timing in
# tests/fuzz/CMakeLists.txt); later runs rebuild what changed, and the two test steps take
# ~10-15 s each.
set -euo pipefail
mode=$1 src=$2 build=$3
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

have_clang() { command -v clang++ > /dev/null && command -v clang > /dev/null; }

case $mode in
  build)
    # -O1 -g1: sanitizer reports keep file:line, and compiling costs about half of -O2 -g.
    args=(-G Ninja -DCMAKE_BUILD_TYPE=None "-DCMAKE_C_FLAGS=-O1 -g1 -fno-omit-frame-pointer"
          "-DCMAKE_CXX_FLAGS=-O1 -g1 -fno-omit-frame-pointer" -DRGNAV_ASAN=ON -DRGNAV_UBSAN=ON
          -DRGNAV_COMPONENTS=fuzz)
    targets=(rgnav_decode_fuzz_test)
    if have_clang; then
      args+=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DRGNAV_FUZZ=ON)
      targets+=(rgnav_decode_fuzzer rgnav_fuzz_corpus)
    else
      echo "clang not found: building the sanitized gtest with the default compiler, no libFuzzer" >&2
    fi
    mkdir -p "$build"
    cmake -S "$src" -B "$build" "${args[@]}" > "$build/configure.log" 2>&1 \
      || { cat "$build/configure.log"; exit 1; }
    ninja -C "$build" -j "${RGNAV_FUZZ_JOBS:-2}" "${targets[@]}"
    ;;
  gtest)
    exec "$build/bin/rgnav_decode_fuzz_test" --gtest_brief=1
    ;;
  fuzz)
    if [[ ! -x $build/bin/rgnav_decode_fuzzer ]]; then
      echo "SKIP: no libFuzzer build (needs clang)" >&2
      exit 77
    fi
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    mkdir -p "$work/seeds" "$work/new"
    "$build/bin/rgnav_fuzz_corpus" "$work/seeds"
    # Bounded and reproducible: fixed seed and run count. -malloc_limit_mb fails the run if one
    # decode allocates more than a message could need; -timeout fails a hanging input.
    exec "$build/bin/rgnav_decode_fuzzer" -runs="${RGNAV_FUZZ_RUNS:-300000}" -seed=1 -max_len=8192 \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 -print_final_stats=1 \
      -artifact_prefix="$build/" "$work/new" "$work/seeds"
    ;;
  *)
    echo "usage: run_sanitized.sh build|gtest|fuzz SOURCE_DIR BUILD_DIR" >&2
    exit 2
    ;;
esac

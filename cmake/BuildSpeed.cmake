# How long a build takes on the 2-core machines rgnav is developed and tested on. Nothing here
# changes generated code: debug info never does (GCC keeps -g code identical to code without it),
# and the linker and the compiler cache only change how fast the same objects are produced.

# Debug info: line tables only (-g1) by default. Backtraces, perf and gdb's breakpoints on lines
# keep working; locals and types need -DRGNAV_DEBUG_INFO=full (or a Debug build). Full -g costs
# about a third of the compile time of an optimised object and most of the link time.
set(RGNAV_DEBUG_INFO "lines" CACHE STRING "Debug info of RelWithDebInfo builds: lines (-g1) or full (-g)")
set_property(CACHE RGNAV_DEBUG_INFO PROPERTY STRINGS lines full)
if(RGNAV_DEBUG_INFO STREQUAL "lines")
  set(CMAKE_C_FLAGS_RELWITHDEBINFO "-O2 -g1 -DNDEBUG")
  set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O2 -g1 -DNDEBUG")
elseif(NOT RGNAV_DEBUG_INFO STREQUAL "full")
  message(FATAL_ERROR "RGNAV_DEBUG_INFO must be 'lines' or 'full', not '${RGNAV_DEBUG_INFO}'")
endif()

# gold links the ~150 executables several times faster than the default ld.bfd (binutils ships both).
include(CheckLinkerFlag)
check_linker_flag(CXX "-fuse-ld=gold" RGNAV_HAVE_GOLD)
if(RGNAV_HAVE_GOLD)
  add_link_options(-fuse-ld=gold)
endif()

# A compiler cache when one is installed and none was chosen: rebuilds after a branch switch or
# in a second worktree cost little. (A fresh machine without ccache builds the same way.)
find_program(RGNAV_CCACHE ccache)
if(RGNAV_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_C_COMPILER_LAUNCHER ${RGNAV_CCACHE})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${RGNAV_CCACHE})
endif()

# Benchmarks are not tests: their executables (and the libraries only they use) are left out of
# the default build, which CI and `./rgnav test` run, and built by the `benchmarks` target, which
# `./rgnav bench` builds first. rgnav_benchmark(target...) marks them.
function(rgnav_benchmark)
  set_target_properties(${ARGN} PROPERTIES EXCLUDE_FROM_ALL TRUE)
  set_property(GLOBAL APPEND PROPERTY RGNAV_BENCHMARKS ${ARGN})
endfunction()

# After every folder is added: the `benchmarks` target builds all the marked executables.
function(rgnav_add_benchmarks_target)
  get_property(benchmarks GLOBAL PROPERTY RGNAV_BENCHMARKS)
  add_custom_target(benchmarks)
  if(benchmarks)
    add_dependencies(benchmarks ${benchmarks})
  endif()
endfunction()

# Unity builds: each target's sources are compiled in batches of RGNAV_UNITY_BATCH files, one
# compiler run a batch. A first build spends most of its time parsing the same headers (gtest,
# Eigen, OpenCV, CLI11) and instantiating the same templates once per file; a batch does that
# once (six CAN test files: 19 s of CPU apart, 8 s as one batch). Nothing in the generated code
# changes: the same functions are compiled with the same flags. A change to one file recompiles
# its batch; developers who rebuild one file often may set -DRGNAV_UNITY=OFF.
# Files of a batch share one scope: names in anonymous namespaces and `static` functions must be
# unique within a target (the build says which clash).
option(RGNAV_UNITY "Compile each target's sources in batches (faster first build)" ON)
set(RGNAV_UNITY_BATCH 8 CACHE STRING "Sources per unity batch")
if(RGNAV_UNITY)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE ${RGNAV_UNITY_BATCH})
endif()

# Entry points (*_main.cpp) are compiled without optimisation. They parse arguments with CLI11
# (header-only: about 7 s of CPU a file at -O2, 3.5 s at -O0, in some 50 files), load the config
# and hand over to a library, which keeps the build's optimisation: no work a process does per
# message or per cycle is in a main. Benchmarks (rgnav_benchmark) keep -O2: their mains drive
# measurements.
function(rgnav_unoptimised_mains)
  _rgnav_targets_under(${PROJECT_SOURCE_DIR} targets)
  get_property(benchmarks GLOBAL PROPERTY RGNAV_BENCHMARKS)
  set(count 0)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY" OR type STREQUAL "UTILITY" OR target IN_LIST benchmarks)
      continue()
    endif()
    get_target_property(sources ${target} SOURCES)
    get_target_property(dir ${target} SOURCE_DIR)
    foreach(source ${sources})
      if(source MATCHES "_main\\.cpp$")
        # The path must be absolute: a relative one is taken relative to this folder, not `dir`.
        if(NOT IS_ABSOLUTE ${source})
          set(source ${dir}/${source})
        endif()
        set_property(SOURCE ${source} DIRECTORY ${dir} APPEND PROPERTY COMPILE_OPTIONS -O0)
        math(EXPR count "${count} + 1")
      endif()
    endforeach()
  endforeach()
  message(STATUS "Entry points compiled without optimisation: ${count}")
endfunction()

# Test executables (gtest files under tests/, not benchmarks) are compiled at -O1 in optimised
# builds. Their code sets up cases and compares results; the work they check runs in the
# libraries they link, which keep the build's -O2. -O1 costs about three quarters of -O2's
# compile time on these template-heavy files (gtest, Eigen, generated LCM types: a planner test
# batch 15.2 s -> 11.5 s of CPU). Libraries under tests/ (support, evaluation) keep -O2: the
# benchmarks run them.
set(RGNAV_TEST_OPTIMISATION "-O1" CACHE STRING "Optimisation of test executables in optimised builds (empty: the build's own)")
function(rgnav_lightly_optimised_tests)
  if(NOT RGNAV_TEST_OPTIMISATION OR NOT CMAKE_BUILD_TYPE MATCHES "^(RelWithDebInfo|Release)$")
    return()
  endif()
  _rgnav_targets_under(${PROJECT_SOURCE_DIR}/tests targets)
  get_property(benchmarks GLOBAL PROPERTY RGNAV_BENCHMARKS)
  set(count 0)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(NOT type STREQUAL "EXECUTABLE" OR target IN_LIST benchmarks)
      continue()
    endif()
    target_compile_options(${target} PRIVATE ${RGNAV_TEST_OPTIMISATION})
    math(EXPR count "${count} + 1")
  endforeach()
  message(STATUS "Test executables compiled with ${RGNAV_TEST_OPTIMISATION}: ${count}")
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rgnav_unoptimised_mains)
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rgnav_lightly_optimised_tests)

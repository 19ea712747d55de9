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

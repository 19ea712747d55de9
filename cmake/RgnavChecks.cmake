# Build checks that keep the tree in shape, run at the end of configure.
#
# rgnav_algorithm_library(target...): the target is an algorithm library, which must build and
# link without LCM (STYLE.md 1: only a node adapter converts messages). At the end of configure
# every registered target's link closure (LINK_LIBRARIES and INTERFACE_LINK_LIBRARIES,
# followed transitively, $<LINK_ONLY:...> included) is searched for LCM; reaching it is a
# FATAL_ERROR naming the chain, e.g.
#   rgnav_rg_kernel -> rgnav_rgmap -> rgnav_lcmtypes
# The message seam goes into a separate `_node` or `_conversions` target instead.
#
# Every target defined under procs/ must not link the simulator (drivers/sim): a process and its
# product tools run on the robot; what drives the simulator around them is evaluation
# (tests/eval).

# What counts as LCM: the library itself, the generated message types, and the runtime (bus,
# node, process main) that links them.
set(RGNAV_LCM_TARGETS PkgConfig::LCM lcm rgnav_lcmtypes rgnav_runtime)
set(RGNAV_SIMULATOR_TARGETS rgnav_sim_core rgnav_sim_node rgnav_sim_protocol)

function(rgnav_algorithm_library)
  set_property(GLOBAL APPEND PROPERTY RGNAV_ALGORITHM_LIBRARIES ${ARGN})
endfunction()

# The direct link items of `target` that name other link items (generator expressions other
# than $<LINK_ONLY:x> cannot be evaluated at configure time and are left out).
function(_rgnav_link_items target out)
  set(items "")
  get_target_property(imported ${target} IMPORTED)
  set(props INTERFACE_LINK_LIBRARIES)
  if(NOT imported)
    list(APPEND props LINK_LIBRARIES)
  endif()
  foreach(prop ${props})
    get_target_property(value ${target} ${prop})
    if(value)
      foreach(item ${value})
        if(item MATCHES "^\\$<LINK_ONLY:([^$<>]+)>$")
          set(item ${CMAKE_MATCH_1})
        endif()
        if(item MATCHES "^::@" OR item MATCHES "\\$<")
          continue()
        endif()
        list(APPEND items ${item})
      endforeach()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES items)
  set(${out} ${items} PARENT_SCOPE)
endfunction()

# Depth-first search from `target` for one of the items in the list `forbidden_var` names; sets
# `out` to the chain "a -> b -> forbidden" or "". `visited_var` names the caller's list of
# targets already searched without finding one.
function(_rgnav_forbidden_chain target chain forbidden_var visited_var out)
  set(visited ${${visited_var}})
  _rgnav_link_items(${target} items)
  foreach(item ${items})
    if(item IN_LIST ${forbidden_var})
      set(${out} "${chain} -> ${item}" PARENT_SCOPE)
      set(${visited_var} ${visited} PARENT_SCOPE)
      return()
    endif()
    if(NOT TARGET ${item} OR item IN_LIST visited)
      continue()
    endif()
    list(APPEND visited ${item})
    _rgnav_forbidden_chain(${item} "${chain} -> ${item}" ${forbidden_var} visited found)
    if(found)
      set(${out} "${found}" PARENT_SCOPE)
      set(${visited_var} ${visited} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
  set(${visited_var} ${visited} PARENT_SCOPE)
endfunction()

# FATAL_ERROR `what` followed by one chain per target of `targets` that reaches an item of the
# list `forbidden_var` names.
function(_rgnav_refuse_links targets forbidden_var what)
  set(errors "")
  foreach(target ${targets})
    if(NOT TARGET ${target})
      message(FATAL_ERROR "rgnav checks: no target named ${target}")
    endif()
    set(visited "")
    _rgnav_forbidden_chain(${target} ${target} ${forbidden_var} visited chain)
    if(chain)
      string(APPEND errors "  ${chain}\n")
    endif()
  endforeach()
  if(errors)
    message(FATAL_ERROR "${what}:\n${errors}")
  endif()
endfunction()

function(rgnav_check_algorithm_libraries)
  get_property(targets GLOBAL PROPERTY RGNAV_ALGORITHM_LIBRARIES)
  _rgnav_refuse_links("${targets}" RGNAV_LCM_TARGETS
                      "Algorithm libraries must not link LCM (move the message code into the node target)")
  list(LENGTH targets count)
  message(STATUS "LCM-free algorithm libraries checked: ${count}")
endfunction()

# Targets defined in `dir` and its subfolders.
function(_rgnav_targets_under dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    _rgnav_targets_under(${sub} more)
    list(APPEND targets ${more})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

function(rgnav_check_procs_without_simulator)
  if(NOT EXISTS ${PROJECT_SOURCE_DIR}/procs/CMakeLists.txt)
    return()
  endif()
  _rgnav_targets_under(${PROJECT_SOURCE_DIR}/procs targets)
  _rgnav_refuse_links("${targets}" RGNAV_SIMULATOR_TARGETS
                      "procs/ must not depend on the simulator (evaluation belongs in tests/eval)")
endfunction()

# Run the checks once every folder has defined its targets: at the end of the top-level
# CMakeLists.txt.
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rgnav_check_algorithm_libraries)
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rgnav_check_procs_without_simulator)

# Build checks that keep the tree in shape.
#
# rgnav_algorithm_library(target...): the target is an algorithm library, which must build and
# link without LCM (STYLE.md 1: only a node adapter converts messages). At the end of configure
# every registered target's link closure (LINK_LIBRARIES and INTERFACE_LINK_LIBRARIES,
# followed transitively, $<LINK_ONLY:...> included) is searched for LCM; reaching it is a
# FATAL_ERROR naming the chain, e.g.
#   rgnav_rg_kernel -> rgnav_rgmap -> rgnav_lcmtypes
# The message seam goes into a separate `_node` or `_conversions` target instead.

# What counts as LCM: the library itself, the generated message types, and the runtime (bus,
# node, process main) that links them.
set(RGNAV_LCM_TARGETS PkgConfig::LCM lcm rgnav_lcmtypes rgnav_runtime)

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

# Depth-first search from `target`; sets `out` to the chain "a -> b -> LCM" or "".
# `visited_var` names the caller's list of targets already searched without finding LCM.
function(_rgnav_lcm_chain target chain visited_var out)
  set(visited ${${visited_var}})
  _rgnav_link_items(${target} items)
  foreach(item ${items})
    if(item IN_LIST RGNAV_LCM_TARGETS)
      set(${out} "${chain} -> ${item}" PARENT_SCOPE)
      set(${visited_var} ${visited} PARENT_SCOPE)
      return()
    endif()
    if(NOT TARGET ${item} OR item IN_LIST visited)
      continue()
    endif()
    list(APPEND visited ${item})
    _rgnav_lcm_chain(${item} "${chain} -> ${item}" visited found)
    if(found)
      set(${out} "${found}" PARENT_SCOPE)
      set(${visited_var} ${visited} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
  set(${visited_var} ${visited} PARENT_SCOPE)
endfunction()

function(rgnav_check_algorithm_libraries)
  get_property(targets GLOBAL PROPERTY RGNAV_ALGORITHM_LIBRARIES)
  set(errors "")
  foreach(target ${targets})
    if(NOT TARGET ${target})
      message(FATAL_ERROR "rgnav_algorithm_library: no target named ${target}")
    endif()
    set(visited "")
    _rgnav_lcm_chain(${target} ${target} visited chain)
    if(chain)
      string(APPEND errors "  ${chain}\n")
    endif()
  endforeach()
  if(errors)
    message(FATAL_ERROR "Algorithm libraries must not link LCM (move the message code into the "
                        "node target):\n${errors}")
  endif()
  list(LENGTH targets count)
  message(STATUS "LCM-free algorithm libraries checked: ${count}")
endfunction()

# Run the check once every folder has defined its targets: at the end of the top-level
# CMakeLists.txt.
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rgnav_check_algorithm_libraries)

# Checks the layering of src/ and include/vibromap/ (run by ctest as `cmake -P`):
# every file belongs to the layer its folder names, and may include project headers only from
# the layers listed for it below, and none of the third-party headers listed as forbidden.
# Fails with one line per offending include.
#   cmake -DSOURCE_DIR=<repository> -P tests/layers/check_layers.cmake

cmake_minimum_required(VERSION 3.20)

# Layer -> layers whose headers it may include (itself included). python is the Python module
# (src/python), beside cli at the top.
set(allowed_core      core)
set(allowed_io        core io)
set(allowed_parallel  parallel)
set(allowed_campaigns core io parallel campaigns)
set(allowed_cli       core io parallel campaigns cli)
set(allowed_python    core io python)
# Layer -> regex of third-party includes it must not use (MPI only in parallel, HDF5 and TOML
# only in io, CLI11 only in cli, NLopt not in the core).
set(forbidden_core     "^(mpi\\.h|hdf5.*|H5.*|toml\\+\\+/.*|CLI/.*|nlopt.*)$")
set(forbidden_io       "^(mpi\\.h|CLI/.*)$")
set(forbidden_parallel "^(hdf5.*|H5.*|toml\\+\\+/.*|CLI/.*)$")
set(forbidden_campaigns "^(mpi\\.h|hdf5.*|H5.*|toml\\+\\+/.*|CLI/.*)$")
set(forbidden_cli      "^(mpi\\.h|hdf5.*|H5.*|toml\\+\\+/.*)$")
set(forbidden_python   "^(mpi\\.h|hdf5.*|H5.*|toml\\+\\+/.*|CLI/.*)$")
set(layers core io parallel campaigns cli python)
# Inside campaigns: each campaign folder may include, besides its own headers and the
# campaigns' shared ones (exit_status.hpp, stoppable.hpp), the public headers of the campaign
# folders listed for it: the census folder holds the following of initial states (state codec,
# follow_state) that basins runs on its plane, and the census map's cell that the sweep solves;
# the multistart runs the sweep that seeds it.
set(campaign_folders accuracy basins census continuation multistart orbit_diagram sweep)
set(campaign_uses_basins census)
set(campaign_uses_sweep  census)
set(campaign_uses_multistart sweep)   # the multistart seeds from a sweep's map

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_layers: give -DSOURCE_DIR=<repository>")
endif()
file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/src/*.[ch]pp" "${SOURCE_DIR}/include/vibromap/*.hpp")
set(problems "")
set(checked 0)
foreach(f IN LISTS files)
  # (Two ifs: a failing second MATCHES in one if() would clear CMAKE_MATCH_1.)
  set(layer "")
  if(f MATCHES "^src/([a-z]+)/")
    set(layer "${CMAKE_MATCH_1}")
  elseif(f MATCHES "^include/vibromap/([a-z]+)/")
    set(layer "${CMAKE_MATCH_1}")
  endif()
  if(layer STREQUAL "")
    string(APPEND problems "${f}: not inside a layer folder (${layers})\n")
    continue()
  endif()
  if(NOT layer IN_LIST layers)
    string(APPEND problems "${f}: '${layer}' is not a layer (${layers})\n")
    continue()
  endif()
  set(campaign "")
  if(f MATCHES "^(src|include/vibromap)/campaigns/([a-z_]+)/")
    set(campaign "${CMAKE_MATCH_2}")
    if(NOT campaign IN_LIST campaign_folders)
      string(APPEND problems "${f}: '${campaign}' is not a campaign folder (${campaign_folders})\n")
    endif()
  endif()
  math(EXPR checked "${checked} + 1")
  file(STRINGS "${SOURCE_DIR}/${f}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"].*$" "\\1" header "${line}")
    if(header MATCHES "^vibromap/([a-z]+)/")
      if(NOT CMAKE_MATCH_1 IN_LIST allowed_${layer})
        string(APPEND problems "${f}: includes ${header}: layer '${layer}' may include only ${allowed_${layer}}\n")
      endif()
      if(NOT campaign STREQUAL "" AND header MATCHES "^vibromap/campaigns/([a-z_]+)/")
        set(used "${CMAKE_MATCH_1}")
        if(NOT used STREQUAL campaign AND NOT used IN_LIST campaign_uses_${campaign})
          string(APPEND problems "${f}: includes ${header}: campaign '${campaign}' may use only its own folder and: ${campaign_uses_${campaign}}\n")
        endif()
      endif()
    elseif(header MATCHES "${forbidden_${layer}}")
      string(APPEND problems "${f}: includes <${header}>, which layer '${layer}' must not see\n")
    elseif(header MATCHES "\\.\\./")
      string(APPEND problems "${f}: includes ${header}: reach another folder through vibromap/<layer>/, not ../\n")
    endif()
  endforeach()
endforeach()
if(problems)
  message(FATAL_ERROR "layering broken:\n${problems}")
endif()
message(STATUS "layers: ${checked} files follow the layering")

# Tests of the Python postprocessing (postprocess/tests, pytest), included from tests/CMakeLists.txt.
# Needs an interpreter that imports numpy, h5py, matplotlib and pytest; without one the
# tests are not added (with a warning), so the C++ build and tests do not depend on Python.
find_package(VibromapPython MODULE)
if(NOT VibromapPython_FOUND)
  message(WARNING "postprocess tests not added: no Python can import numpy, h5py, matplotlib and pytest "
                  "(tried ${VibromapPython_TRIED}). Install python3-numpy python3-h5py python3-matplotlib "
                  "python3-pytest, or configure with -DVIBROMAP_PYTHON=/path/to/python3.")
  return()
endif()
message(STATUS "postprocess tests use ${VibromapPython_EXECUTABLE} (Python ${VibromapPython_VERSION})")

# The C++ trajectory writer leaves its analytic sample file for the Python reader to check
# (tests/io/test_trajectory_file.cpp, TrajectoryFileSample): writer and reader are tested on one file.
set(_vibromap_sample_trajectory "${CMAKE_CURRENT_BINARY_DIR}/postprocess_sample_trajectory.h5")
set(_vibromap_pytest_env
    "PYTHONDONTWRITEBYTECODE=1"
    "MPLCONFIGDIR=${CMAKE_CURRENT_BINARY_DIR}/mplconfig")
# The program itself, for the tests that make their file with it (test_plot_branch.py: a branch
# of vibromap continue).
if(TARGET vibromap)
  list(APPEND _vibromap_pytest_env "VIBROMAP_EXE=$<TARGET_FILE:vibromap>")
endif()
if(TARGET test_trajectory_file)
  add_test(NAME postprocess_sample_trajectory
           COMMAND test_trajectory_file --gtest_filter=TrajectoryFileSample.*)
  set_tests_properties(postprocess_sample_trajectory PROPERTIES
    ENVIRONMENT "VIBROMAP_SAMPLE_TRAJECTORY=${_vibromap_sample_trajectory}"
    FIXTURES_SETUP vibromap_sample_trajectory)
  list(APPEND _vibromap_pytest_env "VIBROMAP_SAMPLE_TRAJECTORY=${_vibromap_sample_trajectory}")
endif()
# Likewise the map writer's sample (tests/io/test_map_file.cpp, MapFileSample), which
# postprocess/tests/test_map_xarray.py opens with h5py and with xarray (netCDF-4 engines).
set(_vibromap_sample_map "${CMAKE_CURRENT_BINARY_DIR}/postprocess_sample_map.h5")
if(TARGET test_map_file)
  add_test(NAME postprocess_sample_map
           COMMAND test_map_file --gtest_filter=MapFileSample.*)
  set_tests_properties(postprocess_sample_map PROPERTIES
    ENVIRONMENT "VIBROMAP_SAMPLE_MAP=${_vibromap_sample_map}"
    FIXTURES_SETUP vibromap_sample_map)
  list(APPEND _vibromap_pytest_env "VIBROMAP_SAMPLE_MAP=${_vibromap_sample_map}")
endif()

# -p no:cacheprovider: write nothing into the source tree. vibromap.files and vibromap.plot on
# files the program makes (test_files.py, test_plot_functions.py) are a test of their own, so
# that the two run side by side.
add_test(NAME postprocess_pytest
         COMMAND "${VibromapPython_EXECUTABLE}" -m pytest -q -p no:cacheprovider postprocess/tests
                 --ignore=postprocess/tests/test_files.py --ignore=postprocess/tests/test_plot_functions.py
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(postprocess_pytest PROPERTIES
  ENVIRONMENT "${_vibromap_pytest_env}"
  TIMEOUT 900)  # about 140 s on 2 idle cores; a loaded machine can take twice that
if(TARGET vibromap)
  add_test(NAME postprocess_files
           COMMAND "${VibromapPython_EXECUTABLE}" -m pytest -q -p no:cacheprovider postprocess/tests/test_files.py
                   postprocess/tests/test_plot_functions.py
           WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
  set_tests_properties(postprocess_files PROPERTIES ENVIRONMENT "${_vibromap_pytest_env}" TIMEOUT 600)
endif()
set(_vibromap_pytest_fixtures "")
if(TARGET test_trajectory_file)
  list(APPEND _vibromap_pytest_fixtures vibromap_sample_trajectory)
endif()
if(TARGET test_map_file)
  list(APPEND _vibromap_pytest_fixtures vibromap_sample_map)
endif()
if(_vibromap_pytest_fixtures)
  set_tests_properties(postprocess_pytest PROPERTIES FIXTURES_REQUIRED "${_vibromap_pytest_fixtures}")
endif()
unset(_vibromap_pytest_fixtures)
unset(_vibromap_sample_trajectory)
unset(_vibromap_sample_map)
unset(_vibromap_pytest_env)

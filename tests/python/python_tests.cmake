# Tests of the Python package (tests/python, pytest) against the built program, included from
# tests/CMakeLists.txt. The package is imported from the build tree (src/python assembles it
# there), so nothing is installed; without the module (no pybind11 or Python headers) the
# tests are not added.
if(NOT TARGET vibromap_python OR NOT TARGET vibromap)
  return()
endif()
# python.api: the point, its scene and keys (in this process); python.studies: the studies the
# package runs through the program (branch, curve, optimise, sweep on 2 MPI ranks).
add_test(NAME python.api
         COMMAND "${VIBROMAP_PYTHON_EXECUTABLE}" -m pytest -q -p no:cacheprovider tests/python
                 --ignore=tests/python/test_studies.py
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
add_test(NAME python.studies
         COMMAND "${VIBROMAP_PYTHON_EXECUTABLE}" -m pytest -q -p no:cacheprovider tests/python/test_studies.py
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(python.api python.studies PROPERTIES
  ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;PYTHONDONTWRITEBYTECODE=1;VIBROMAP_EXE=$<TARGET_FILE:vibromap>"
  TIMEOUT 300)

# End-to-end sweeps under mpiexec (tests/campaigns/sweep/test_sweep_mpi.py, pytest), included from
# tests/CMakeLists.txt after postprocess_tests.cmake has found the Python interpreter.
if(NOT VibromapPython_FOUND)
  message(WARNING "sweep tests not added: no Python with numpy, h5py and pytest")
  return()
endif()
add_test(NAME sweep_mpi
         COMMAND "${VibromapPython_EXECUTABLE}" -m pytest -q -p no:cacheprovider tests/campaigns/sweep
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(sweep_mpi PROPERTIES
  ENVIRONMENT "VIBROMAP_EXE=$<TARGET_FILE:vibromap>;VIBROMAP_MPIEXEC=${MPIEXEC_EXECUTABLE};PYTHONDONTWRITEBYTECODE=1"
  TIMEOUT 900
  RUN_SERIAL TRUE)

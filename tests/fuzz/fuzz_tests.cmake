# The command-line fuzzer (tests/fuzz/fuzz_cli.py, issue #28): one test per class of hostile
# input, each a fixed seed and a fixed number of cases, so a failure names its class and the
# same cases run every time. Included from tests/CMakeLists.txt after postprocess_tests.cmake
# (which finds the Python interpreter; the fuzzer reads HDF5 outputs with h5py).
#
#   ctest --test-dir build -L fuzz                       # every class
#   tests/fuzz/fuzz_cli.py --exe build/vibromap --classes output --cases 500   # by hand
#   VIBROMAP_FUZZ_CASES=3000 tests/fuzz/fuzz_cli.py --exe build/vibromap --report long.txt
#
# Each test writes its report (counts by exit code, failing cases with their command lines)
# to build/tests/fuzz/<class>.txt and each failing case's files and repro.sh beside it.
if(NOT VibromapPython_FOUND)
  message(WARNING "fuzz tests not added: no Python with numpy and h5py")
  return()
endif()

set(_vibromap_fuzz_dir "${CMAKE_CURRENT_BINARY_DIR}/fuzz")
file(MAKE_DIRECTORY "${_vibromap_fuzz_dir}")
# class and cases: every class, about a minute in all on 2 cores (a longer run by hand:
# VIBROMAP_FUZZ_CASES=3000 as above).
foreach(_entry IN ITEMS scene:60 scene-path:20 options:60 output:40 signal:30 damage:30)
  string(REPLACE ":" ";" _pair "${_entry}")
  list(GET _pair 0 _class)
  list(GET _pair 1 _cases)
  add_test(NAME fuzz.${_class}
           COMMAND "${VibromapPython_EXECUTABLE}" tests/fuzz/fuzz_cli.py --exe $<TARGET_FILE:vibromap>
                   --seed 28 --classes ${_class} --cases ${_cases} --jobs 2 --quiet
                   --report "${_vibromap_fuzz_dir}/${_class}.txt"
           WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
  # RUN_SERIAL: the cases run two at a time and the signal class times how fast a run stops.
  set_tests_properties(fuzz.${_class} PROPERTIES
    LABELS fuzz
    TIMEOUT 600
    RUN_SERIAL TRUE
    ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
endforeach()
# The fuzzer's self-test: run on tests/fuzz/fake_vibromap.py, a stand-in with one fault per
# check, it must report every one of these tags (so a check that stopped working fails here).
add_test(NAME fuzz.selftest
         COMMAND "${VibromapPython_EXECUTABLE}" tests/fuzz/fuzz_cli.py --exe tests/fuzz/fake_vibromap.py
                 --seed 28 --classes output --cases 16 --jobs 2 --timeout 5 --signal-bound 1 --memory-mb 100 --quiet
                 --expect-tags canary,expected-exit,exit-1,stderr,nonfinite-json,leak,memory,hang,crash,wrote-on-exit-2
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(fuzz.selftest PROPERTIES LABELS fuzz TIMEOUT 300 RUN_SERIAL TRUE
                     ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
# The check of written HDF5 files on made-up files with known answers (NaN where a file declares
# none, inf, a NaN coordinate).
add_test(NAME fuzz.checks COMMAND "${VibromapPython_EXECUTABLE}" tests/fuzz/test_fuzz_checks.py
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(fuzz.checks PROPERTIES LABELS fuzz TIMEOUT 60 ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
# Case generation alone, no vibromap run: 150 cases (the fuzzer's default) of each of the seeds
# 1..1000 must build, so that no seed makes the fuzzer fail before it has tested anything.
add_test(NAME fuzz.generate
         COMMAND "${VibromapPython_EXECUTABLE}" tests/fuzz/fuzz_generate.py --seeds 1-1000 --cases 150 --jobs 2
         WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
set_tests_properties(fuzz.generate PROPERTIES LABELS fuzz TIMEOUT 300 PROCESSORS 2
                     ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")
unset(_entry)
unset(_pair)
unset(_class)
unset(_cases)
unset(_vibromap_fuzz_dir)

# tests/benchmarks/compare.sh, the timing script the docs' figures name (docs/benchmarks.md):
# what it runs and in what order, and what it reports (no time is checked). Included from
# tests/CMakeLists.txt, whether or not the library benchmarks are built.
add_test(NAME benchmarks.compare_script
         COMMAND ${CMAKE_COMMAND} -DSCRIPT=${PROJECT_SOURCE_DIR}/tests/benchmarks/compare.sh
                 -DWORK=${CMAKE_CURRENT_BINARY_DIR}/compare_script -P ${PROJECT_SOURCE_DIR}/tests/benchmarks/check_compare.cmake)

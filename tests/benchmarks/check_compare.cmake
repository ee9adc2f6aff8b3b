# The test of tests/benchmarks/compare.sh (compare_tests.cmake), run with cmake -P:
#   SCRIPT  compare.sh   WORK  a scratch folder
# Two commands that write A and B into a log: the log shows the warm-ups and the turns
# (A B, then A B three times), and the report names both, their medians and the ratio. Then a
# failing command: exit 1 and its stderr named. No time is checked: only what ran, in what order.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND bash ${SCRIPT} -n 3 "echo A >> log" "echo B >> log" WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(READ ${WORK}/log log)
string(REPLACE "\n" " " log "${log}")
if(NOT rc STREQUAL "0" OR NOT log STREQUAL "A B A B A B A B ")
  message(FATAL_ERROR "compare.sh -n 3 A B: exit ${rc}, ran '${log}' (expected 'A B A B A B A B ')\n${out}${err}")
endif()
foreach(line "^A: echo A >> log\nB: echo B >> log\n" "\nruns: 3 each, in turn A B \\(after 1 warm-up run\\(s\\) of each\\)\n"
             "\nA: median [0-9.e-]+ s \\(min [0-9.e-]+, max [0-9.e-]+\\)\n" "\nB: median [0-9.e-]+ s "
             "\nA/B: [0-9.e-]+ \\(median of the 3 pair ratios, min [0-9.e-]+, max [0-9.e-]+\\; ratio of the medians [0-9.e-]+\\)\n$")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "compare.sh report lacks '${line}':\n${out}")
  endif()
endforeach()
execute_process(COMMAND bash ${SCRIPT} -w 0 "echo gone wrong >&2; exit 3" WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "1" OR NOT err MATCHES "^compare.sh: error: command A exited with status 3: .*\n  gone wrong\n$")
  message(FATAL_ERROR "a failing command: exit ${rc}, stderr:\n${err}")
endif()

# Command-line tests: run the built vibromap and check its exit code (exactly, not just
# "non-zero"), its stderr and its stdout. Included from tests/CMakeLists.txt.
#
# Each test runs check_cli.cmake (written below into the build tree) with cmake -P:
#   EXE          the vibromap executable
#   ARGS         its arguments, separated by '|' (<empty> stands for an empty argument, which a
#                CMake list would drop)
#   EXPECT_RC    the exact exit code
#   EXPECT_ERR   a regex stderr must match (optional)
#   EXPECT_OUT   a regex stdout must match (optional)
#   MAX_ERR      the longest stderr may be, in characters (optional)
# When EXPECT_RC is not 0, stderr must be exactly one line "vibromap: error: ..." and stdout
# must be empty: a failed command writes nothing else. Tests run in the source directory,
# so scenes are named as a user would name them (jobs/paper/table1.toml).

set(VIBROMAP_CLI_CHECK ${CMAKE_CURRENT_BINARY_DIR}/check_cli.cmake)
file(WRITE ${VIBROMAP_CLI_CHECK} [=[
string(REPLACE "|" ";" args "${ARGS}")
set(call "")
foreach(a IN LISTS args)
  if(a STREQUAL "<empty>")
    string(APPEND call " \"\"")
  else()
    string(APPEND call " [==[${a}]==]")
  endif()
endforeach()
cmake_language(EVAL CODE "execute_process(COMMAND [==[${EXE}]==] ${call}
                          RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)")
set(context "vibromap ${args}\n--- exit code: ${rc}\n--- stdout:\n${out}\n--- stderr:\n${err}")
if(NOT rc STREQUAL EXPECT_RC)
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT_RC}\n${context}")
endif()
if(NOT EXPECT_RC STREQUAL "0")
  if(NOT err MATCHES "^vibromap: error: [^\n]+\n$")
    message(FATAL_ERROR "stderr is not one line 'vibromap: error: ...'\n${context}")
  endif()
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "a failed command wrote to stdout\n${context}")
  endif()
endif()
if(DEFINED EXPECT_ERR AND NOT err MATCHES "${EXPECT_ERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_ERR}'\n${context}")
endif()
if(DEFINED EXPECT_OUT AND NOT out MATCHES "${EXPECT_OUT}")
  message(FATAL_ERROR "stdout does not match '${EXPECT_OUT}'\n${context}")
endif()
string(LENGTH "${err}" err_length)
if(DEFINED MAX_ERR AND err_length GREATER MAX_ERR)
  string(SUBSTRING "${err}" 0 300 head)
  message(FATAL_ERROR "stderr has ${err_length} characters, more than ${MAX_ERR}: ${head}...")
endif()
]=])

# vibromap_cli_test(name RC code ARGS arg... [ERR regex] [OUT regex] [MAX_ERR characters])
function(vibromap_cli_test name)
  cmake_parse_arguments(T "" "RC;ERR;OUT;MAX_ERR" "ARGS" ${ARGN})
  string(REPLACE ";" "|" args "${T_ARGS}")
  set(defs "-DEXE=$<TARGET_FILE:vibromap>" "-DARGS=${args}" "-DEXPECT_RC=${T_RC}")
  if(DEFINED T_ERR)
    list(APPEND defs "-DEXPECT_ERR=${T_ERR}")
  endif()
  if(DEFINED T_OUT)
    list(APPEND defs "-DEXPECT_OUT=${T_OUT}")
  endif()
  if(DEFINED T_MAX_ERR)
    list(APPEND defs "-DMAX_ERR=${T_MAX_ERR}")
  endif()
  add_test(NAME cli.${name} COMMAND ${CMAKE_COMMAND} ${defs} -P ${VIBROMAP_CLI_CHECK}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.${name} PROPERTIES LABELS cli TIMEOUT 120)
endfunction()

# A scene with a typo in a key, made at configure time.
set(VIBROMAP_CLI_TYPO_SCENE ${CMAKE_CURRENT_BINARY_DIR}/cli_typo.toml)
file(WRITE ${VIBROMAP_CLI_TYPO_SCENE} "[system]\nm1 = 1000.0\nomgea2 = 5.0\n")

# Help and version: exit 0, text on stdout.
vibromap_cli_test(help RC 0 ARGS --help OUT "Usage: vibromap.*run.*keys.*Exit codes:\n  0  done")
# The main help's list of commands is made from the registry: every command is in it, continue too.
vibromap_cli_test(help_lists_every_command RC 0 ARGS --help
                  OUT "'vibromap run --help' explains a run.*'vibromap orbit-diagram --help'.*'vibromap continue --help'.*'vibromap basins --help'.*'vibromap restitution --help'.*'vibromap keys --help'")
# A command's help points to the exit codes in one line instead of repeating the table.
vibromap_cli_test(sweep_help_exit_codes RC 0 ARGS sweep --help OUT "\nExit codes: 'vibromap --help' lists them\\.\nOutputs are written")
vibromap_cli_test(keys_help_exit_codes RC 0 ARGS keys --help OUT "--toml.*\nExit codes: 'vibromap --help' lists them\\.\n")
vibromap_cli_test(run_help RC 0 ARGS run --help
                  OUT "--set.*--format.*--trajectory.*vibromap keys.*jobs/reference.toml.*\\[system\\] +m1 m2.*mpirun -n N.*shared out over the N ranks")
vibromap_cli_test(version RC 0 ARGS --version OUT "^vibromap [0-9]+\\.[0-9]+\\.[0-9]+")
vibromap_cli_test(keys RC 0 ARGS keys OUT "system\\.omega2 +5\\.646 +rad/s")

# Bad input: exit 2, one line naming the file, the key and what is allowed.
vibromap_cli_test(missing_scene RC 2 ARGS run jobs/no_such_scene.toml
                  ERR "jobs/no_such_scene\\.toml: cannot read scene: no such file")
vibromap_cli_test(unknown_key RC 2 ARGS run ${VIBROMAP_CLI_TYPO_SCENE}
                  ERR "cli_typo\\.toml:3: unknown key 'omgea2' in \\[system\\] \\(did you mean 'omega2'\\?\\)")
vibromap_cli_test(negative_mass_by_set RC 2 ARGS run jobs/paper/table1.toml --set system.m2=-5
                  ERR "jobs/paper/table1\\.toml: --set system\\.m2=-5: \\[system\\] m2 = -5: must be > 0 \\(kg\\)")
vibromap_cli_test(unknown_key_by_set RC 2 ARGS run jobs/paper/table1.toml --set contact.E3=1e9
                  ERR "--set contact\\.E3=1e9: unknown key 'E3' in \\[contact\\]")
vibromap_cli_test(set_without_equals RC 2 ARGS run jobs/paper/table1.toml --set system.m2
                  ERR "--set system\\.m2: expected section\\.key=value")
# --set names a key as [sweep] does: the key alone when only one section has it (#29 item 4).
# m2 = 300 kg gives the (7,3) with k_con 775.110929... that --set system.m2=300 gives.
vibromap_cli_test(set_short_key RC 0 ARGS run jobs/paper/table1.toml --set m2=300 --format json
                  OUT "\"regime\": \"\\(7,3\\)\",.*\"k_con\": 775\\.1109292869")
vibromap_cli_test(set_short_key_checked RC 2 ARGS run jobs/paper/table1.toml --set m2=-5
                  ERR "jobs/paper/table1\\.toml: --set m2=-5: \\[system\\] m2 = -5: must be > 0 \\(kg\\)")
vibromap_cli_test(set_short_key_of_two_sections RC 2 ARGS run jobs/paper/table1.toml --set x1=0.01
                  ERR "--set x1=0\\.01: several sections have the key 'x1': name it section\\.key \\(initial\\.x1 or census\\.x1\\)")
vibromap_cli_test(bad_format RC 2 ARGS run jobs/paper/table1.toml --format xml ERR "--format")
vibromap_cli_test(unknown_option RC 2 ARGS run jobs/paper/table1.toml --bogus ERR "--bogus")
vibromap_cli_test(no_command RC 2 ARGS ERR "subcommand is required")
vibromap_cli_test(unknown_command RC 2 ARGS solve jobs/paper/table1.toml ERR "unknown command 'solve'")

# A key of 1 MB (a pasted blob, a binary file given as a scene): the error line echoes it cut.
string(REPEAT "x" 1048576 _vibromap_long_key)
set(VIBROMAP_CLI_LONG_KEY_SCENE ${CMAKE_CURRENT_BINARY_DIR}/cli_long_key.toml)
file(WRITE ${VIBROMAP_CLI_LONG_KEY_SCENE} "[system]\n${_vibromap_long_key} = 1.0\n")
unset(_vibromap_long_key)
vibromap_cli_test(long_key_is_cut_in_the_error_line RC 2 ARGS run ${VIBROMAP_CLI_LONG_KEY_SCENE}
                  ERR "cli_long_key\\.toml:2: unknown key 'xxxx.*1048576 characters" MAX_ERR 400)

# A scene must be a regular file of at most 4 MiB (issue #28): a device that never ends, a FIFO
# with no writer, a directory or a bigger file is refused at once (before this, /dev/zero was read
# until memory ran out and a FIFO blocked), by every command that reads a scene.
set(VIBROMAP_CLI_FIFO ${CMAKE_CURRENT_BINARY_DIR}/cli_fifo.toml)
file(REMOVE ${VIBROMAP_CLI_FIFO})
execute_process(COMMAND mkfifo ${VIBROMAP_CLI_FIFO} RESULT_VARIABLE _vibromap_rc)
if(NOT _vibromap_rc EQUAL 0)
  message(FATAL_ERROR "mkfifo ${VIBROMAP_CLI_FIFO} failed")
endif()
set(VIBROMAP_CLI_BIG_SCENE ${CMAKE_CURRENT_BINARY_DIR}/cli_big.toml)
execute_process(COMMAND truncate -s 4194305 ${VIBROMAP_CLI_BIG_SCENE})
set(_vibromap_chr "cannot read scene: it is a character device, not a regular file")
set(_vibromap_fifo_tail "cli_fifo\\.toml: it is a FIFO \\(named pipe\\), not a regular file")
set(_vibromap_fifo "cli_fifo\\.toml: cannot read scene: it is a FIFO \\(named pipe\\), not a regular file")
vibromap_cli_test(scene_dev_zero RC 2 ARGS run /dev/zero ERR "^vibromap: error: /dev/zero: ${_vibromap_chr}")
vibromap_cli_test(scene_fifo RC 2 ARGS run ${VIBROMAP_CLI_FIFO} ERR "${_vibromap_fifo}")
vibromap_cli_test(scene_directory RC 2 ARGS run jobs ERR "jobs: cannot read scene: it is a directory, not a regular file")
vibromap_cli_test(scene_too_big RC 2 ARGS run ${VIBROMAP_CLI_BIG_SCENE}
                  ERR "cli_big\\.toml: cannot read scene: 4194305 bytes, more than the 4 MiB \\(4194304 bytes\\) a scene may have")
vibromap_cli_test(sweep_scene_dev_urandom RC 2 ARGS sweep /dev/urandom ERR "/dev/urandom: ${_vibromap_chr}")
vibromap_cli_test(sweep_scene_fifo RC 2 ARGS sweep ${VIBROMAP_CLI_FIFO} ERR "${_vibromap_fifo}")
vibromap_cli_test(optimise_scene_fifo RC 2 ARGS optimise ${VIBROMAP_CLI_FIFO} ERR "${_vibromap_fifo}")
vibromap_cli_test(optimise_scene_dev_zero RC 2 ARGS optimise /dev/zero ERR "/dev/zero: ${_vibromap_chr}")
vibromap_cli_test(accuracy_scene_fifo RC 2 ARGS accuracy ${VIBROMAP_CLI_FIFO} ERR "${_vibromap_fifo}")
vibromap_cli_test(continue_scene_dev_zero RC 2 ARGS continue /dev/zero -p omega --from 7 --to 8
                  ERR "/dev/zero: ${_vibromap_chr}")
vibromap_cli_test(orbit_diagram_scene_fifo RC 2 ARGS orbit-diagram ${VIBROMAP_CLI_FIFO} -p omega --from 7 --to 8
                  ERR "${_vibromap_fifo}")
vibromap_cli_test(basins_scene_dev_urandom RC 2 ARGS basins /dev/urandom ERR "/dev/urandom: ${_vibromap_chr}")
# The one other file a scene names, [optimise] map (HDF5 would block on a FIFO for ever).
vibromap_cli_test(optimise_map_fifo RC 2 ARGS optimise jobs/demo/optimise_law.toml --set optimise.map=${VIBROMAP_CLI_FIFO}
                  ERR "optimise_law\\.toml: \\[optimise\\] map .*${_vibromap_fifo_tail}")
vibromap_cli_test(optimise_map_dev_zero RC 2 ARGS optimise jobs/demo/optimise_law.toml --set optimise.map=/dev/zero
                  ERR "optimise_law\\.toml: \\[optimise\\] map /dev/zero: it is a character device, not a regular file")
unset(_vibromap_chr)
unset(_vibromap_fifo)
unset(_vibromap_fifo_tail)
unset(_vibromap_rc)

# The trajectory file: an existing file is kept without --overwrite, a device is never written,
# and a trajectory that cannot fit in memory is refused with its size, all before the solve.
set(VIBROMAP_CLI_EXISTING ${CMAKE_CURRENT_BINARY_DIR}/cli_existing_trajectory.h5)
file(WRITE ${VIBROMAP_CLI_EXISTING} "not a trajectory yet\n")
vibromap_cli_test(trajectory_refuses_an_existing_file RC 2
                  ARGS run jobs/paper/table1.toml --trajectory ${VIBROMAP_CLI_EXISTING}
                  ERR "cli_existing_trajectory\\.h5: --trajectory: already exists. use --overwrite to replace it")
vibromap_cli_test(trajectory_refuses_a_device RC 2 ARGS run jobs/paper/table1.toml --trajectory /dev/full --overwrite
                  ERR "/dev/full: --trajectory: is a character device, not a regular file")
vibromap_cli_test(trajectory_too_big_is_refused_with_its_size RC 4
                  ARGS run jobs/paper/table1.toml --trajectory ${CMAKE_CURRENT_BINARY_DIR}/cli_huge.h5
                       --set analysis.trajectory_periods=100000000 --set analysis.trajectory_samples=100000
                  ERR "100000000 periods x 100000 samples .* need about [0-9.e+]+ GB of memory, more than half the")

# I/O failure: exit 4, before the solve.
vibromap_cli_test(trajectory_directory_missing RC 4
                  ARGS run jobs/paper/table1.toml --trajectory no_such_dir/t.h5
                  ERR "no_such_dir/t\\.h5: cannot write here: directory 'no_such_dir' does not exist")

# End to end: the paper's scenes solve to the (1,1) regime (the numbers are checked in
# test_paper_tables; here only that run reads the scene and prints the result).
vibromap_cli_test(run_table1_json RC 0 ARGS run jobs/paper/table1.toml --format json
                  OUT "\"status\": \"ok\".*\"regime\": \"\\(1,1\\)\".*\"impacts\": \\[")
vibromap_cli_test(run_table2_table RC 0 ARGS run jobs/paper/table2.toml
                  OUT "regime +\\(1,1\\).*T_con \\(s\\)")
# One definition of soft: Table 2 is soft (k_con 8.96, z_max/R* 0.024); Table 1 is rigid
# (k_con 1111); Table 2 with E2 = 2e4 Pa and R1 = R2 = 0.1 m has small k_con but z_max/R* 3.7,
# beyond the Hertz limit, so it is not soft. The default answer is the motion from rest.
vibromap_cli_test(run_table2_is_soft RC 0 ARGS run jobs/paper/table2.toml --format json
                  OUT "\"hertz_valid\": true,[ \n]*\"soft\": true.*\"steady_method\": \"follow\"")
vibromap_cli_test(run_table1_is_not_soft RC 0 ARGS run jobs/paper/table1.toml --format json
                  OUT "\"regime\": \"\\(1,1\\)\".*\"hertz_valid\": true,[ \n]*\"soft\": false")
vibromap_cli_test(run_hertz_invalid_is_not_soft RC 0
                  ARGS run jobs/paper/table2.toml --set contact.E2=2e4 --set contact.R1=0.1 --set contact.R2=0.1
                       --format json
                  OUT "\"z_ratio\": 3\\.[0-9]+,[ \n]*\"hertz_valid\": false,[ \n]*\"soft\": false")
vibromap_cli_test(run_table2_soft_row RC 0 ARGS run jobs/paper/table2.toml
                  OUT "soft +yes +periodic with impacts, stable, Hertz-valid, k_con <= 10")
# Keys of earlier versions are refused with what replaced them.
vibromap_cli_test(run_retired_basin_check RC 2 ARGS run jobs/paper/table2.toml --set analysis.basin_check=true
                  ERR "\\[analysis\\] basin_check was removed: the motion from the initial state is now the default")
vibromap_cli_test(run_retired_census_soft_kcon RC 2 ARGS run jobs/paper/table2.toml --set census.soft_kcon=5
                  ERR "\\[census\\] soft_kcon was removed: soft has one definition everywhere: set analysis.soft_kcon")

# `vibromap accuracy`: help, bad input (exit 2), an unwritable CSV (exit 4, before the
# study), and the default study end to end on Table 2 (~6 s, rk4 at 2^15 steps dominating;
# the numbers are checked in test_accuracy).
vibromap_cli_test(accuracy_help RC 0 ARGS accuracy --help
                  OUT "--csv.*--format.*reference +dopri5 at rtol 1e-13.*rk4.*dopri5.*hybrid\\+shooting.*solve time")
vibromap_cli_test(accuracy_missing_scene RC 2 ARGS accuracy jobs/no_such_scene.toml
                  ERR "jobs/no_such_scene\\.toml: cannot read scene: no such file")
vibromap_cli_test(accuracy_bad_set RC 2 ARGS accuracy jobs/paper/table2.toml --set analysis.steady=newton
                  ERR "--set analysis\\.steady=newton: \\[analysis\\] steady = \"newton\": must be one of \"follow\", \"shooting\", \"integrate\"")
vibromap_cli_test(accuracy_bad_format RC 2 ARGS accuracy jobs/paper/table2.toml --format csv ERR "--format")
vibromap_cli_test(accuracy_csv_directory_missing RC 4
                  ARGS accuracy jobs/paper/table2.toml --csv no_such_dir/a.csv
                  ERR "no_such_dir/a\\.csv: cannot write here: directory 'no_such_dir' does not exist")
vibromap_cli_test(accuracy_table2 RC 0
                  ARGS accuracy jobs/paper/table2.toml -q --overwrite --csv ${CMAKE_CURRENT_BINARY_DIR}/cli_accuracy_table2.csv
                  OUT "reference +rtol 1e-13 +ok +\\(1,1\\).*rk4 +2\\^11 steps/T.*dopri5 +rtol 1e-6 +ok.*hybrid\\+shooting +rtol 1e-12 +ok +\\(1,1\\)")

# run --census: the attractor table of one point (the monostable Table 1: one (1,1), fraction 1),
# its JSON with labels, and the errors of its flags and [census] keys.
vibromap_cli_test(run_census_table RC 0 ARGS run jobs/paper/table1.toml --census --set census.initial_conditions=4
                  OUT "census +4 initial states.*attractors +1\n.*\\(1,1\\) +1\\.0000 +0\\.0000 +111[0-9] ")
vibromap_cli_test(run_census_json RC 0 ARGS run jobs/paper/table1.toml --census --labels --format json
                  --set census.initial_conditions=3
                  OUT "\"attractors\": \\[.*\"regime\": \"\\(1,1\\)\".*\"fraction\": 1,.*\"from_rest\": true.*\"strobe\": \\[.*\"initial_conditions\": \\[.*\"labels\": \\[[^]]*0,[^]]*0,[^]]*0[^]]*\\]")
vibromap_cli_test(run_labels_needs_census RC 2 ARGS run jobs/paper/table1.toml --labels ERR "--labels needs --census")
vibromap_cli_test(run_census_bad_box RC 2 ARGS run jobs/paper/table1.toml --census --set "census.x1=[1, 0]"
                  ERR "census\\.x1=\\[1, 0\\]: \\[census\\] x1 = \\[1, 0\\]: must be an array \\[lo, hi\\]")
vibromap_cli_test(run_census_unknown_key RC 2 ARGS run jobs/paper/table1.toml --census --set census.initial_states=4
                  ERR "unknown key 'initial_states' in \\[census\\]. keys of \\[census\\]: initial_conditions")
# The minimal critical shock's keys: a bad value in one line, exit 2; --shock needs --census.
vibromap_cli_test(run_shock_needs_census RC 2 ARGS run jobs/paper/table1.toml --shock ERR "--shock needs --census")
vibromap_cli_test(run_census_shock_on_bad RC 2 ARGS run jobs/paper/table1.toml --census --shock
                  --set "census.shock_on=[\"v1\", \"v3\"]"
                  ERR "\\[census\\] shock_on = .*: must be a non-empty array of distinct names among \"x1\", \"x2\", \"v1\", \"v2\"")
vibromap_cli_test(run_census_shock_on_empty RC 2 ARGS run jobs/paper/table1.toml --census --set "census.shock_on=[]"
                  ERR "\\[census\\] shock_on = \\[\\]: must be a non-empty array")
vibromap_cli_test(run_census_shock_tolerance_bad RC 2 ARGS run jobs/paper/table1.toml --census --set census.shock_tolerance=0.5
                  ERR "\\[census\\] shock_tolerance = 0\\.5: must be in \\[1e-08, 0\\.1\\]")
vibromap_cli_test(run_census_shock_directions_bad RC 2 ARGS run jobs/paper/table1.toml --census --set census.shock_directions=0
                  ERR "\\[census\\] shock_directions = 0: must be an integer in \\[1, 1e\\+06\\]")
vibromap_cli_test(run_census_shock_max_radius_bad RC 2 ARGS run jobs/paper/table1.toml --census --set census.shock_max_radius=-1
                  ERR "\\[census\\] shock_max_radius = -1: must be in \\(0, 1000\\]")
# Table 1 has one attractor: no other to knock it into, so its shock is none (up to the largest radius).
vibromap_cli_test(run_census_shock_monostable RC 0 ARGS run jobs/paper/table1.toml --census --shock
                  --set census.initial_conditions=2 --set census.shock_directions=2 --set census.shock_max_radius=0.5
                  OUT "soft +shock\n.*\\(1,1\\) .* none\n")

# `vibromap orbit-diagram` (issue #12): the path up and back down, the state carried; a clear
# line for a bad key, range or option.
vibromap_cli_test(orbit_diagram_json RC 0 ARGS orbit-diagram jobs/paper/table2.toml --param omega --from 7.8 --to 8
                  --steps 2 --keep 2 --format json -q
                  OUT "\"key\": \"forcing\.omega\".*\"param\": 7\.8,[^}]*\"direction\": \"up\",[^}]*\"status\": \"ok\".*\"param\": 8,[^}]*\"direction\": \"down\"")
vibromap_cli_test(orbit_diagram_bad_key RC 2 ARGS orbit-diagram jobs/paper/table2.toml --param omeg --from 7 --to 8
                  ERR "--param omeg: unknown key 'omeg' \\(did you mean 'omega'\\?\\)")
vibromap_cli_test(orbit_diagram_bad_range RC 2 ARGS orbit-diagram jobs/paper/table2.toml --param omega --from 8 --to 8
                  ERR "--from 8 --to 8: need finite, different values")
# --from and --to in either order (as for continue): the same points, "up" still the key
# increasing, so the JSON is the one of --from 7.8 --to 8 above.
vibromap_cli_test(orbit_diagram_either_order RC 0 ARGS orbit-diagram jobs/paper/table2.toml --param omega --from 8 --to 7.8
                  --steps 2 --keep 2 --format json -q
                  OUT "\"param\": 7\\.8,[^}]*\"direction\": \"up\",[^}]*\"status\": \"ok\".*\"param\": 8,[^}]*\"direction\": \"up\".*\"param\": 8,[^}]*\"direction\": \"down\".*\"param\": 7\\.8,[^}]*\"direction\": \"down\"")
vibromap_cli_test(orbit_diagram_out_of_range RC 2 ARGS orbit-diagram jobs/paper/table2.toml --param m2 --from -1 --to 8
                  ERR "--param m2: .*must be > 0")
vibromap_cli_test(orbit_diagram_help RC 0 ARGS orbit-diagram --help OUT "--param.*--from.*--transient.*--keep.*hysteresis")

# `vibromap continue` (issue #12): the branch of Table 2's (1,1) up in omega turns at a fold near
# 8.242 rad/s (checked against the orbit diagram in tests/core/test_continuation.cpp); one line
# for a start that is not periodic or a bad key.
vibromap_cli_test(continue_json RC 0 ARGS continue jobs/paper/table2.toml --param omega --from 7.23 --to 8.3
                  --format json --pd-depth 0
                  OUT "\"key\": \"forcing\\.omega\".*\"points\": \\[.*\"multipliers\": \\[.*\"clearance_min\": .*\"bifurcations\": \\[[^]]*\"type\": \"fold\",[^]]*\"param\": 8\\.242")
# Table 1's (1,1) down in omega: a period doubling near 6.4617 rad/s, the doubled branch switched
# onto there (checked against the orbit diagram in tests/core/test_continuation.cpp).
vibromap_cli_test(continue_switches_at_period_doubling RC 0 ARGS continue jobs/paper/table1.toml --param omega
                  --from 7.23 --to 6.3
                  OUT "bifurcations +1\n +period-doubling +forcing\\.omega = 6\\.4617[0-9]+ +max\\|mu\\| 1\nswitched +branch 1: period 2 T, born at the period doubling forcing\\.omega = 6\\.4617[0-9]+ of branch 0. [0-9]+ points")
# The table is a summary (#29 item 4): one line per branch, no point unless --points; the output
# ends with the branch line (the contact-free branch over omega in [2, 3]: 24 points), and with
# --points with the last point, omega = 3.
vibromap_cli_test(continue_summary RC 0 ARGS continue jobs/paper/table1.toml --set system.D=10 --param omega --from 2 --to 3
                  OUT "^branch +forcing\\.omega from 2 to 3, period 1 T \\(no-contact at the start\\)\npoints +24. reached the end of the interval\nbifurcations +0\n\n +branch +period +from +to +points +stopped +\\(every point: --points, or --format json\\)\n +0 +1 T +2 +3 +24 +reached the end of the interval\n$")
vibromap_cli_test(continue_points RC 0 ARGS continue jobs/paper/table1.toml --set system.D=10 --param omega --from 2 --to 3 --points
                  OUT "\n +0 +1 T +2 +3 +24 +reached the end of the interval\n\n  branch 0 \\(period 1 T\\)\n +param +stable +max\\|mu\\| +regime +k_con +F_max \\(N\\)\n +2 +yes [^\n]+\n( +[0-9.]+ +yes [^\n]+\n)+ +3 +yes +0\\.91217 +no-contact +0 +0\n$")
vibromap_cli_test(continue_bad_key RC 2 ARGS continue jobs/paper/table2.toml --param omeg --from 7 --to 8
                  ERR "--param omeg: unknown key 'omeg'")
vibromap_cli_test(continue_same_ends RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 7
                  ERR "--from 7 --to 7: need finite, different values")
vibromap_cli_test(continue_file RC 0 ARGS continue jobs/paper/table1.toml --set system.D=10 --param omega --from 2 --to 3
                  -o ${CMAKE_CURRENT_BINARY_DIR}/cli_branch.h5 --overwrite
                  OUT "bifurcations +0\nfile +.*cli_branch\\.h5")
vibromap_cli_test(continue_file_exists RC 2 ARGS continue jobs/paper/table1.toml --param omega --from 7 --to 7.5
                  -o jobs/paper/table2.toml
                  ERR "jobs/paper/table2\\.toml: --output: already exists. use --overwrite to replace it")

# `vibromap continue --curve` (issue #31): curves in two parameters. The grazing of Table 2's
# contact-free orbit (followed down from omega = 11 rad/s) as a curve in (omega, F0): it crosses
# the box from F0 = 700 N to omega = 7.3 rad/s (checked against the linear closed form in
# tests/core/test_curve_continuation.cpp), a contact-free orbit touching, the contact at higher
# F0; one line for each bad use of the options.
vibromap_cli_test(continue_curve_grazing RC 0 ARGS continue jobs/paper/table2.toml --param omega --from 11 --to 7.3
                  --pd-depth 0 --curve grazing --param2 forcing.F0 --from2 300 --to2 700
                  OUT "\ncurves +1 in \\(forcing\\.omega, forcing\\.F0\\), started at forcing\\.F0 = 500 [^\n]*\n +curve 0 +grazing \\(period 1 T\\): [0-9]+ points, forcing\\.omega 7\\.3 \\.\\. 7\\.88[0-9]+, forcing\\.F0 [0-9.]+ \\.\\. 700, worst residual [^\n]+\n +stop: left the box at forcing\\.F0 = 700. left the box at forcing\\.omega = 7\\.3\n +grazing: a contact-free orbit touches: 1 at higher forcing\\.F0, 0 at lower forcing\\.F0\n")
vibromap_cli_test(continue_curve_json RC 0 ARGS continue jobs/paper/table2.toml --param omega --from 11 --to 7.3
                  --pd-depth 0 --curve grazing --param2 F0 --from2 300 --to2 700 --format json
                  OUT "\"curves\": \\[[ \n]*\\{[ \n]*\"kind\": \"grazing\",[ \n]*\"n\": 1,[ \n]*\"stop\": \"left the box at forcing\\.F0 = 700. left the box at forcing\\.omega = 7\\.3\",[ \n]*\"start\": [0-9]+,[ \n]*\"grazing\": \"a contact-free orbit touches: 1 at higher forcing\\.F0, 0 at lower forcing\\.F0\",[ \n]*\"codim2\": \\[\\],[ \n]*\"points\": \\[[ \n]*\\{[ \n]*\"param\": 7\\.3,[ \n]*\"param2\": [0-9.]+,[ \n]*\"T_con\": ")
vibromap_cli_test(continue_curve_without_param2 RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold ERR "--curve: needs --param2 KEY --from2 C --to2 D \\(the second key and its range\\)")
vibromap_cli_test(continue_param2_without_curve RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --param2 F0 --from2 1 --to2 2 ERR "--param2/--from2/--to2: only with --curve KIND")
vibromap_cli_test(continue_curve_bad_kind RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve cusp --param2 F0 --from2 1 --to2 2
                  ERR "--curve cusp: not one of fold, period-doubling, neimark-sacker, grazing, level:NAME=VALUE")
vibromap_cli_test(continue_curve_bad_level RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve level:x1=3 --param2 F0 --from2 1 --to2 2
                  ERR "--curve level:x1=3: NAME x1 is not one of k_con, T_con, F_max, z_ratio")
vibromap_cli_test(continue_curve_level_outside_its_range RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7
                  --to 8 --curve level:k_con=-1 --param2 F0 --from2 300 --to2 700
                  ERR "--curve level:k_con=-1: VALUE -1 is outside the values k_con takes: it must be > 0\n")
vibromap_cli_test(continue_curve_level_z_ratio_negative RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7
                  --to 8 --curve level:z_ratio=-0.5 --param2 F0 --from2 300 --to2 700
                  ERR "--curve level:z_ratio=-0\\.5: VALUE -0\\.5 is outside the values z_ratio takes: it must be >= 0\n")
vibromap_cli_test(continue_curve_from2_nan RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 F0 --from2 nan --to2 700
                  ERR "--from2 nan: not a finite number \\(an end of --param2's range\\)\n")
vibromap_cli_test(continue_curve_span2_overflows RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 phi0 --from2 -1e308 --to2 1e308
                  ERR "--from2 -1e\\+308 --to2 1e\\+308: the span D - C must be finite")
vibromap_cli_test(continue_curve_empty_param2 RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 <empty> --from2 300 --to2 700 ERR "--param2 '': names no key")
# A scene whose [sweep] has an `order`: the command's own axes are not the file's to order.
vibromap_cli_test(continue_curve_scene_with_a_sweep_order RC 2 ARGS continue jobs/demo/e1_e2.toml --param omega
                  --from 7 --to 8 --curve fold --param2 forcing.nosuchkey --from2 1 --to2 2
                  ERR "^vibromap: error: --param2 forcing\\.nosuchkey: unknown key 'forcing\\.nosuchkey'; it must be a parameter")
vibromap_cli_test(continue_scene_with_a_sweep_order RC 0 ARGS continue jobs/demo/e1_e2.toml --param omega --from 7
                  --to 7.05 --max-points 5
                  OUT "branch +forcing\\.omega from 7 to 7\\.05, period 1 T .*points +5; max_points reached")
vibromap_cli_test(continue_curve_reversed_range RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 F0 --from2 700 --to2 300
                  ERR "--from2 700 --to2 300: need finite values with --from2 < --to2")
vibromap_cli_test(continue_curve_scene_value_outside RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 forcing.F0 --from2 600 --to2 700
                  ERR "--param2 forcing\\.F0: the scene's value 500 is outside \\[600, 700\\]")
vibromap_cli_test(continue_curve_same_key RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 omega --from2 6 --to2 9 ERR "--param2 omega: the same key as --param")
vibromap_cli_test(continue_curve_not_a_parameter RC 2 ARGS continue jobs/paper/table2.toml --param omega --from 7 --to 8
                  --curve fold --param2 solver.rtol --from2 1e-12 --to2 1e-8
                  ERR "--param2 solver\\.rtol: solver\\.rtol cannot be continued: the key must be a parameter")
vibromap_cli_test(continue_curve_help RC 0 ARGS continue --help OUT "--curve KIND.*--param2 KEY2.*--from2 C.*--to2 D.*followed as a curve in \\(KEY, KEY2\\)")
# A key over decades is continued in ln(KEY) (both ends > 0, ratio >= 100) and printed in its own
# units: the demo plane's k_con = 10 curve reaches E1 = 1.48e6 Pa (in E1 itself: 3.8e9 at the least).
vibromap_cli_test(continue_log_help RC 0 ARGS continue --help OUT "B/A or A/B >= 100 is continued in ln KEY")
vibromap_cli_test(continue_curve_log_key RC 0 ARGS continue jobs/demo/e1_e2.toml --param contact.E2 --from 2e5 --to 2e7
                  --curve level:k_con=10 --param2 contact.E1 --from2 2e4 --to2 2.1e11
                  OUT "30 points, contact.E2 1375311 \\.\\. 2e\\+07, contact.E1 1476858 \\.\\. 2.1e\\+11.*stop: left the box at contact.E1 = 2.1e\\+11. left the box at contact.E2 = 20000000")

# `vibromap restitution` (issue #13): the effective restitution of a free impact per law and e
# (values checked against an independent integration in tests/core/test_contact_laws.cpp);
# e = 1 gives chi = 0 (elastic Hertz); one line for an unknown law or an e outside (0, 1].
vibromap_cli_test(restitution_json RC 0 ARGS restitution --law gonthier --e 0.5 --e 1 --format json
                  OUT "\"law\": \"gonthier\",[^}]*\"e\": 0\\.5,[^}]*\"chi\": 1\\.5,[^}]*\"e_effective\": 0\\.48774.*\"e\": 1,[^}]*\"chi\": 0,")
vibromap_cli_test(restitution_table RC 0 ARGS restitution --law flores --e 0.1
                  OUT "flores +0\\.1 +14\\.4 +0\\.069444 +-0\\.030556 +no")
vibromap_cli_test(restitution_bad_law RC 2 ARGS restitution --law kelvin
                  ERR "--law: unknown contact law 'kelvin' \\(one of hertz, hunt-crossley")
vibromap_cli_test(restitution_bad_e RC 2 ARGS restitution --e 1.5 ERR "--e 1\\.5: a restitution must be in \\(0, 1\\]")

# Extreme input (issue #28): a result or exit 2 with the allowed range, never exit 1 or a hang.
# Before: run and continue never ended, optimise ignored SIGTERM, restitution exited 1 ("non-finite
# state"), basins wrote an x1 coordinate of inf, and --e '' was e = 0.
# A radius so small that z_max/R* overflowed (fuzz seed 11, case 1408), and a clearance so large
# that the census box D +- L was infinite (case 326): refused by the keys' ranges.
vibromap_cli_test(run_radius_denormal RC 2 ARGS run jobs/paper/table1.toml --set contact.R2=5e-324
                  ERR "jobs/paper/table1\\.toml: --set contact\\.R2=5e-324: \\[contact\\] R2 = 5e-324: must be in \\[1e-09, 1e\\+06\\] \\(m\\)")
vibromap_cli_test(basins_clearance_huge RC 2 ARGS basins jobs/paper/table1.toml --grid 3x3 -o never.h5 --set system.D=1e308
                  ERR "jobs/paper/table1\\.toml: --set system\\.D=1e308: \\[system\\] D = 1e\\+308: must be in \\[0, 1e\\+06\\] \\(m\\)")
vibromap_cli_test(run_forcing_near_zero RC 2 ARGS run jobs/paper/table1.toml --set forcing.omega=1e-9
                  ERR "jobs/paper/table1\\.toml: --set forcing\\.omega=1e-9: forcing\\.omega = 1e-09 rad/s is 1\\.43e-10 times omega_n = 6\\.98 rad/s, the fastest natural frequency of m1 and m2 on their springs \\(k1, k2\\): omega/omega_n must be in \\[0\\.0001, 1e\\+04\\], i\\.e\\. forcing\\.omega in \\[0\\.000698, 6\\.98e\\+04\\] rad/s")
vibromap_cli_test(continue_from_1e-300_to_1e308 RC 2 ARGS continue jobs/paper/table1.toml -p forcing.omega --from 1e-300 --to 1e308
                  ERR "jobs/paper/table1\\.toml: --param forcing\\.omega: at the cell forcing\\.omega = 1e-300: forcing\\.omega = 1e-300 rad/s is .* must be in \\[0\\.0001, 1e\\+04\\]")
vibromap_cli_test(orbit_diagram_forcing_too_fast RC 2 ARGS orbit-diagram jobs/paper/table1.toml -p omega --from 7 --to 1e6
                  ERR "--param omega: at the cell forcing\\.omega = 1e\\+06: forcing\\.omega = 1e\\+06 rad/s is 1\\.43e\\+05 times omega_n")
vibromap_cli_test(sweep_forcing_too_slow_at_a_corner RC 2 ARGS sweep jobs/demo/frequency_response.toml
                  --set "sweep.forcing.omega={from=1e-4,to=12,n=3}" -o no_file.h5
                  ERR "--set sweep\\.forcing\\.omega=\\{from=1e-4,to=12,n=3\\}: at the cell forcing\\.F0 = 50, forcing\\.omega = 1e-04: forcing\\.omega = 0\\.0001 rad/s is 1\\.49e-05 times omega_n = 6\\.72 rad/s")
vibromap_cli_test(optimise_main_spring_of_2147483647 RC 2 ARGS optimise jobs/demo/optimise_law.toml --set system.omega1=2147483647
                  ERR "optimise_law\\.toml: --set system\\.omega1=2147483647: forcing\\.omega = 7\\.23 rad/s is 3\\.37e-09 times omega_n = 2\\.15e\\+09 rad/s")
vibromap_cli_test(restitution_flores_1e-6 RC 0 ARGS restitution --law flores --e 1e-6 --format json
                  OUT "\"law\": \"flores\",[^}]*\"e\": 1e-06,[^}]*\"e_effective\": 6\\.25000[0-9]*e-07")
vibromap_cli_test(restitution_gonthier_1e-6 RC 0 ARGS restitution --law gonthier --e 1e-6 --format json
                  OUT "\"law\": \"gonthier\",[^}]*\"e\": 1e-06,[^}]*\"e_effective\": 1\\.00000[0-9]*e-06")
vibromap_cli_test(restitution_below_the_lower_limit RC 2 ARGS restitution --e 1e-9
                  ERR "--e 1e-09: below the lower limit of flores, e >= 1\\.6e-08 \\(its damping chi\\(e\\) = 1\\.6e\\+09 must be <= 1e\\+08, the most a free impact is integrated for\\)")
vibromap_cli_test(restitution_empty_e RC 2 ARGS restitution --e <empty> ERR "--e: an empty value is not a number")
vibromap_cli_test(continue_empty_from RC 2 ARGS continue jobs/paper/table1.toml -p omega --from <empty> --to 8
                  ERR "--from: an empty value is not a number")
vibromap_cli_test(basins_box_of_every_double RC 2 ARGS basins jobs/paper/table1.toml --grid 3x3
                  --set "census.x1=[-1e308,1e308]" -o no_file.h5
                  ERR "--set census\\.x1=\\[-1e308,1e308\\]: \\[census\\] x1 = \\[-1e\\+308, 1e\\+308\\]: must be an array \\[lo, hi\\] of two finite numbers with lo <= hi and a finite hi - lo")
# Keys each in range whose product overflows (fuzz seed 24680, case 38: basins wrote x1 and v1
# coordinates [-inf nan inf] from lambda F0 / k1, exit 0): refused naming the key and its bound.
vibromap_cli_test(basins_force_amplitude_overflows RC 2 ARGS basins jobs/paper/table1.toml --grid 3x3
                  --set analysis.max_periods=20 --set forcing.lambda=1.7976931348623157e308 -o no_file.h5
                  ERR "jobs/paper/table1\\.toml: --set forcing\\.lambda=1\\.7976931348623157e308: \\[forcing\\] lambda = 1\\.7976931348623157e\\+308: makes the force amplitude lambda F0 \\(N\\) not finite; with the other keys as given it must be at most 3\\.595e\\+305\n")
vibromap_cli_test(run_flores_chi_overflows RC 2 ARGS run jobs/paper/table1.toml --set contact.law=flores
                  --set contact.restitution=5e-324
                  ERR "\\[contact\\] restitution = 5e-324: makes the contact's damping factor chi \\(-\\) not finite; with the other keys as given it must be at least 8\\.9003e-309\n")
vibromap_cli_test(sweep_force_amplitude_overflows_at_a_corner RC 2 ARGS sweep jobs/paper/table1.toml
                  --set "sweep.forcing.lambda={from=1,to=1e308,n=2}" -o no_file.h5
                  ERR "--set sweep\\.forcing\\.lambda=\\{from=1,to=1e308,n=2\\}: at the cell forcing\\.lambda = 1e\\+308: \\[forcing\\] lambda = 1e\\+308: makes the force amplitude lambda F0 \\(N\\) not finite; with the other keys as given it must be at most 3\\.595e\\+305\n")
vibromap_cli_test(continue_span_overflows RC 2 ARGS continue jobs/paper/table1.toml -p phi0 --from -1e308 --to 1e308
                  ERR "--from -1e\\+308 --to 1e\\+308: the span B - A must be finite")
vibromap_cli_test(step_budget_ceiling RC 2 ARGS run jobs/paper/table1.toml --set solver.max_steps=1e11
                  ERR "--set solver\\.max_steps=1e11: \\[solver\\] max_steps = 1e\\+11: must be an integer in \\[1, 1e\\+10\\]")
vibromap_cli_test(fragility_bounds RC 2 ARGS run jobs/paper/table1.toml --set analysis.fragility=0.5
                  ERR "--set analysis\\.fragility=0\\.5: \\[analysis\\] fragility = 0\\.5: must be in \\[0, 0\\.1\\]")
vibromap_cli_test(period_budget_ceiling RC 2 ARGS run jobs/paper/table1.toml --set analysis.max_periods=9e18
                  ERR "--set analysis\\.max_periods=9e18: \\[analysis\\] max_periods = 9e\\+18: must be an integer in \\[1, 1e\\+08\\]")
# A forcing phase of 1e308 rad swallowed omega t (a constant force, and impacts without end that
# grew basins, run and sweep to 500 MB and more: fuzz finding): forcing.phi0 is in [-1000, 1000]
# rad, one range for every command, a --set, a sweep axis and a continued key alike.
vibromap_cli_test(basins_phase_huge RC 2 ARGS basins jobs/paper/table1.toml --grid 3x3 -o never.h5 --set forcing.phi0=-1e308
                  ERR "jobs/paper/table1\\.toml: --set forcing\\.phi0=-1e308: \\[forcing\\] phi0 = -1e\\+308: must be in \\[-1000, 1000\\] \\(rad\\)")
vibromap_cli_test(run_phase_huge RC 2 ARGS run jobs/paper/table1.toml --set forcing.phi0=1e308
                  ERR "jobs/paper/table1\\.toml: --set forcing\\.phi0=1e308: \\[forcing\\] phi0 = 1e\\+308: must be in \\[-1000, 1000\\] \\(rad\\)")
vibromap_cli_test(sweep_phase_axis_huge RC 2 ARGS sweep jobs/demo/frequency_response.toml -o no_file.h5
                  --set "sweep.forcing.phi0={values=[0,-1e308]}"
                  ERR "--set sweep\\.forcing\\.phi0=\\{values=\\[0,-1e308\\]\\}: .*must be in \\[-1000, 1000\\] \\(rad\\)")
vibromap_cli_test(continue_phase_huge RC 2 ARGS continue jobs/paper/table1.toml -p phi0 --from 0 --to 1e6
                  ERR "--param phi0: \\[forcing\\] phi0 = 1e\\+06: must be in \\[-1000, 1000\\] \\(rad\\)")
# The best point's trajectory of optimise (2 periods x trajectory_samples) is checked as run
# --trajectory's is, before any work (before: 2147483647 samples grew optimise to 567 MB and on).
vibromap_cli_test(optimise_trajectory_too_big_is_refused_with_its_size RC 4
                  ARGS optimise jobs/demo/optimise_law.toml -o ${CMAKE_CURRENT_BINARY_DIR}/cli_optimise_huge.h5
                       --set analysis.trajectory_samples=2147483647
                  ERR "cli_optimise_huge_trajectory\\.h5: the best point's trajectory: 2 periods x 2147483647 samples .* need about [0-9.e+]+ GB of memory, more than half the")
# A map keeps no trajectory: the cells of a sweep whose scene keeps one (for run --trajectory) no
# longer integrate and store it (before: 10^8 periods of samples per cell, hours and gigabytes).
vibromap_cli_test(sweep_keeps_no_trajectory RC 0 ARGS sweep jobs/demo/frequency_response.toml
                  -o ${CMAKE_CURRENT_BINARY_DIR}/cli_sweep_no_trajectory.h5 --overwrite --quiet
                  --set analysis.trajectory_periods=100000000 --set analysis.trajectory_samples=10
                  --set "sweep.forcing.omega={values=[7.23]}" --set "sweep.forcing.F0={values=[500]}"
                  OUT "cells +1 \\(0 from the resumed map, 1 computed now\\).*regimes +\\(1,1\\) 1")
# A diverging integration whose measure overflows (rk4 at 2^11 steps a period on an impact at
# 1e9 m/s: F_max = inf) is a failed point naming the measure, never an infinite number (#28).
vibromap_cli_test(run_measure_overflow_is_a_failed_point RC 0
                  ARGS run jobs/paper/table1.toml --set "solver.method=\"rk4\"" --set solver.rk4_steps=2048
                  --set initial.v2=1e9 --set analysis.max_periods=5 --set "analysis.steady=\"integrate\"" -f json
                  OUT "\"status\": \"failed\",[^}]*\"message\": \"non-finite F_max: the integration diverged[^}]*\"F_max\": null")

# sweep.refine_on names a quantity the map must keep, since a resume plans from the file: the
# census's attractors and soft_fraction need [census] (#30).
set(VIBROMAP_CLI_REFINE_SCENE ${CMAKE_CURRENT_BINARY_DIR}/cli_refine_on_census.toml)
file(WRITE ${VIBROMAP_CLI_REFINE_SCENE}
     "[sweep]\nE1 = { from = 1e9, to = 2e11, n = 3 }\nrefine = 1\nrefine_on = [\"regime\", \"soft_fraction:0.1\"]\n")
vibromap_cli_test(sweep_refine_on_census_quantity_without_census RC 2 ARGS sweep ${VIBROMAP_CLI_REFINE_SCENE} -o no_file.h5
                  ERR "cli_refine_on_census\\.toml:4[:0-9]*: \\[sweep\\] refine_on = .*: sweep\\.refine_on names soft_fraction, a census quantity, but the scene has no \\[census\\] section: add one")
vibromap_cli_test(sweep_refine_on_attractors_by_set_without_census RC 2 ARGS sweep jobs/demo/e1_e2.toml
                  --set sweep.refine=1 --set "sweep.refine_on=[\"attractors\"]" -o no_file.h5
                  ERR "jobs/demo/e1_e2\\.toml: --set sweep\\.refine_on=\\[\"attractors\"\\]: \\[sweep\\] refine_on = \\[\"attractors\"\\]: sweep\\.refine_on names attractors, a census quantity, but the scene has no \\[census\\] section")

# An adaptive map without an audit says that the inherited points' mismatch is unmeasured (it
# printed "0 of 0 audited points differ (95 % upper bound 1)").
set(VIBROMAP_CLI_REFINE_LINE ${CMAKE_CURRENT_BINARY_DIR}/cli_refine_line.toml)
file(WRITE ${VIBROMAP_CLI_REFINE_LINE} "[system]\nD = 1000.0\n[sweep]\nE1 = { from = 1e9, to = 2e11, n = 3 }\nrefine = 1\nrefine_audit = 0\n")
vibromap_cli_test(sweep_refine_without_audit RC 0 ARGS sweep ${VIBROMAP_CLI_REFINE_LINE} -o ${CMAKE_CURRENT_BINARY_DIR}/cli_refine_line.h5 --overwrite
                  OUT "refine         1 levels: 3 points solved \\(60 %. per level 3 0. 0 speckled coarse cells solved whole\\), 2 inherited, no audit \\(sweep\\.refine_audit = 0 or nothing inherited: the inherited points' mismatch is unmeasured\\)")

# The campaigns end to end under mpiexec (pytest: tests/campaigns/sweep, multistart, basins),
# and the optimiser's command-line checks. Included from tests/CMakeLists.txt after
# cli_tests.cmake and postprocess_tests.cmake (which finds the Python interpreter).

# `vibromap optimise`: command-line checks (vibromap_cli_test, from cli_tests.cmake).
vibromap_cli_test(optimise_help RC 0 ARGS optimise --help
                  OUT "--set.*--output.*--overwrite.*--format.*\\[optimise\\].*gradient_projection.*FILE_map\\.h5.*Exit codes")
vibromap_cli_test(optimise_without_section RC 2 ARGS optimise jobs/paper/table1.toml
                  ERR "jobs/paper/table1\\.toml: no \\[optimise\\] section: nothing to optimise")
# optimise.law: the contact law as a categorical variable, named like the algorithms.
vibromap_cli_test(optimise_unknown_law RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.law=flors
                  ERR "--set optimise\\.law=flors: \\[optimise\\] law = \"flors\": unknown contact law 'flors' \\(did you mean 'flores'\\?\\); allowed: hertz, hunt-crossley, lankarani-nikravesh, flores, gonthier, or \"all\"")
vibromap_cli_test(optimise_bad_algorithm RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.algorithm=bobyq
                  ERR "--set optimise\\.algorithm=bobyq: \\[optimise\\] algorithm = \"bobyq\": unknown algorithm 'bobyq' \\(did you mean 'bobyqa'\\?\\)")
# optimise.min_soft_fraction and its re-check size: out of range or not a number, before any work.
vibromap_cli_test(optimise_min_soft_fraction_above_one RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.min_soft_fraction=1.5
                  ERR "jobs/paper/optimise_box\\.toml: --set optimise\\.min_soft_fraction=1\\.5: \\[optimise\\] min_soft_fraction = 1\\.5: must be in \\[0, 1\\]")
vibromap_cli_test(optimise_min_soft_fraction_negative RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.min_soft_fraction=-0.2
                  ERR "jobs/paper/optimise_box\\.toml: --set optimise\\.min_soft_fraction=-0\\.2: \\[optimise\\] min_soft_fraction = -0\\.2: must be in \\[0, 1\\]")
vibromap_cli_test(optimise_min_soft_fraction_not_a_number RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.min_soft_fraction=most
                  ERR "--set optimise\\.min_soft_fraction=most: \\[optimise\\] min_soft_fraction = \"most\": must be a finite number in \\[0, 1\\]")
vibromap_cli_test(optimise_soft_check_without_states RC 2
                  ARGS optimise jobs/paper/optimise_box.toml --set optimise.soft_check_initial_conditions=0
                  ERR "--set optimise\\.soft_check_initial_conditions=0: \\[optimise\\] soft_check_initial_conditions = 0: must be an integer in \\[1, 1e\\+06\\]")
vibromap_cli_test(optimise_output_directory_missing RC 4
                  ARGS optimise jobs/paper/optimise_box.toml -o no_such_dir/o.h5
                  ERR "no_such_dir/o\\.h5: cannot write here: directory 'no_such_dir' does not exist")

# `vibromap basins`: command-line checks. Bad options are refused before any MPI or file work
# (no file, no lock file is left behind), with one line naming the option and what it allows.
vibromap_cli_test(basins_help RC 0 ARGS basins --help
                  OUT "--plane.*--grid.*--at.*--resume.*--overwrite.*census.*-1 unresolved.*plot_basins.*Exit codes")
vibromap_cli_test(basins_unknown_variable RC 2 ARGS basins jobs/paper/table2.toml --plane x1,q1 -o no_file.h5
                  ERR "--plane x1,q1: unknown variable 'q1' \\(allowed: x1, x2, v1, v2\\)")
vibromap_cli_test(basins_same_variable RC 2 ARGS basins jobs/paper/table2.toml --plane v1,v1 -o no_file.h5
                  ERR "--plane v1,v1: the two variables must differ")
vibromap_cli_test(basins_bad_grid RC 2 ARGS basins jobs/paper/table2.toml --grid 200x1 -o no_file.h5
                  ERR "--grid 200x1: must be NxM with N and M whole numbers from 2 to 4096")
vibromap_cli_test(basins_grid_not_nxm RC 2 ARGS basins jobs/paper/table2.toml --grid 200 -o no_file.h5
                  ERR "--grid 200: must be NxM")
vibromap_cli_test(basins_at_plane_variable RC 2 ARGS basins jobs/paper/table2.toml --plane x1,v1 --at v1=0.1
                  -o no_file.h5 ERR "--at v1=0\\.1: v1 is a plane variable; fix only the other two")
vibromap_cli_test(basins_at_bad_value RC 2 ARGS basins jobs/paper/table2.toml --at x2=abc -o no_file.h5
                  ERR "--at x2=abc: the value must be a finite number")
vibromap_cli_test(basins_bad_entropy_box RC 2 ARGS basins jobs/paper/table2.toml --grid 8x6 --entropy-box 7 -o no_file.h5
                  ERR "--entropy-box 7: must be a whole number of pixels from 1 to the grid's smaller side \\(6\\)")
vibromap_cli_test(basins_bad_census RC 2 ARGS basins jobs/paper/table2.toml --set "census.x1=[1, 0]" -o no_file.h5
                  ERR "census\\.x1=\\[1, 0\\]: \\[census\\] x1 = \\[1, 0\\]: must be an array \\[lo, hi\\]")

if(NOT VibromapPython_FOUND)
  message(WARNING "campaign tests not added: no Python with numpy, h5py and pytest")
  return()
endif()

# vibromap_campaign_pytest(name folder): pytest on tests/campaigns/<folder>, alone on the machine
# (the runs use every core and time signals).
function(vibromap_campaign_pytest name folder)
  add_test(NAME ${name}
           COMMAND "${VibromapPython_EXECUTABLE}" -m pytest -q -p no:cacheprovider tests/campaigns/${folder}
           WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
  set_tests_properties(${name} PROPERTIES
    ENVIRONMENT "VIBROMAP_EXE=$<TARGET_FILE:vibromap>;VIBROMAP_BASINS_BRUTE=$<TARGET_FILE:basins_brute_force>;VIBROMAP_MPIEXEC=${MPIEXEC_EXECUTABLE};PYTHONDONTWRITEBYTECODE=1;MPLCONFIGDIR=${CMAKE_CURRENT_BINARY_DIR}/mplconfig"
    TIMEOUT 900
    RUN_SERIAL TRUE)
endfunction()

vibromap_campaign_pytest(sweep_mpi sweep)
vibromap_campaign_pytest(optimise_mpi multistart)
vibromap_campaign_pytest(basins_mpi basins)
# outputs: every output written the one safe way (test_outputs.py), and every HDF5 file kind
# opening in xarray with both netCDF-4 engines, group by group (test_xarray_outputs.py).
vibromap_campaign_pytest(outputs outputs)
vibromap_campaign_pytest(stop_mpi stop)
# continue (issue #31): curves in two parameters against plain runs and the curve file, and the
# branch against the closed-form linear response at the scene's Newton tolerance (item 5).
vibromap_campaign_pytest(continuation continuation)

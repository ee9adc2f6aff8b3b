# One step of the install tests (install_tests.cmake), run with cmake -P:
#   STEP        tree | run_table1 | python | post | consumer_core | consumer_all | python_package
#   SOURCE_DIR  BUILD_DIR  PREFIX (the install prefix)  WORK (scratch folder)
#   EXE         the build tree's vibromap   GENERATOR CXX CC LAUNCHER: for the consumer project
#   PYTHON      the interpreter of the postprocess tests (python_package), of the package (python)

# Runs a command; fails the test unless it exits 0. Sets <prefix>_out.
function(run prefix)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${WORK})
  if(NOT rc STREQUAL "0")
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "${cmd}\n--- exit code: ${rc}\n--- stdout:\n${out}\n--- stderr:\n${err}")
  endif()
  set(${prefix}_out "${out}" PARENT_SCOPE)
endfunction()

# The regime and k_con rows of `vibromap run SCENE` as "regime (1,1) k_con 1111.22".
function(regime_of exe scene result)
  run(cli ${exe} run ${scene})
  if(NOT cli_out MATCHES "\n  regime +([^ ]+) .*\n  k_con +([^ ]+) ")
    message(FATAL_ERROR "${exe} run ${scene}: no regime and k_con rows in\n${cli_out}")
  endif()
  set(${result} "regime ${CMAKE_MATCH_1} k_con ${CMAKE_MATCH_2}" PARENT_SCOPE)
endfunction()

# `vibromap.run` of Table 1 with the package found in `path` prints the regime and k_con the
# build tree's vibromap prints.
function(python_run_table1 path)
  # A script file: a list (run's ARGN) would split code at its semicolons.
  file(WRITE ${WORK}/table1.py "import vibromap\n"
       "r = vibromap.run(vibromap.Scene.from_toml('${SOURCE_DIR}/${table1}'))\n"
       "print(vibromap.__file__)\nprint('regime', r.regime, 'k_con', r.k_con)\n")
  run(py ${CMAKE_COMMAND} -E env PYTHONPATH=${path} ${PYTHON} ${WORK}/table1.py)
  run(cli ${EXE} run ${SOURCE_DIR}/${table1} --format json)
  if(NOT cli_out MATCHES "\"regime\": \"([^\"]+)\".*\"k_con\": ([^,]+),")
    message(FATAL_ERROR "no regime and k_con in\n${cli_out}")
  endif()
  if(NOT py_out STREQUAL "${path}/vibromap/__init__.py\nregime ${CMAKE_MATCH_1} k_con ${CMAKE_MATCH_2}\n")
    message(FATAL_ERROR "vibromap.run printed '${py_out}', vibromap run: regime ${CMAKE_MATCH_1} k_con ${CMAKE_MATCH_2}")
  endif()
endfunction()

file(MAKE_DIRECTORY ${WORK})
set(table1 jobs/paper/table1.toml)

if(STEP STREQUAL "tree")
  file(REMOVE_RECURSE ${PREFIX})
  run(install ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(f bin/vibromap bin/vibromap-post
            share/vibromap/${table1} share/vibromap/jobs/demo/e1_e2.toml share/vibromap/jobs/reference.toml
            share/doc/vibromap/README.md share/doc/vibromap/CHANGELOG.md share/doc/vibromap/docs/model.md
            share/doc/vibromap/docs/img/demo_e1_e2_soft.png
            include/vibromap/core/analysis/point/point_solver.hpp include/vibromap/campaigns/exit_status.hpp)
    if(NOT EXISTS ${PREFIX}/${f})
      message(FATAL_ERROR "not installed: ${PREFIX}/${f}")
    endif()
  endforeach()
  file(GLOB_RECURSE config RELATIVE ${PREFIX} ${PREFIX}/*/vibromapConfig.cmake)
  file(GLOB_RECURSE libs RELATIVE ${PREFIX} ${PREFIX}/*/libvibromap_*.a)
  list(SORT libs)
  list(TRANSFORM libs REPLACE ".*/" "")
  if(NOT config MATCHES "cmake/vibromap/vibromapConfig.cmake$"
     OR NOT libs STREQUAL "libvibromap_campaigns.a;libvibromap_core.a;libvibromap_io.a;libvibromap_parallel.a")
    message(FATAL_ERROR "package config '${config}', libraries '${libs}'")
  endif()
  # The package, the readers and pictures with it; no loose scripts beside it.
  file(GLOB package ${PREFIX}/lib/python*/*-packages/vibromap/plot/_regime_map.py
                    ${PREFIX}/lib/python*/*-packages/vibromap/_io/map.py)
  list(LENGTH package found)
  if(NOT found EQUAL 2 OR EXISTS ${PREFIX}/share/vibromap/postprocess)
    message(FATAL_ERROR "the package vibromap is not installed whole under ${PREFIX}/lib/python3.X ('${package}'), "
                        "or share/vibromap/postprocess is")
  endif()
  file(GLOB bin RELATIVE ${PREFIX}/bin ${PREFIX}/bin/*)
  list(SORT bin)
  if(NOT bin STREQUAL "vibromap;vibromap-post")
    message(FATAL_ERROR "bin/ holds '${bin}', expected 'vibromap;vibromap-post' (no test program)")
  endif()

elseif(STEP STREQUAL "run_table1")
  regime_of(${PREFIX}/bin/vibromap ${PREFIX}/share/vibromap/${table1} installed)
  regime_of(${EXE} ${SOURCE_DIR}/${table1} built)
  if(NOT installed STREQUAL built OR NOT installed MATCHES "^regime \\(1,1\\) ")
    message(FATAL_ERROR "installed: '${installed}', build tree: '${built}' (the paper: (1,1))")
  endif()
  message(STATUS "installed vibromap, table1: ${installed}")

elseif(STEP STREQUAL "python")
  # The package cmake --install put under the prefix, imported from there.
  file(GLOB init ${PREFIX}/lib/python*/*-packages/vibromap/__init__.py)
  if(NOT init MATCHES "^(${PREFIX}/lib/python3[.][0-9]+/(dist|site)-packages)/vibromap/__init__.py$")
    message(FATAL_ERROR "the package vibromap is not installed under ${PREFIX}/lib/python3.X/: '${init}'")
  endif()
  python_run_table1(${CMAKE_MATCH_1})

elseif(STEP STREQUAL "post")
  run(help ${PREFIX}/bin/vibromap-post --help)
  if(NOT help_out MATCHES "^usage: vibromap-post SCRIPT" OR NOT help_out MATCHES "\n  plot_regime_map\n"
     OR help_out MATCHES "_io")
    message(FATAL_ERROR "vibromap-post --help:\n${help_out}")
  endif()
  # A script of the package installed under the prefix, found by the launcher without PYTHONPATH.
  run(script ${CMAKE_COMMAND} -E env --unset=PYTHONPATH ${PREFIX}/bin/vibromap-post summarize_map --help)
  if(NOT script_out MATCHES "^usage: summarize_map ")
    message(FATAL_ERROR "vibromap-post summarize_map --help:\n${script_out}")
  endif()

elseif(STEP MATCHES "^consumer_(core|all)$")
  set(components "")
  if(CMAKE_MATCH_1 STREQUAL "core")
    set(components core)
  endif()
  set(dir ${WORK}/${STEP})
  file(REMOVE_RECURSE ${dir})
  # Only the prefix: no package registry, no build tree.
  run(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${dir} -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_C_COMPILER=${CC}
      -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER} -DCMAKE_PREFIX_PATH=${PREFIX}
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCONSUMER_COMPONENTS=${components})
  string(FIND "${configure_out}" " from ${PREFIX}/" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "vibromap not found in ${PREFIX}:\n${configure_out}")
  endif()
  run(build ${CMAKE_COMMAND} --build ${dir})
  run(consumer ${dir}/consumer)
  regime_of(${EXE} ${SOURCE_DIR}/${table1} built)
  if(NOT consumer_out STREQUAL "${built}\n")
    message(FATAL_ERROR "consumer printed '${consumer_out}', vibromap run ${table1}: '${built}'")
  endif()
  message(STATUS "consumer (${STEP}): ${consumer_out}")

elseif(STEP STREQUAL "python_package")
  # pip install --no-build-isolation --no-deps of a copy of postprocess/ (setuptools builds in
  # the tree it is given), into a folder of its own: the package, its readers and pictures, and
  # the one command vibromap-post.
  set(dir ${WORK}/python)
  file(REMOVE_RECURSE ${dir})
  # With PYTHON_CORE (a build with the module) the compiled core too, which setup.py has CMake
  # build in the build tree (VIBROMAP_BUILD_DIR).
  set(copied pyproject.toml vibromap)
  if(PYTHON_CORE)
    list(APPEND copied setup.py)
  endif()
  foreach(f ${copied})
    file(COPY ${SOURCE_DIR}/postprocess/${f} DESTINATION ${dir}/src)
  endforeach()
  run(pip ${CMAKE_COMMAND} -E env VIBROMAP_BUILD_DIR=${BUILD_DIR}
      ${PYTHON} -m pip install --no-build-isolation --no-deps --no-index --no-cache-dir
      --disable-pip-version-check --target ${dir}/target ${dir}/src)
  if(PYTHON_CORE)
    python_run_table1(${dir}/target)
  endif()
  file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR}/postprocess ${SOURCE_DIR}/postprocess/vibromap/*.py)
  file(GLOB_RECURSE installed RELATIVE ${dir}/target ${dir}/target/vibromap/*.py)
  list(SORT sources)
  list(SORT installed)
  file(GLOB scripts RELATIVE ${dir}/target/bin ${dir}/target/bin/*)
  if(NOT installed STREQUAL sources OR NOT scripts STREQUAL "vibromap-post")
    message(FATAL_ERROR "modules installed '${installed}', expected '${sources}'; "
                        "commands '${scripts}', expected 'vibromap-post' (postprocess/pyproject.toml)")
  endif()
  run(help ${CMAKE_COMMAND} -E env PYTHONPATH=${dir}/target ${dir}/target/bin/vibromap-post summarize_map --help)
  if(NOT help_out MATCHES "^usage: summarize_map ")
    message(FATAL_ERROR "vibromap-post summarize_map --help:\n${help_out}")
  endif()

else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()

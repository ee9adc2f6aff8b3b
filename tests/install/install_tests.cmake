# The installed tree (cmake/install.cmake): included from tests/CMakeLists.txt. The first test
# installs the build into build/tests/install/prefix; the others use that prefix only.
#   install.tree            cmake --install succeeds and gives the expected files, nothing more in bin/
#   install.run_table1      the installed vibromap on the installed jobs/paper/table1.toml prints
#                           the regime and k_con the build tree's vibromap prints
#   install.python          the installed package vibromap (with its _core) runs Table 1 as the
#                           build tree's vibromap does
#   install.post            the installed vibromap-post lists the scripts and runs one
#   install.consumer_core   find_package(vibromap COMPONENTS core) from a project outside the
#                           tree (tests/install/consumer), linked to vibromap::core, solves Table 1
#   install.consumer_all    the same with every component, linked to vibromap::campaigns
#   install.python_package  pip installs postprocess/ (pyproject.toml) without network: the
#                           package vibromap whole, whose run() gives Table 1's regime and k_con,
#                           and its one command vibromap-post, which runs a script
set(_check ${PROJECT_SOURCE_DIR}/tests/install/check_install.cmake)
set(_args -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DPREFIX=${CMAKE_CURRENT_BINARY_DIR}/install/prefix -DWORK=${CMAKE_CURRENT_BINARY_DIR}/install
          -DEXE=$<TARGET_FILE:vibromap> -DGENERATOR=${CMAKE_GENERATOR}
          -DCXX=${CMAKE_CXX_COMPILER} -DCC=${CMAKE_C_COMPILER} -DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
add_test(NAME install.tree COMMAND ${CMAKE_COMMAND} ${_args} -DSTEP=tree -P ${_check})
set_tests_properties(install.tree PROPERTIES FIXTURES_SETUP vibromap_installed)
foreach(_step run_table1 post consumer_core consumer_all)
  add_test(NAME install.${_step} COMMAND ${CMAKE_COMMAND} ${_args} -DSTEP=${_step} -P ${_check})
  set_tests_properties(install.${_step} PROPERTIES FIXTURES_REQUIRED vibromap_installed)
endforeach()
unset(_step)
if(TARGET vibromap_python)
  add_test(NAME install.python COMMAND ${CMAKE_COMMAND} ${_args} -DPYTHON=${VIBROMAP_PYTHON_EXECUTABLE}
           -DSTEP=python -P ${_check})
  set_tests_properties(install.python PROPERTIES FIXTURES_REQUIRED vibromap_installed)
endif()
add_test(NAME install.python_package COMMAND ${CMAKE_COMMAND} ${_args} -DPYTHON=${VibromapPython_EXECUTABLE}
         -DPYTHON_CORE=$<TARGET_EXISTS:vibromap_python>
         -DSTEP=python_package -P ${_check})
unset(_args)
unset(_check)

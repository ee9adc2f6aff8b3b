# Installation (included from the top-level CMakeLists.txt): `cmake --install build --prefix P` gives
#   P/bin/vibromap                          the executable
#   P/bin/vibromap-post                     the postprocess scripts, one command (postprocess/vibromap-post)
#   P/lib/python3.X/dist-packages/vibromap/ the Python package (site-packages for a Python not Debian's):
#                                           the solver (with its compiled core when built), the
#                                           readers, the pictures and the scripts vibromap-post runs
#   P/share/vibromap/jobs/                  the example scenes (jobs/)
#   P/share/doc/vibromap/                   README.md, CHANGELOG.md, docs/
#   P/include/vibromap/, P/lib/libvibromap_*.a and P/lib/cmake/vibromap/: the libraries, for
#   find_package(vibromap [COMPONENTS core io parallel campaigns]) and vibromap::core etc.
# One export set per layer, so that a user of the core alone needs Eigen only.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(VIBROMAP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/vibromap)

install(TARGETS vibromap RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

foreach(_layer core io parallel campaigns)
  install(TARGETS vibromap_${_layer} EXPORT vibromap-${_layer}-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT vibromap-${_layer}-targets NAMESPACE vibromap::
          DESTINATION ${VIBROMAP_INSTALL_CMAKEDIR})
endforeach()
unset(_layer)
install(DIRECTORY include/vibromap DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

configure_package_config_file(cmake/vibromapConfig.cmake.in
  ${PROJECT_BINARY_DIR}/vibromapConfig.cmake INSTALL_DESTINATION ${VIBROMAP_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vibromapConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vibromapConfig.cmake ${PROJECT_BINARY_DIR}/vibromapConfigVersion.cmake
        DESTINATION ${VIBROMAP_INSTALL_CMAKEDIR})

# The launcher: the same file as in the checkout, which finds the package under its prefix.
install(PROGRAMS postprocess/vibromap-post DESTINATION ${CMAKE_INSTALL_BINDIR})

# The Python package (postprocess/vibromap, src/python): its files, and its compiled _core when it
# is built, where the interpreter it is for looks under the prefix: lib/python3.X/dist-packages
# for Debian's (which reads /usr/local/lib/python3.X/dist-packages), else
# lib/python3.X/site-packages. Under another prefix: PYTHONPATH=PREFIX/<that folder>
# (docs/python.md); bin/vibromap-post finds it there by itself.
if(VIBROMAP_PACKAGE_PYTHON)
  execute_process(
    COMMAND "${VIBROMAP_PACKAGE_PYTHON}" -c
            "import sys; d = 'dist' if any(p.endswith('dist-packages') for p in sys.path) else 'site'; print('lib/python%d.%d/%s-packages' % (*sys.version_info[:2], d))"
    OUTPUT_VARIABLE _vibromap_python_dir OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(VIBROMAP_PYTHON_INSTALL_DIR "${_vibromap_python_dir}" CACHE STRING
      "Where cmake --install puts the Python package vibromap, under the prefix")
  if(TARGET vibromap_python)
    install(TARGETS vibromap_python LIBRARY DESTINATION ${VIBROMAP_PYTHON_INSTALL_DIR}/vibromap)
  endif()
  foreach(_file IN LISTS VIBROMAP_PYTHON_FILES)
    get_filename_component(_dir ${_file} DIRECTORY)
    install(FILES postprocess/vibromap/${_file} DESTINATION ${VIBROMAP_PYTHON_INSTALL_DIR}/vibromap/${_dir})
  endforeach()
  unset(_file)
  unset(_dir)
  unset(_vibromap_python_dir)
endif()

install(DIRECTORY jobs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/vibromap/jobs USE_SOURCE_PERMISSIONS)
install(FILES README.md CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs DESTINATION ${CMAKE_INSTALL_DOCDIR})
include(${CMAKE_CURRENT_LIST_DIR}/package.cmake)

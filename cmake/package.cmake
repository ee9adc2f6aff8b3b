# A Debian package of the installed tree (cmake/install.cmake), included from there:
#   cmake --build build && (cd build && cpack)      ->  build/vibromap_<version>_<arch>.deb
# Installs under /usr. Depends: the shared libraries vibromap links (dpkg-shlibdeps: Open MPI,
# HDF5, NLopt, libstdc++ ...) and openmpi-bin for mpirun; the Python of the postprocess scripts
# is recommended; the headers a C++ user of find_package(vibromap) needs are suggested.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME vibromap)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "vibromap maintainers <vibromap@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "parallel parameter-space explorer for two-body vibro-impact systems with Hertz contact")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "openmpi-bin")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-numpy, python3-h5py, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "libeigen3-dev (>= 3.4), libhdf5-dev, libopenmpi-dev, libnlopt-cxx-dev, libtomlplusplus-dev, python3-xarray, python3-netcdf4, python3-h5netcdf")
include(CPack)

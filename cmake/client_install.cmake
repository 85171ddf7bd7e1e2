# `cmake --install BUILD --prefix P` for outside solvers (docs/clients.md):
#   P/lib/libcosim_client.so.1...                  the library (C ABI, SONAME libcosim_client.so.1)
#   P/include/cosim/client.h client.hpp            C and C++ interfaces
#   P/include/cosim/cosim_client.f90               the Fortran module, as source
#   P/lib/cmake/cosim/cosimConfig.cmake ...        find_package(cosim CONFIG): cosim::client, cosim_FORTRAN_MODULE
#   P/lib/pkgconfig/cosim-client.pc                pkg-config: cflags, libs, variable fortran_module
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS cosim_client EXPORT cosimTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES ${CMAKE_SOURCE_DIR}/include/cosim/client.h ${CMAKE_SOURCE_DIR}/include/cosim/client.hpp
              ${CMAKE_SOURCE_DIR}/include/cosim/cosim_client.f90 DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cosim)

set(COSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/cosim)
install(EXPORT cosimTargets NAMESPACE cosim:: DESTINATION ${COSIM_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/cosimConfig.cmake.in ${CMAKE_BINARY_DIR}/cmake/cosimConfig.cmake
                              INSTALL_DESTINATION ${COSIM_CMAKE_DIR} PATH_VARS CMAKE_INSTALL_INCLUDEDIR)
# 0.x: a new minor version may change the interface.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/cosimConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/cosimConfig.cmake ${CMAKE_BINARY_DIR}/cmake/cosimConfigVersion.cmake
        DESTINATION ${COSIM_CMAKE_DIR})

# The .pc finds its prefix from its own place (${pcfiledir}), so any --prefix works.
file(RELATIVE_PATH COSIM_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" COSIM_PC_TO_PREFIX "${COSIM_PC_TO_PREFIX}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/cosim-client.pc.in ${CMAKE_BINARY_DIR}/cmake/cosim-client.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/cmake/cosim-client.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# Installs the headers and a CMake package: find_package(gyro CONFIG REQUIRED); the C API
# (libgyro, shared and static: gyro::c, gyro::c_static) also for pkg-config.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS gyro_exact gyro_model gyro_component gyro_port gyro_examples gyro_hil_stub ${GYRO_C_TARGETS}
        EXPORT gyroTargets)
install(DIRECTORY component/exact/include/ component/report/include/ component/flight/include/ port/include/
                  hil_stub/include/ examples/include/ c/include/ ${CMAKE_BINARY_DIR}/c/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The C API for pkg-config (pkg-config --cflags --libs gyro).
install(FILES ${CMAKE_BINARY_DIR}/c/gyro.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
install(EXPORT gyroTargets NAMESPACE gyro:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gyro)
configure_package_config_file(cmake/gyroConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/gyroConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gyro)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/gyroConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/gyroConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/gyroConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gyro)

# Shared part of the Linux cross toolchain files (aarch64-linux-gnu.cmake,
# arm-linux-gnueabihf.cmake, powerpc-linux-gnu.cmake, riscv64-linux-gnu.cmake).
# The including file sets GYRO_TRIPLE, GYRO_PROCESSOR, GYRO_CPU_FLAGS and GYRO_QEMU first.
#
# Compiler: Debian's g++-<triple> cross compiler (GCC 12), with the target's libc and
# libstdc++ under /usr/<triple>. Emulator: qemu-user (Debian package qemu-user), run with
# -L /usr/<triple> so it finds the target's dynamic loader (binfmt_misc is not needed).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR ${GYRO_PROCESSOR})

set(CMAKE_C_COMPILER   ${GYRO_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${GYRO_TRIPLE}-g++)

# *_FLAGS_INIT only seed the cache: -DCMAKE_CXX_FLAGS=... on the command line replaces
# them. Add flags through the CXXFLAGS environment variable or target_*() instead.
set(CMAKE_C_FLAGS_INIT   "${GYRO_CPU_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${GYRO_CPU_FLAGS}")

# Target libraries and headers come from the cross root only; programs from the host.
# Eigen (header-only) is found on the host by the project's
# find_package(Eigen3 ... CMAKE_FIND_ROOT_PATH_BOTH).
set(CMAKE_FIND_ROOT_PATH /usr/${GYRO_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# ctest and gtest_discover_tests run target executables through qemu-user.
# The if() lets -DCMAKE_CROSSCOMPILING_EMULATOR=... override it.
if(NOT CMAKE_CROSSCOMPILING_EMULATOR)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${GYRO_QEMU} -L /usr/${GYRO_TRIPLE})
endif()

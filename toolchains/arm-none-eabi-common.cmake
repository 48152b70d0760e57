# Shared part of the bare-metal Arm toolchain files (arm-none-eabi-cortex-m4f.cmake,
# arm-none-eabi-cortex-m7.cmake). The including file sets GYRO_ARM_CPU_FLAGS and
# GYRO_QEMU_MACHINE first.
#
# Compiler: Debian package gcc-arm-none-eabi (GCC 12.2.rel1); C library: newlib 3.3.0
# (libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib). Emulator: qemu-system-arm.
#
# Only the compiler, the CPU/FPU/ABI and the emulator are set here. Language and library
# choices of an image (-fno-exceptions, newlib-nano, semihosting, linker script) belong to
# the project that builds it (firmware/CMakeLists.txt).
#
# CMAKE_SYSTEM_NAME Generic makes the project set GYRO_BARE_METAL: it then builds the
# libraries and the firmware images only (no host tools, no GoogleTest).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER   arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
# CMake finds ar/objcopy/objdump/nm itself, not size.
find_program(CMAKE_SIZE arm-none-eabi-size)

# No operating system to link against: try_compile() builds a static library instead.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# *_FLAGS_INIT only seed the cache. Passing -DCMAKE_CXX_FLAGS=... on the command line
# REPLACES them (CPU flags lost: soft-float objects, link error "uses VFP register
# arguments"). Add flags through the CXXFLAGS environment variable or target_*() instead.
set(CMAKE_C_FLAGS_INIT   "${GYRO_ARM_CPU_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${GYRO_ARM_CPU_FLAGS}")
set(CMAKE_ASM_FLAGS_INIT "${GYRO_ARM_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${GYRO_ARM_CPU_FLAGS}")

# ctest runs an image as <emulator...> <image.elf>; output and exit status go through
# semihosting. The if() lets -DCMAKE_CROSSCOMPILING_EMULATOR=... override it.
if(NOT CMAKE_CROSSCOMPILING_EMULATOR)
  set(CMAKE_CROSSCOMPILING_EMULATOR
      qemu-system-arm -M ${GYRO_QEMU_MACHINE} -nographic -monitor none -serial none
      -semihosting-config enable=on,target=native -kernel)
endif()

# No CMAKE_FIND_ROOT_PATH: find_package(Eigen3 CONFIG) finds the host's header-only copy,
# which is what a bare-metal build wants. Programs (size, nm, qemu) come from the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)

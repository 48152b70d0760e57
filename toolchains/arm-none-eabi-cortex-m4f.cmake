# Bare-metal Arm Cortex-M4F (e.g. STM32F4, SAM4E, Kinetis K): ARMv7E-M, Thumb-2.
#   CPU:    cortex-m4
#   FPU:    FPv4-SP-D16: single precision only; double is emulated in software (libgcc
#           __aeabi_d*), tens of times slower
#   ABI:    AAPCS hard-float (-mfloat-abi=hard: float arguments in s0-s15)
#   Scalar: float (gyro::*<float>); keep double out of the tick (-Wdouble-promotion)
#   Compiler: arm-none-eabi-gcc / arm-none-eabi-g++, Debian package gcc-arm-none-eabi
#           (+ libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib)
#   Runs on: qemu-system-arm -M mps2-an386 (Arm MPS2 FPGA image AN386, a Cortex-M4 with FPU)
#           (Debian package qemu-system-arm). The FPU is off at reset: the startup code must
#           enable CP10/CP11 in CPACR before the first floating-point instruction
#           (firmware/startup.c does).
#   Use:    cmake --preset cortex-m4f   (or -DCMAKE_TOOLCHAIN_FILE=toolchains/arm-none-eabi-cortex-m4f.cmake)
set(GYRO_ARM_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
set(GYRO_QEMU_MACHINE mps2-an386)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)

# Bare-metal Arm Cortex-M7 with double-precision FPU (e.g. STM32F7/H7, SAM V71/E70,
# i.MX RT): ARMv7E-M, Thumb-2.
#   CPU:    cortex-m7
#   FPU:    FPv5-D16: single and double precision in hardware (also fused multiply-add)
#   ABI:    AAPCS hard-float (-mfloat-abi=hard)
#   Scalar: double (float also runs in hardware)
#   Compiler: arm-none-eabi-gcc / arm-none-eabi-g++, Debian package gcc-arm-none-eabi
#           (+ libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib)
#   Runs on: qemu-system-arm -M mps2-an500 (Arm MPS2 FPGA image AN500, a Cortex-M7 with
#           FPv5-D16) (Debian package qemu-system-arm). The startup code must enable the FPU.
#   Use:    cmake --preset cortex-m7   (or -DCMAKE_TOOLCHAIN_FILE=toolchains/arm-none-eabi-cortex-m7.cmake)
set(GYRO_ARM_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
set(GYRO_QEMU_MACHINE mps2-an500)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)

# Linux on 32-bit Arm (ARMv7-A; Cortex-A9, e.g. Zynq-7000 APU, i.MX 6), little-endian.
#   CPU:    cortex-a9
#   FPU:    VFPv3 + NEON (-mfpu=neon-fp16); VFPv3 has no fused multiply-add (GCC's vmla
#           rounds twice, like separate * and +)
#   ABI:    EABI hard-float (gnueabihf: float/double arguments in VFP registers), ILP32
#   Scalar: double (VFPv3-D32 is a full double-precision unit)
#   Compiler: arm-linux-gnueabihf-g++, Debian package g++-arm-linux-gnueabihf
#   Runs on: qemu-arm -cpu cortex-a9 -L /usr/arm-linux-gnueabihf (Debian package qemu-user)
#   Use:    cmake --preset armhf
set(GYRO_TRIPLE arm-linux-gnueabihf)
set(GYRO_PROCESSOR arm)
set(GYRO_CPU_FLAGS "-mcpu=cortex-a9 -mfpu=neon-fp16 -mfloat-abi=hard")
set(GYRO_QEMU qemu-arm -cpu cortex-a9)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)

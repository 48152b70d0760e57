# Linux on 64-bit Arm (ARMv8-A; Cortex-A53/A72, e.g. Zynq UltraScale+ APU, i.MX 8, NXP
# LS10xx), little-endian.
#   CPU:    cortex-a53 (-mcpu=cortex-a53: ARMv8-A baseline, runs on any later core)
#   FPU:    Armv8 FP + Advanced SIMD (NEON), always present; fused multiply-add (fmadd)
#   ABI:    LP64, AAPCS64 (hard float by definition)
#   Scalar: double
#   Compiler: aarch64-linux-gnu-g++, Debian package g++-aarch64-linux-gnu
#   Runs on: qemu-aarch64 -cpu cortex-a53 -L /usr/aarch64-linux-gnu (Debian package qemu-user)
#   Note:   GCC contracts a*b+c into fmadd by default even with -std=c++17 (only C's ISO
#           modes turn -ffp-contract off), so results can differ from x86-64 in the last bits.
#   Use:    cmake --preset aarch64
set(GYRO_TRIPLE aarch64-linux-gnu)
set(GYRO_PROCESSOR aarch64)
set(GYRO_CPU_FLAGS "-mcpu=cortex-a53")
set(GYRO_QEMU qemu-aarch64 -cpu cortex-a53)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)

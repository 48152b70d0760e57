# Linux on 64-bit RISC-V (RV64GC application cores, e.g. SiFive U74, the NOEL-V/GR765
# class of space processors), little-endian.
#   CPU:    rv64gc (-march=rv64gc: IMAFD + compressed; Debian's baseline)
#   FPU:    F and D extensions: single and double precision, fused multiply-add (fmadd.d)
#   ABI:    lp64d (-mabi=lp64d: doubles passed in FP registers)
#   Scalar: double
#   Compiler: riscv64-linux-gnu-g++, Debian package g++-riscv64-linux-gnu
#   Runs on: qemu-riscv64 -L /usr/riscv64-linux-gnu (Debian package qemu-user)
#   Note:   Eigen has no RISC-V SIMD path (EIGEN_MAX_STATIC_ALIGN_BYTES is 0 here, 16 on
#           the other targets): layouts of structs holding Eigen types differ. GCC contracts
#           a*b+c into fmadd by default (also with -std=c++17).
#   Use:    cmake --preset riscv64
set(GYRO_TRIPLE riscv64-linux-gnu)
set(GYRO_PROCESSOR riscv64)
set(GYRO_CPU_FLAGS "-march=rv64gc -mabi=lp64d")
set(GYRO_QEMU qemu-riscv64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)

# Linux on 32-bit PowerPC, big-endian (classic PowerPC 750 family: the RAD750 of many
# spacecraft and missiles; also e300/e600-class cores).
#   CPU:    750 (-mcpu=750: PowerPC 32-bit with hardware FPU, no AltiVec)
#   FPU:    classic PowerPC double-precision FPU; fused multiply-add (fmadd)
#   ABI:    32-bit SVR4 PowerPC ABI, hard float, BIG-endian
#   Scalar: double
#   Compiler: powerpc-linux-gnu-g++, Debian package g++-powerpc-linux-gnu
#   Runs on: qemu-ppc -cpu 750 -L /usr/powerpc-linux-gnu (Debian package qemu-user)
#   AltiVec: Eigen 3.4.0's AltiVec code does not compile for 32-bit PowerPC without VSX
#           (__builtin_vsx_cmpge_4si requires -mvsx). For an AltiVec core (e600/7450) add
#           -maltivec together with -DEIGEN_DONT_VECTORIZE, and run qemu-ppc -cpu 7450.
#   Note:   GCC contracts a*b+c into fmadd by default (also with -std=c++17).
#   Use:    cmake --preset ppc
set(GYRO_TRIPLE powerpc-linux-gnu)
set(GYRO_PROCESSOR powerpc)
set(GYRO_CPU_FLAGS "-mcpu=750")
set(GYRO_QEMU qemu-ppc -cpu 750)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)

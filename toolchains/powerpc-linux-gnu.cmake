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
#   QEMU:   glibc 2.36 executes POWER9's mffscrn/mffsl on every CPU (atan2, long double
#           functions, ...); older hardware decodes them as mffs, QEMU 7.2 raises SIGILL.
#           The emulator command therefore preloads qemu-ppc-mffs.c (built here, into the
#           build directory), which executes them as mffs like the hardware does.
#   Use:    cmake --preset ppc
set(GYRO_TRIPLE powerpc-linux-gnu)
set(GYRO_PROCESSOR powerpc)
set(GYRO_CPU_FLAGS "-mcpu=750")
set(GYRO_QEMU qemu-ppc -cpu 750)
if(NOT CMAKE_CROSSCOMPILING_EMULATOR)
  set(_gyro_mffs_so ${CMAKE_BINARY_DIR}/qemu-ppc-mffs.so)
  if(NOT EXISTS ${_gyro_mffs_so})
    execute_process(
      COMMAND ${GYRO_TRIPLE}-gcc -O2 -shared -fPIC -o ${_gyro_mffs_so}
              ${CMAKE_CURRENT_LIST_DIR}/qemu-ppc-mffs.c
      RESULT_VARIABLE _gyro_mffs_rc)
    if(NOT _gyro_mffs_rc EQUAL 0)
      message(FATAL_ERROR "could not build ${_gyro_mffs_so}")
    endif()
  endif()
  list(APPEND GYRO_QEMU -E LD_PRELOAD=${_gyro_mffs_so})
endif()
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)

# Warnings for our own targets only (toolchain files set the CPU, never policy).
# -Wdouble-promotion keeps float code float: a single-precision FPU has no double unit.
add_library(gyro_warnings INTERFACE)
target_compile_options(gyro_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wsign-conversion -Wdouble-promotion -Wcast-align -Wnon-virtual-dtor
    -Wold-style-cast -Wnull-dereference>)
# GCC 12 at -O3 (a plain Release build) reports -Wrestrict inside std::string's inlined
# copies ("memcpy accessing 9223372036854775810 or more bytes", GCC bugs 105329, 105651; gone
# in GCC 13) wherever a string literal is added to a string: off before GCC 13. The flight
# libraries copy no strings; a real overlap in a copy is still caught at run time by
# AddressSanitizer (scripts/sanitize.sh).
target_compile_options(gyro_warnings INTERFACE
  $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>)
# Warnings are errors in the presets and CI (CMakePresets.json), not by default: a user's own
# build type or compiler must not fail on a warning we do not see.
option(GYRO_WERROR "Treat warnings as errors" OFF)
if(GYRO_WERROR)
  target_compile_options(gyro_warnings INTERFACE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
endif()

# The flight rules: no exceptions, no RTTI (applied to code that must honour them).
add_library(gyro_flight_rules INTERFACE)
target_compile_options(gyro_flight_rules INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-fno-exceptions -fno-rtti>)

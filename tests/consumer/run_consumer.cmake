# ctest script: install gyro into a scratch prefix, then configure, build and run a
# consumer project against it with find_package(gyro CONFIG REQUIRED), and build the C example
# with pkg-config alone (where pkg-config is found).
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK}/prefix"
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${WORK}/build"
                        "-DCMAKE_PREFIX_PATH=${WORK}/prefix" -DCMAKE_BUILD_TYPE=Release
                        "-DGYRO_C_EXAMPLE=${C_EXAMPLE}"
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed: ${rc}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed: ${rc}")
endif()
set(programs "${WORK}/build/consumer" "${WORK}/build/consumer_c" "${WORK}/build/consumer_c_static")

find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
  file(GLOB pc_dirs "${WORK}/prefix/lib*/pkgconfig" "${WORK}/prefix/lib*/*/pkgconfig")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PKG_CONFIG_PATH=${pc_dirs}" "${PKG_CONFIG}" --cflags --libs gyro
                  RESULT_VARIABLE rc OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(rc)
    message(FATAL_ERROR "pkg-config --cflags --libs gyro failed: ${rc}")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  string(REGEX MATCH "-L[^ ;]+" libdir "${flags}")
  string(SUBSTRING "${libdir}" 2 -1 libdir)
  execute_process(COMMAND "${C_COMPILER}" -std=c99 -Wall -Wextra -pedantic -Werror "${C_EXAMPLE}" ${flags}
                          "-Wl,-rpath,${libdir}" -o "${WORK}/consumer_pkg_config"
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "building the C example with pkg-config's flags (${flags}) failed: ${rc}")
  endif()
  list(APPEND programs "${WORK}/consumer_pkg_config")
endif()

foreach(p IN LISTS programs)
  execute_process(COMMAND "${p}" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(rc)
    message(FATAL_ERROR "${p} failed: ${rc}")
  endif()
  message(STATUS "${p}: ${out}")
endforeach()

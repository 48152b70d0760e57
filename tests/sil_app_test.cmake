# Runs the gyro_sil executable as a user would (ctest: sil_app_plot, sil_app_bad_scenario,
# sil_app_no_gnuplot).
#   cmake -DEXE=<gyro_sil> -DSOURCE=<repo> -DWORK=<scratch dir> -DMODE=plot|bad|no_gnuplot -P sil_app_test.cmake
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

if(MODE STREQUAL "plot")
  # The README's run: report_sample.json -> CSV and PNG (output directory created on demand).
  set(csv "${WORK}/out/report_sample.csv")
  set(png "${WORK}/out/report_sample.png")
  execute_process(COMMAND "${EXE}" "${SOURCE}/scenarios/report_sample.json" -o "${csv}" --plot "${png}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "gyro_sil exited with ${rc}:\n${out}\n${err}")
  endif()
  foreach(f IN ITEMS "${csv}" "${png}")
    if(NOT EXISTS "${f}")
      message(FATAL_ERROR "missing ${f}\n${err}")
    endif()
    file(SIZE "${f}" size)
    if(size EQUAL 0)
      message(FATAL_ERROR "empty ${f}")
    endif()
  endforeach()
  file(READ "${png}" magic LIMIT 8 HEX)
  if(NOT magic STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${png} is not a PNG (starts with ${magic})")
  endif()
  file(STRINGS "${csv}" rows)
  list(LENGTH rows n)
  if(NOT n EQUAL 803)  # header + ticks 0..801
    message(FATAL_ERROR "${csv}: ${n} lines, expected 803")
  endif()
  message(STATUS "gyro_sil wrote ${csv} and ${png} (${size} bytes); stderr:\n${err}")
  # A fault scenario's plot (every panel, the raster, the markers): gnuplot draws it without a
  # warning (an empty series or a datablock it cannot read would be one).
  execute_process(COMMAND "${EXE}" "${SOURCE}/scenarios/fault_saturated_torquer.json" -o "${WORK}/fault.csv"
                          --plot "${WORK}/fault.png" -q
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK}/fault.png")
    message(FATAL_ERROR "gyro_sil exited with ${rc} on fault_saturated_torquer.json:\n${err}")
  endif()
  string(FIND "${err}" "warning" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "gnuplot warned on fault_saturated_torquer.json's plot:\n${err}")
  endif()

elseif(MODE STREQUAL "bad")
  set(bad "${SOURCE}/tests/data/bad_scenarios/missing_field.json")
  execute_process(COMMAND "${EXE}" "${bad}" -o "${WORK}/bad.csv"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "expected exit status 2 for ${bad}, got ${rc}:\n${err}")
  endif()
  string(FIND "${err}" "missing_field.json: gyro.rotor.pitch_inertia: missing required field" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the message does not name file, field and reason:\n${err}")
  endif()
  if(EXISTS "${WORK}/bad.csv")
    message(FATAL_ERROR "a refused scenario left a CSV behind")
  endif()
  # A bad command line is exit status 2 as well.
  execute_process(COMMAND "${EXE}" "${SOURCE}/scenarios/report_sample.json" --precision half
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "expected exit status 2 for --precision half, got ${rc}:\n${err}")
  endif()

elseif(MODE STREQUAL "no_gnuplot")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env GNUPLOT=/nonexistent/bin/gnuplot
                          "${EXE}" "${SOURCE}/scenarios/report_sample.json" -o "${WORK}/a.csv" --plot "${WORK}/a.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 3)
    message(FATAL_ERROR "expected exit status 3 without gnuplot, got ${rc}:\n${err}")
  endif()
  string(FIND "${err}" "gnuplot not found" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "no clear message without gnuplot:\n${err}")
  endif()
  if(NOT EXISTS "${WORK}/a.csv")
    message(FATAL_ERROR "the CSV should still be written when only the plot fails")
  endif()

else()
  message(FATAL_ERROR "MODE must be plot, bad or no_gnuplot")
endif()

# Runs gyro_campaign as a user would (ctest: campaign_app_parallel, _rerun, _refusals).
#   cmake -DEXE=<gyro_campaign> -DSIL=<gyro_sil> -DSOURCE=<repo> -DWORK=<scratch dir>
#         -DMODE=parallel|rerun|refusals [-DMPIEXEC=<mpiexec>] -P campaign_app_test.cmake
#
# parallel: the small campaign (tests/data/campaigns/small.json: every distribution, float
#   and double runs, refused runs, random faults) with 1 and 2 threads, as 3 shards merged,
#   and, when built with MPI, under mpiexec -np 1, 2 and 3: every output byte-identical.
# rerun: --run K reproduces run K's row exactly, and its scenario run by gyro_sil gives its
#   time history byte for byte.
# refusals: bad command lines, outputs that would overwrite inputs, shards that do not make
#   one campaign.
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(campaign "${SOURCE}/tests/data/campaigns/small.json")
set(outputs runs.csv summary.md campaign.json manifest.json)

function(run_ok)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit status ${rc} from:\n${ARGN}\n${out}\n${err}")
  endif()
endfunction()

# Runs the command, expects exit status `status` and `text` in its standard error.
function(run_refused status text)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL status)
    message(FATAL_ERROR "expected exit status ${status}, got ${rc} from:\n${ARGN}\n${err}")
  endif()
  string(FIND "${err}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected \"${text}\" in the message of:\n${ARGN}\ngot:\n${err}")
  endif()
endfunction()

function(same_outputs reference dir)
  foreach(f IN LISTS outputs)
    file(SHA256 "${reference}/${f}" a)
    file(SHA256 "${dir}/${f}" b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "${dir}/${f} differs from ${reference}/${f}")
    endif()
  endforeach()
  message(STATUS "${dir}: byte-identical to ${reference}")
endfunction()

# The CSV row of run `k` (0-based) of a runs.csv.
function(row_of file k var)
  file(STRINGS "${file}" lines)
  math(EXPR line "${k} + 1")
  list(GET lines ${line} row)
  set(${var} "${row}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "parallel")
  set(ref "${WORK}/threads1")
  run_ok("${EXE}" run "${campaign}" -o "${ref}" -j 1 --no-plots -q)
  file(STRINGS "${ref}/runs.csv" rows)
  list(LENGTH rows n)
  if(NOT n EQUAL 31)
    message(FATAL_ERROR "${ref}/runs.csv: ${n} lines, expected a header and 30 runs")
  endif()
  foreach(status IN ITEMS ",ok,true," ",refused,false," ",ok,false,")
    string(FIND "${rows}" "${status}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "the small campaign should have a run with \"${status}\" (it exercises every outcome)")
    endif()
  endforeach()

  run_ok("${EXE}" run "${campaign}" -o "${WORK}/threads2" -j 2 --no-plots -q)
  same_outputs("${ref}" "${WORK}/threads2")

  foreach(i 1 2 3)
    run_ok("${EXE}" run "${campaign}" -o "${WORK}/shard${i}" --shard ${i}/3 -j 2 --no-plots -q)
  endforeach()
  # Shards given in any order.
  run_ok("${EXE}" merge "${WORK}/shard3" "${WORK}/shard1" "${WORK}/shard2" -o "${WORK}/merged" --no-plots -q)
  same_outputs("${ref}" "${WORK}/merged")

  if(MPIEXEC)
    # --oversubscribe: more ranks than cores (CI machines may have fewer than 3). Under
    # AddressSanitizer the leak check is off for the ranks: Open MPI does not free what its
    # start-up allocates (in plugins it has unloaded by then, beyond suppression); the threads
    # and shards above run the same code of ours with the leak check on.
    set(mpi "${CMAKE_COMMAND}" -E env "ASAN_OPTIONS=$ENV{ASAN_OPTIONS}:detect_leaks=0" "${MPIEXEC}")
    foreach(np 1 2 3)
      run_ok(${mpi} -np ${np} --oversubscribe "${EXE}" run "${campaign}" -o "${WORK}/mpi${np}" --no-plots -q)
      same_outputs("${ref}" "${WORK}/mpi${np}")
    endforeach()
    run_ok(${mpi} -np 2 --oversubscribe "${EXE}" run "${campaign}" -o "${WORK}/mpi2_threads2" -j 2 --no-plots -q)
    same_outputs("${ref}" "${WORK}/mpi2_threads2")
  else()
    message(STATUS "gyro_campaign built without MPI: the mpiexec runs are skipped")
  endif()

  # With plots: the summary shows them and they are PNG images.
  run_ok("${EXE}" run "${campaign}" -o "${WORK}/plots" -j 2 -q)
  foreach(png latency_cdf histograms)
    file(READ "${WORK}/plots/plots/${png}.png" magic LIMIT 8 HEX)
    if(NOT magic STREQUAL "89504e470d0a1a0a")
      message(FATAL_ERROR "plots/${png}.png is not a PNG")
    endif()
  endforeach()
  file(READ "${WORK}/plots/summary.md" summary)
  string(FIND "${summary}" "![plots/latency_cdf.png](plots/latency_cdf.png)" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the summary does not show the latency plot")
  endif()

elseif(MODE STREQUAL "rerun")
  set(all "${WORK}/all")
  run_ok("${EXE}" run "${campaign}" -o "${all}" -j 2 --no-plots -q)
  file(STRINGS "${all}/runs.csv" rows)
  # One run of each kind the campaign has: passed, failed a criterion, refused; and a float one.
  set(picked "")
  foreach(pattern IN ITEMS ",ok,true," ",ok,false," ",refused," ",ok,.*,float,")
    foreach(k RANGE 0 29)
      math(EXPR line "${k} + 1")
      list(GET rows ${line} row)
      if(row MATCHES "^${k},[0-9]+${pattern}")
        list(APPEND picked ${k})
        break()
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES picked)
  list(LENGTH picked n)
  if(n LESS 3)
    message(FATAL_ERROR "expected a passed, a failed and a refused run in ${all}/runs.csv, found runs ${picked}")
  endif()
  foreach(k IN LISTS picked)
    set(dir "${WORK}/run${k}")
    run_ok("${EXE}" run "${campaign}" --run ${k} -o "${dir}" -q)
    row_of("${all}/runs.csv" ${k} expected)
    row_of("${dir}/run-${k}-metrics.csv" 0 got)
    if(NOT got STREQUAL expected)
      message(FATAL_ERROR "--run ${k} gave\n${got}\nthe campaign had\n${expected}")
    endif()
    if(expected MATCHES ",refused,")
      if(EXISTS "${dir}/run-${k}.csv")
        message(FATAL_ERROR "a refused run has no time history, yet run-${k}.csv exists")
      endif()
      continue()
    endif()
    # The run's scenario through gyro_sil: the same time history, byte for byte.
    run_ok("${SIL}" "${dir}/run-${k}.json" -o "${dir}/sil.csv" -q)
    file(SHA256 "${dir}/run-${k}.csv" a)
    file(SHA256 "${dir}/sil.csv" b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "gyro_sil on run-${k}.json does not give run-${k}.csv")
    endif()
    file(READ "${dir}/run-${k}.png" magic LIMIT 8 HEX)
    if(NOT magic STREQUAL "89504e470d0a1a0a")
      message(FATAL_ERROR "run-${k}.png is not a PNG")
    endif()
    message(STATUS "--run ${k}: the same row, and gyro_sil gives the same time history")
  endforeach()

elseif(MODE STREQUAL "refusals")
  run_refused(2 "bad_runs.json: runs: must be an integer" "${EXE}" run "${SOURCE}/tests/data/campaigns/bad_runs.json" -o "${WORK}/x")
  if(EXISTS "${WORK}/x/runs.csv")
    message(FATAL_ERROR "a refused campaign wrote runs.csv")
  endif()
  run_refused(2 "no_such.json: (file): cannot open" "${EXE}" run "${WORK}/no_such.json" -o "${WORK}/x")
  run_refused(2 "--shard 4/3: expected I/N with 1 <= I <= N" "${EXE}" run "${campaign}" --shard 4/3 -o "${WORK}/x")
  if(EXISTS "${WORK}/x")
    message(FATAL_ERROR "a refused command line created the output directory")
  endif()
  run_refused(2 "--shard 1-3: expected I/N" "${EXE}" run "${campaign}" --shard 1-3 -o "${WORK}/x")
  run_refused(2 "more shards than the campaign's 30 runs" "${EXE}" run "${campaign}" --shard 1/31 -o "${WORK}/x")
  run_refused(2 "--run 30: the campaign has runs 0 to 29" "${EXE}" run "${campaign}" --run 30 -o "${WORK}/x")
  run_refused(2 "--run and --shard do not go together" "${EXE}" run "${campaign}" --run 1 --shard 1/2 -o "${WORK}/x")
  run_refused(2 "" "${EXE}" run "${campaign}")  # no -o

  # An output that would overwrite an input: the campaign itself, named like an output.
  file(MAKE_DIRECTORY "${WORK}/clash")
  file(COPY_FILE "${SOURCE}/tests/data/campaigns/small.json" "${WORK}/clash/campaign.json")
  file(READ "${WORK}/clash/campaign.json" before)
  string(REPLACE "../../../scenarios/" "${SOURCE}/scenarios/" moved "${before}")
  file(WRITE "${WORK}/clash/campaign.json" "${moved}")
  run_refused(2 "would overwrite the input" "${EXE}" run "${WORK}/clash/campaign.json" -o "${WORK}/clash")
  file(READ "${WORK}/clash/campaign.json" after)
  if(NOT after STREQUAL moved)
    message(FATAL_ERROR "the input campaign was changed")
  endif()

  # A directory gyro_campaign did not write: its files are not replaced.
  file(WRITE "${WORK}/users/runs.csv" "the user's own table\n")
  run_refused(2 "runs.csv exists, in a directory gyro_campaign did not write"
              "${EXE}" run "${campaign}" -o "${WORK}/users" --no-plots -q)
  file(READ "${WORK}/users/runs.csv" users)
  if(NOT users STREQUAL "the user's own table\n")
    message(FATAL_ERROR "the user's runs.csv was changed")
  endif()
  # One it wrote: run again into it, and --run K beside the campaign's outputs.
  run_ok("${EXE}" run "${campaign}" -o "${WORK}/again" --no-plots -q)
  run_ok("${EXE}" run "${campaign}" -o "${WORK}/again" --no-plots -q)
  run_ok("${EXE}" run "${campaign}" --run 3 -o "${WORK}/again" --no-plots -q)

  # Shards: a missing one, an overlap, another campaign, the output among the inputs.
  foreach(i 1 2)
    run_ok("${EXE}" run "${campaign}" -o "${WORK}/s${i}" --shard ${i}/2 --no-plots -q)
  endforeach()
  run_refused(2 "runs 15 to 29 are in none of the directories (a shard missing?)"
              "${EXE}" merge "${WORK}/s1" -o "${WORK}/m")
  run_refused(2 "the shards overlap" "${EXE}" merge "${WORK}/s1" "${WORK}/s2" "${WORK}/s1" -o "${WORK}/m")
  run_refused(2 "is one of the inputs" "${EXE}" merge "${WORK}/s1" "${WORK}/s2" -o "${WORK}/s1")
  file(READ "${WORK}/s2/campaign.json" other)
  string(REPLACE "\"seed\": 7" "\"seed\": 8" other "${other}")
  file(WRITE "${WORK}/s2/campaign.json" "${other}")
  run_refused(2 "not the campaign of" "${EXE}" merge "${WORK}/s1" "${WORK}/s2" -o "${WORK}/m")
  run_refused(2 "cannot open" "${EXE}" merge "${WORK}/s1" "${WORK}/none" -o "${WORK}/m")

else()
  message(FATAL_ERROR "MODE must be parallel, rerun or refusals")
endif()

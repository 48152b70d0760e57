# Runs gyro_campaign as a user would (ctest: campaign_app_parallel, _rerun, _refusals,
# _tracking).
#   cmake -DEXE=<gyro_campaign> -DSIL=<gyro_sil> -DSOURCE=<repo> -DWORK=<scratch dir>
#         -DMODE=parallel|rerun|refusals|tracking [-DMPIEXEC=<mpiexec>] -P campaign_app_test.cmake
#
# parallel: the small campaign (tests/data/campaigns/small.json: every distribution, float
#   and double runs, refused runs, random faults) with 1 and 2 threads, as 3 shards merged,
#   and, when built with MPI, under mpiexec -np 1, 2 and 3: every output byte-identical;
#   --runs 12: the first 12 rows of it.
# rerun: --run K reproduces run K's row exactly, and its scenario run by gyro_sil gives its
#   time history byte for byte.
# refusals: bad command lines, outputs that would overwrite inputs, shards that do not make
#   one campaign; and every host input bounded, every user file safe (docs/campaigns.md):
#   inputs that never end or nest without end, too many runs or threads, option values that
#   are empty, negative or not numbers, weights whose sum overflows, symbolic links and
#   read-only files in the output directory, a directory in use
#   (tests/campaign_lock_signals.sh: the lock under SIGINT, SIGTERM and SIGKILL), control
#   characters in messages.
# tracking: the shipped campaigns/track_crossing.json, its first 100 runs.
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

# Runs the command, expects exit status `status` and `text` in its standard error, within
# 60 s (a refusal is prompt).
function(run_refused status text)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
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

  # --runs N: the first N runs, each row the same as in the whole campaign; the outputs say N runs.
  run_ok("${EXE}" run "${campaign}" --runs 12 -o "${WORK}/first12" -j 2 --no-plots -q)
  file(READ "${WORK}/first12/runs.csv" first)
  file(READ "${ref}/runs.csv" whole)
  string(FIND "${whole}" "${first}" at)
  file(STRINGS "${WORK}/first12/runs.csv" first_rows)
  list(LENGTH first_rows first_n)
  if(NOT at EQUAL 0 OR NOT first_n EQUAL 13)
    message(FATAL_ERROR "--runs 12: the rows differ from the first 12 of the whole campaign")
  endif()
  file(READ "${WORK}/first12/campaign.json" resolved)
  string(JSON n GET "${resolved}" runs)
  if(NOT n EQUAL 12)
    message(FATAL_ERROR "--runs 12: campaign.json says ${n} runs")
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
  run_refused(2 "runs: the first 31 runs: expected 1 to the campaign's 30" "${EXE}" run "${campaign}" --runs 31 -o "${WORK}/x")
  run_refused(2 "--runs 0: run at least one" "${EXE}" run "${campaign}" --runs 0 -o "${WORK}/x")
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

  # ---- Every host input bounded.
  # Inputs that never end: the campaign file, its base scenario, a shard's manifest.
  run_refused(2 "/dev/zero: (file): gave more than the limit of 4194304 bytes for a campaign file (stopped reading)"
              "${EXE}" run /dev/zero -o "${WORK}/b")
  set(scenario "${SOURCE}/scenarios/seeker_slew.json")
  set(tiny "\"base\": \"${scenario}\", \"seed\": 1")
  file(WRITE "${WORK}/zero_base.json" "{ \"base\": \"/dev/zero\", \"runs\": 2, \"seed\": 1 }")
  run_refused(2 "zero_base.json: base: the base scenario \"/dev/zero\": gave more than the limit of 1048576 bytes for a scenario"
              "${EXE}" run "${WORK}/zero_base.json" -o "${WORK}/b")
  # Too many runs: refused before the base is read (here /dev/zero) or anything allocated.
  file(WRITE "${WORK}/many.json" "{ \"base\": \"/dev/zero\", \"runs\": 100000000, \"seed\": 1 }")
  run_refused(2 "many.json: runs: must be an integer in [1, 1000000], got 100000000"
              "${EXE}" run "${WORK}/many.json" -o "${WORK}/b")
  foreach(i 1 2)
    run_ok("${EXE}" run "${campaign}" -o "${WORK}/z${i}" --shard ${i}/2 --no-plots -q)
  endforeach()
  file(REMOVE "${WORK}/z2/manifest.json")
  file(CREATE_LINK /dev/zero "${WORK}/z2/manifest.json" SYMBOLIC)
  run_refused(2 "z2/manifest.json: gave more than the limit of 65536 bytes for a manifest (stopped reading)"
              "${EXE}" merge "${WORK}/z1" "${WORK}/z2" -o "${WORK}/zm")
  # Threads: a documented bound, refused with a message (it aborted the process).
  run_refused(2 "-j 100000: more than the limit of 1024" "${EXE}" run "${campaign}" -o "${WORK}/b" -j 100000)
  # Option values that are empty, negative or not numbers: refused, never "no limit" or unset.
  run_refused(2 "-j -1: expected a whole number from 0 to 1024" "${EXE}" run "${campaign}" -o "${WORK}/b" -j -1)
  run_refused(2 "-j nan: expected a whole number" "${EXE}" run "${campaign}" -o "${WORK}/b" -j nan)
  run_refused(2 "-j inf: expected a whole number" "${EXE}" run "${campaign}" -o "${WORK}/b" -j inf)
  run_refused(2 "--run -1: expected a whole number from 0 to 999999" "${EXE}" run "${campaign}" -o "${WORK}/b" --run -1)
  # An empty value (given directly: a function's ARGN drops empty arguments).
  foreach(option -j --run --shard -o merge)
    if(option STREQUAL "-o")
      execute_process(COMMAND "${EXE}" run "${campaign}" -o "" RESULT_VARIABLE rc ERROR_VARIABLE err)
      set(text "-o is empty")
    elseif(option STREQUAL "merge")
      execute_process(COMMAND "${EXE}" merge "${WORK}/z1" "" -o "${WORK}/b" RESULT_VARIABLE rc ERROR_VARIABLE err)
      set(text "merge: a directory is named by an empty string")
    else()
      execute_process(COMMAND "${EXE}" run "${campaign}" -o "${WORK}/b" ${option} "" RESULT_VARIABLE rc ERROR_VARIABLE err)
      set(text "${option} is empty")
    endif()
    string(FIND "${err}" "${text}" at)
    if(NOT rc EQUAL 2 OR at EQUAL -1)
      message(FATAL_ERROR "an empty ${option}: exit status ${rc}, expected 2 and \"${text}\":\n${err}")
    endif()
  endforeach()
  if(EXISTS "${WORK}/b")
    message(FATAL_ERROR "a refused command line created the output directory")
  endif()
  # Choice weights whose sum overflows: refused up front, naming the field.
  file(WRITE "${WORK}/weights.json" "{ ${tiny}, \"runs\": 2, \"dispersions\": [ { \"path\": \"run.precision\",
    \"distribution\": \"choice\", \"values\": [\"float\", \"double\"], \"weights\": [1e308, 1e308] } ] }")
  run_refused(2 "weights.json: dispersions[0].weights: the weights' total overflows a double at weights[1]"
              "${EXE}" run "${WORK}/weights.json" -o "${WORK}/b")

  # Nesting without end: refused while parsing (10^6 levels overflowed the stack).
  string(REPEAT "[" 100000 deep)
  file(WRITE "${WORK}/deep.json" "{ ${tiny}, \"runs\": 2, \"set\": { \"body.weave\": ${deep} } }")
  run_refused(2 "deep.json: set.body.weave[0][0]" "${EXE}" run "${WORK}/deep.json" -o "${WORK}/b")
  run_refused(2 "[0]: nested deeper than 32 levels" "${EXE}" run "${WORK}/deep.json" -o "${WORK}/b")

  # ---- Every user file safe.
  run_ok("${EXE}" run "${campaign}" -o "${WORK}/mine" -q)
  # A symbolic link in place of plots/: refused before anything runs; the linked file untouched.
  file(WRITE "${WORK}/users_plots/histograms.png" "the user's picture\n")
  file(REMOVE_RECURSE "${WORK}/mine/plots")
  file(CREATE_LINK "${WORK}/users_plots" "${WORK}/mine/plots" SYMBOLIC)
  run_refused(2 "mine/plots\" is a symbolic link: refused, not followed" "${EXE}" run "${campaign}" -o "${WORK}/mine" -q)
  file(READ "${WORK}/users_plots/histograms.png" picture)
  file(GLOB linked RELATIVE "${WORK}/users_plots" "${WORK}/users_plots/*")
  if(NOT picture STREQUAL "the user's picture\n" OR NOT linked STREQUAL "histograms.png")
    message(FATAL_ERROR "the linked directory was written: ${linked}")
  endif()
  file(REMOVE "${WORK}/mine/plots")
  # A read-only output: not replaced.
  file(READ "${WORK}/mine/summary.md" summary_before)
  file(CHMOD "${WORK}/mine/summary.md" PERMISSIONS OWNER_READ GROUP_READ WORLD_READ)
  run_refused(2 "mine/summary.md\" is read-only: not replaced" "${EXE}" run "${campaign}" -o "${WORK}/mine" -q)
  file(READ "${WORK}/mine/summary.md" summary_after)
  if(NOT summary_after STREQUAL summary_before)
    message(FATAL_ERROR "the read-only summary.md was replaced")
  endif()
  file(CHMOD "${WORK}/mine/summary.md" PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
  run_ok("${EXE}" run "${campaign}" -o "${WORK}/mine" -q --no-plots)
  if(EXISTS "${WORK}/mine/.gyro_campaign.lock")
    message(FATAL_ERROR "the lock file outlived the run")
  endif()
  # A directory in use by another run: refused; the lock released on SIGINT, SIGTERM, SIGKILL.
  file(READ "${campaign}" long)
  string(REPLACE "../../../scenarios/" "${SOURCE}/scenarios/" long "${long}")
  string(REPLACE "\"runs\": 30," "\"runs\": 1000000," long "${long}")
  file(WRITE "${WORK}/long.json" "${long}")
  file(MAKE_DIRECTORY "${WORK}/lock")
  execute_process(COMMAND sh "${SOURCE}/tests/campaign_lock_signals.sh" "${EXE}" "${WORK}/long.json" "${WORK}/lock"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "ok\n")
    message(FATAL_ERROR "campaign_lock_signals.sh: exit status ${rc}:\n${out}\n${err}")
  endif()

  # ---- Control characters in messages: escaped, never sent to the terminal raw.
  string(ASCII 27 esc)
  # (JSON escapes the control character; the key read holds it.)
  file(WRITE "${WORK}/control.json" "{ ${tiny}, \"runs\": 2, \"\\u001b[2Jruns\": 1 }")
  run_refused(2 "control.json: \\x1b[2Jruns: unknown key" "${EXE}" run "${WORK}/control.json" -o "${WORK}/b")
  foreach(args IN ITEMS "run;${WORK}/control.json;-o;${WORK}/b" "run;${campaign};-o;${WORK}/b;--shard;1${esc}]0;x/2"
                        "run;${campaign};-o;${WORK}/b;-j;2${esc}[31m" "run;${campaign};-o;${WORK}/b;--bogus${esc}[31m")
    execute_process(COMMAND "${EXE}" ${args} RESULT_VARIABLE rc ERROR_VARIABLE err)
    string(FIND "${err}" "${esc}" raw)
    if(NOT rc EQUAL 2 OR NOT raw EQUAL -1 OR NOT err MATCHES "x1b")
      message(FATAL_ERROR "exit status ${rc}, a raw escape in the message of ${args}:\n${err}")
    endif()
  endforeach()

elseif(MODE STREQUAL "tracking")
  # The shipped tracking campaign's first 100 runs (about 1 s): every run tracks, and the
  # summary gives the pointing and LOS-rate errors' percentiles (docs/campaigns.md has the
  # whole campaign's figures).
  run_ok("${EXE}" run "${SOURCE}/campaigns/track_crossing.json" --runs 100 -o "${WORK}/track" -j 2 --no-plots -q)
  file(STRINGS "${WORK}/track/runs.csv" rows)
  list(LENGTH rows n)
  if(NOT n EQUAL 101)
    message(FATAL_ERROR "track_crossing --runs 100: ${n} lines in runs.csv, expected 101")
  endif()
  file(READ "${WORK}/track/summary.md" md)
  foreach(metric IN ITEMS max_track_pointing_error_rad max_los_rate_error_rad_s)
    if(NOT md MATCHES "\\| ${metric} \\| 100 \\| [0-9.e-]+ \\|")
      message(FATAL_ERROR "the summary has no figures of ${metric} over the 100 runs:\n${md}")
    endif()
  endforeach()

else()
  message(FATAL_ERROR "MODE must be parallel, rerun, refusals or tracking")
endif()

# SIGTERM, SIGHUP and SIGINT each stop `goris train` with a checkpoint, an "interrupted" message and the
# shell's status for the signal (143, 129, 130), and the run resumes; SIGTERM stops `goris remove` the same
# way. A resume may repeat the run's settings, not change them. A run folder with a config but no checkpoint
# says how to go on, and --restart starts it over.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(DATA "${RESOURCES}/default_scene")
set(TINY --mode radiance --resolution 32 --device cpu --init-points 1000)

# Runs goris and sends it `sig` once it has printed a line matching `pattern`; sets RC, OUT and ERR.
function(goris_signalled sig pattern)
  execute_process(COMMAND "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../support/signal_after_line.sh" ${sig} "${pattern}"
                          "${GORIS}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(RC "${rc}" PARENT_SCOPE)
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

foreach(case "TERM;143" "HUP;129" "INT;130")
  list(GET case 0 sig)
  list(GET case 1 code)
  set(RUN "${WORK}/run_${sig}")
  goris_signalled(${sig} "^\\[ *[0-9]+/" train "${DATA}" --out "${RUN}" ${TINY} --iters 1000000)
  if(NOT RC EQUAL ${code})
    message(FATAL_ERROR "SIG${sig}: goris train exited with ${RC}, expected ${code}\n${OUT}\n${ERR}")
  endif()
  expect_text("${OUT}" "interrupted (SIG${sig}) at iteration")
  file(GLOB ckpts "${RUN}/checkpoints/*.ckpt")
  if(NOT ckpts)
    message(FATAL_ERROR "SIG${sig}: no checkpoint written on stop\n${OUT}")
  endif()
  string(REGEX MATCH "at iteration ([0-9]+)/" _ "${OUT}")
  math(EXPR more "${CMAKE_MATCH_1} + 3")
  goris_ok(train "${DATA}" --out "${RUN}" --resume --iters ${more} --device cpu)
  if(NOT EXISTS "${RUN}/point_cloud.ply")
    message(FATAL_ERROR "SIG${sig}: the resumed run did not finish\n${OUT}")
  endif()
endforeach()

# --resume accepts options that repeat the run's settings (all of TINY) and refuses one that changes a
# setting, naming it with both values.
math(EXPR again "${more} + 2")
goris_ok(train "${DATA}" --out "${WORK}/run_INT" --resume --iters ${again} ${TINY})
expect_text("${OUT}" "resuming")
goris_fails("resolution 32 -> 64" train "${DATA}" --out "${WORK}/run_INT" --resume --iters 1000 --resolution 64
            --device cpu)

# A folder with config.json but no checkpoint (a run killed before its first one): plain train and --resume
# say to use --restart, which starts it over.
set(RUN "${WORK}/run_TERM")
file(REMOVE_RECURSE "${RUN}/checkpoints")
goris_fails("--restart" train "${DATA}" --out "${RUN}" ${TINY} --iters 3)
goris_fails("--restart" train "${DATA}" --out "${RUN}" --resume --iters 3 --device cpu)
goris_ok(train "${DATA}" --out "${RUN}" ${TINY} --iters 3 --restart)
file(GLOB ckpts "${RUN}/checkpoints/*.ckpt")
if(NOT ckpts OR NOT EXISTS "${RUN}/point_cloud.ply")
  message(FATAL_ERROR "--restart did not train the run again\n${OUT}")
endif()

# goris remove, stopped in its fine-tune (or earlier), exits 143.
goris_ok(select "${RUN}" --masks --device cpu)
goris_signalled(TERM "fine-tune" remove "${RUN}" --iters 1000000 --device cpu)
if(NOT RC EQUAL 143)
  message(FATAL_ERROR "SIGTERM: goris remove exited with ${RC}, expected 143\n${OUT}\n${ERR}")
endif()
expect_text("${OUT}" "interrupted (SIGTERM)")

# A FIFO under a checkpoint's name (RUN/checkpoints/iter_00000200.ckpt) is refused by its type, never opened
# (that would wait for a writer forever): `goris info` and `goris render` fall back to the intact checkpoint
# before it with a warning naming it. When no checkpoint is intact, the error names each file and --restart.
# `train --init` of a FIFO says it is one. Every command runs under a time limit, so a hang fails the test.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(DATA "${RESOURCES}/default_scene")
set(RUN "${WORK}/run")
find_program(MKFIFO mkfifo)
if(NOT MKFIFO)
  message("GORIS_TEST_SKIPPED: no mkfifo")
  return()
endif()

# Runs goris with a 60 s limit; sets RC, OUT and ERR.
function(goris_limited)
  execute_process(COMMAND "${GORIS}" ${ARGN} TIMEOUT 60 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc MATCHES "timeout")
    message(FATAL_ERROR "goris ${ARGN} hung (no answer in 60 s)\n${out}\n${err}")
  endif()
  set(RC "${rc}" PARENT_SCOPE)
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

goris_ok(train "${DATA}" --out "${RUN}" --mode radiance --resolution 32 --device cpu --init-points 1000 --iters 4
         --checkpoint-every 2)
set(FIFO "${RUN}/checkpoints/iter_00000200.ckpt")
execute_process(COMMAND "${MKFIFO}" "${FIFO}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mkfifo ${FIFO} failed")
endif()

goris_limited(info "${RUN}")
if(NOT RC EQUAL 0)
  message(FATAL_ERROR "goris info with a FIFO checkpoint exited with ${RC}\n${ERR}")
endif()
expect_text("${ERR}" "${FIFO} is a FIFO (named pipe), not a checkpoint file; using iter_00000004.ckpt")
goris_limited(render "${RUN}" --out "${WORK}/renders" --device cpu)
if(NOT RC EQUAL 0 OR NOT EXISTS "${WORK}/renders/r_000.png")
  message(FATAL_ERROR "goris render with a FIFO checkpoint exited with ${RC}\n${ERR}")
endif()
expect_text("${ERR}" "is a FIFO (named pipe)")

# No intact checkpoint: info says which and why, render fails naming them and --restart.
file(GLOB ckpts "${RUN}/checkpoints/iter_0000000*.ckpt")
foreach(f IN LISTS ckpts)
  file(WRITE "${f}" "not a checkpoint")
endforeach()
goris_limited(info "${RUN}")
expect_text("${OUT}" "no intact checkpoint")
expect_text("${OUT}" "iter_00000200.ckpt is a FIFO")
expect_text("${OUT}" "iter_00000004.ckpt is truncated or corrupted")
goris_limited(render "${RUN}" --out "${WORK}/renders2" --device cpu)
if(RC EQUAL 0)
  message(FATAL_ERROR "goris render with no intact checkpoint succeeded")
endif()
foreach(expected "iter_00000200.ckpt is a FIFO" "iter_00000004.ckpt is truncated" "--restart")
  expect_text("${ERR}" "${expected}")
endforeach()

# train --init of a FIFO.
execute_process(COMMAND "${MKFIFO}" "${WORK}/model.ply")
goris_limited(train "${DATA}" --out "${WORK}/run_init" --init "${WORK}/model.ply" --iters 2 --device cpu)
if(RC EQUAL 0)
  message(FATAL_ERROR "train --init of a FIFO succeeded")
endif()
expect_text("${ERR}" "${WORK}/model.ply: --init: is a FIFO (named pipe), not a model file")

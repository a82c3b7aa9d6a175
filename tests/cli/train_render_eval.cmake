# A short `goris train` on lego at 32x32, then resume, render --maps and eval; Ctrl-C leaves a checkpoint
# and the message how to resume. Skipped when ../shared/datasets/lego is absent.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
if(NOT EXISTS "${SHARED}/datasets/lego")
  message("GORIS_TEST_SKIPPED: ../shared/datasets/lego is absent")
  return()
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
get_filename_component(DATA "${SHARED}/datasets/lego" REALPATH)
set(RUN "${WORK}/run")

set(common --resolution 32 --device cpu --init-points 2000 --checkpoint-every 20)
goris_ok(train "${DATA}" --out "${RUN}" --iters 30 ${common})
expect_text("${OUT}" "done: 30 iterations")
foreach(f config.json log.csv point_cloud.ply checkpoints/iter_00000030.ckpt)
  if(NOT EXISTS "${RUN}/${f}")
    message(FATAL_ERROR "train did not write ${f}")
  endif()
endforeach()
file(READ "${RUN}/config.json" cfg)
expect_text("${cfg}" "\"data\": \"${DATA}\"")

# A second train into the same folder needs --resume; --resume extends the run.
execute_process(COMMAND "${GORIS}" train "${DATA}" --out "${RUN}" --iters 30 ${common}
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "training into an existing run without --resume succeeded")
endif()
expect_text("${err}" "--resume")
goris_ok(train "${DATA}" --out "${RUN}" --resume --iters 45 --device cpu)
expect_text("${OUT}" "resuming")
expect_text("${OUT}" "done: 45 iterations")
# log.csv: the header, the last iteration of each session (the log interval, 100, is longer than both).
file(STRINGS "${RUN}/log.csv" log)
list(LENGTH log lines)
list(GET log 1 first)
list(GET log 2 second)
if(NOT lines EQUAL 3 OR NOT first MATCHES "^30," OR NOT second MATCHES "^45,")
  message(FATAL_ERROR "log.csv after resume:\n${log}")
endif()

goris_ok(render "${RUN}" --split test --out "${WORK}/renders" --maps --device cpu)
foreach(f r_0.png r_0_depth.png r_0_normal.png r_0_alpha.png r_0_median_depth.png r_0_depth_normal.png r_0_label.png)
  if(NOT EXISTS "${WORK}/renders/${f}")
    message(FATAL_ERROR "render --maps did not write ${f}")
  endif()
endforeach()

goris_ok(eval "${RUN}" --split test --device cpu)
expect_text("${OUT}" "PSNR")
file(READ "${RUN}/metrics.json" metrics)
string(JSON views GET "${metrics}" views)
string(JSON psnr GET "${metrics}" psnr)
if(NOT views EQUAL 50 OR psnr LESS 8)
  message(FATAL_ERROR "metrics.json: views ${views}, psnr ${psnr}")
endif()
execute_process(COMMAND "${GORIS}" eval "${RUN}" --gt full --device cpu RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "eval --gt full on lego (no full_XXX.png) succeeded")
endif()
expect_text("${err}" "full_XXX.png")

# Ctrl-C: finish the iteration, checkpoint, exit 130 (interrupted) with the resume command. timeout(1) delivers its SIGINT
# twice (to the child, then to the process group): that must still count as one Ctrl-C. WHEN is "after N s"
# for the log; the command line before DATA decides how the signal is sent.
function(train_interrupted when dir)
  execute_process(COMMAND ${ARGN} "${GORIS}" train "${DATA}" --out "${dir}" --iters 100000 ${common}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 130)
    message(FATAL_ERROR "training interrupted ${when} exited with ${rc}, expected 130\n${out}\n${err}")
  endif()
  if(NOT out MATCHES "interrupted \\(SIGINT\\) at iteration ([0-9]+)/")
    message(FATAL_ERROR "training interrupted ${when} did not say where it stopped:\n${out}\n${err}")
  endif()
  expect_text("${out}" "resume with: goris train")
  set(STOPPED_AT "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

train_interrupted("after 8 s" "${WORK}/run_int" timeout --preserve-status -s INT 8)
file(GLOB ckpts "${WORK}/run_int/checkpoints/*.ckpt")
if(NOT ckpts)
  message(FATAL_ERROR "no checkpoint after Ctrl-C")
endif()

# Ctrl-C while the data set still loads (sent when train says "loading"): the run stops at its first step
# with a checkpoint and resumes.
train_interrupted("while loading" "${WORK}/run_int_early" "${CMAKE_CURRENT_LIST_DIR}/../support/signal_after_line.sh" INT "^loading ")
math(EXPR more "${STOPPED_AT} + 10")
goris_ok(train "${DATA}" --out "${WORK}/run_int_early" --resume --iters ${more})
expect_text("${OUT}" "done: ${more} iterations")

# `goris detect RUN`: the glossy-region detection of --mode auto on a trained run's checkpoint, with the
# agreement against the data set's own glossy masks and the masks written with --out; bad inputs are named.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
set(RUN "${WORK}/run")
goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode radiance --iters 40 --resolution 32 --device cpu
         --init-points 3000 --checkpoint-every 20)
goris_ok(detect "${RUN}" --device cpu --out "${WORK}/masks")
expect_text("${OUT}" "iter_00000040.ckpt (iteration 40): ")
expect_text("${OUT}" "of the covered pixels look view-dependent (threshold 0.20 %)")
expect_text("${OUT}" "against the data set's glossy masks: IoU ")
expect_text("${OUT}" "wrote 40 masks to")
if(NOT EXISTS "${WORK}/masks/gloss_r_000.png")
  message(FATAL_ERROR "goris detect --out wrote no gloss_r_000.png")
endif()
goris_ok(detect "${RUN}" --checkpoint "${RUN}/checkpoints/iter_00000020.ckpt" --device cpu)
expect_text("${OUT}" "(iteration 20)")

file(MAKE_DIRECTORY "${WORK}/empty")
goris_fails("has no checkpoint" detect "${WORK}/empty" --device cpu)
file(WRITE "${WORK}/bad.ckpt" "not a checkpoint")
goris_fails("bad.ckpt" detect "${RUN}" --checkpoint "${WORK}/bad.ckpt" --device cpu)

# A run whose data set moved after training: render, eval, select, remove and export say that the data set's
# path comes from RUN/config.json and how to point the run at its new folder (--data DIR), which is checked
# to hold the same training views; train --resume takes the new folder as DATA and records it. Uses a copy
# of the embedded scene.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
file(COPY "${RESOURCES}/default_scene/" DESTINATION "${WORK}/data")
set(RUN "${WORK}/run")
set(MOVED "${WORK}/moved")
goris_ok(train "${WORK}/data" --out "${RUN}" --mode radiance --resolution 32 --device cpu --init-points 1000
         --iters 4 --checkpoint-every 2)
file(RENAME "${WORK}/data" "${MOVED}")

# Without --data: the missing path, where it comes from and what to do, for every command that reads it.
foreach(cmd "render|${RUN}|--out|${WORK}/renders" "eval|${RUN}" "select|${RUN}|--masks" "remove|${RUN}"
            "export|${RUN}|--ply|${WORK}/model.ply")
  string(REPLACE "|" ";" args "${cmd}")
  foreach(expected "${WORK}/data: not found" "${RUN}/config.json" "--data DIR")
    goris_fails("${expected}" ${args} --device cpu)
  endforeach()
endforeach()

# Another data set given as --data (one training view fewer) is refused.
file(COPY "${MOVED}/" DESTINATION "${WORK}/other")
file(READ "${WORK}/other/transforms_train.json" transforms)
string(JSON transforms REMOVE "${transforms}" frames 0)
file(WRITE "${WORK}/other/transforms_train.json" "${transforms}")
goris_fails("the training views differ" render "${RUN}" --out "${WORK}/renders" --data "${WORK}/other" --device cpu)

# --data at the moved folder: each command works and says which folder it uses.
goris_ok(render "${RUN}" --out "${WORK}/renders" --data "${MOVED}" --device cpu)
expect_text("${ERR}" "was trained on the data set at ${WORK}/data; using ${MOVED}, which holds the same")
if(NOT EXISTS "${WORK}/renders/r_000.png")
  message(FATAL_ERROR "render --data wrote no r_000.png\n${OUT}")
endif()
goris_ok(eval "${RUN}" --data "${MOVED}" --device cpu)
expect_text("${OUT}" "PSNR")
goris_ok(export "${RUN}" --ply "${WORK}/model.ply" --data "${MOVED}" --device cpu)
goris_ok(select "${RUN}" --masks --data "${MOVED}" --device cpu)
goris_ok(remove "${RUN}" --iters 2 --data "${MOVED}" --device cpu)
file(READ "${RUN}/removal/config.json" removal_config)
expect_text("${removal_config}" "\"data\": \"${MOVED}\"")

# A run from before the fingerprint: the moved folder is taken unchecked, with a warning.
file(READ "${RUN}/config.json" run_config)
string(JSON run_config REMOVE "${run_config}" data_views)
file(WRITE "${RUN}/config.json" "${run_config}")
goris_ok(render "${RUN}" --out "${WORK}/renders_unchecked" --data "${MOVED}" --device cpu)
expect_text("${ERR}" "records no fingerprint of its training views: ${MOVED} is used unchecked")

# train --resume: another data set as DATA is refused, the moved folder is taken and recorded.
goris_fails("this run was trained on ${WORK}/data, not ${WORK}/other: the training views differ"
            train "${WORK}/other" --out "${RUN}" --resume --iters 6 --device cpu)
goris_ok(train "${MOVED}" --out "${RUN}" --resume --iters 6 --resolution 32 --device cpu)
expect_text("${OUT}" "resuming")
file(READ "${RUN}/config.json" run_config)
expect_text("${run_config}" "\"data\": \"${MOVED}\"")

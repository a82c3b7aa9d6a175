# A run folder whose config.json an older version wrote (no config_version, a setting removed since at its
# off value) opened by the scripted editor: it opens as a run with its data set and model, says how it read
# the file (the migration note), shows non-blank, distinct channels, and trains on from where it stopped.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()
execute_process(COMMAND "${GORIS}" train "${RESOURCES}/default_scene" --out "${WORK}/run" --iters 40 --resolution 64
                        --device cpu --init-points 3000 --checkpoint-every 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "goris train failed:\n${out}\n${err}")
endif()
file(READ "${WORK}/run/config.json" cfg)
string(REPLACE "\"config_version\": 3," "\"intrinsic_prune_mirror_world_plane\": false," old "${cfg}")
if(old STREQUAL cfg)
  message(FATAL_ERROR "config.json has no \"config_version\": 3 to replace:\n${cfg}")
endif()
file(WRITE "${WORK}/run/config.json" "${old}")

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 192}\n")
file(WRITE "${WORK}/old.txt" "# written by tests/gui/studio_open_old_run.cmake
open ${WORK}/run
grid 2
channel main final
channel 0 depth
channel 1 normal
screenshot ${WORK}/old.png
train 50
quit
")
studio_run_ok("${WORK}/old.txt" R)
expect_text("${R_OUT}" "opened run ${WORK}/run")
expect_text("${R_ERR}" "written by an older version (config_version 1)")
expect_text("${R_ERR}" "'intrinsic_prune_mirror_world_plane' dropped")
expect_text("${R_OUT}" "trained to iteration 90")
expect_tiles("${WORK}/old.png" 3 "the old run's channels")

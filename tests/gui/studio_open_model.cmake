# A model file opened on its own: a tiny run of the embedded scene exported as SPZ (goris export), opened by
# the scripted editor with no data set or run beside it. Its final colour, depth and normal tiles are
# non-blank and different, a click in the middle of the view selects Gaussians, and training and removal
# are refused with a message that says why (a model file has no photos).
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()
foreach(args
    "train;${RESOURCES}/default_scene;--out;${WORK}/run;--iters;60;--resolution;64;--device;cpu;--init-points;3000;--checkpoint-every;0"
    "export;${WORK}/run;--spz;${WORK}/scene.spz;--device;cpu")
  execute_process(COMMAND "${GORIS}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "goris ${args} failed:\n${out}\n${err}")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}/run")  # the model file alone

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 192}\n")
file(WRITE "${WORK}/model.txt" "# written by tests/gui/studio_open_model.cmake
open ${WORK}/scene.spz
grid 2
channel main final
channel 0 depth
channel 1 normal
screenshot ${WORK}/model.png
select_grow 0.05
select_click 50% 50%
quit
")
studio_run_ok("${WORK}/model.txt" R)
expect_text("${R_OUT}" "opened model ${WORK}/scene.spz")
expect_text("${R_OUT}" "a model file has no photos")
expect_text("${R_OUT}" "picked Gaussian")
expect_tiles("${WORK}/model.png" 3 "the model's channels")

foreach(action "train 10" "remove 10")
  file(WRITE "${WORK}/refused.txt" "open ${WORK}/scene.spz\n${action}\nquit\n")
  studio_run("${WORK}/refused.txt" R)
  if(R_RC EQUAL 0)
    message(FATAL_ERROR "'${action}' on a model file was accepted\n${R_OUT}")
  endif()
  expect_text("${R_ERR}" "a model file has no photos")
endforeach()

# The scripted editor opens the embedded scene, trains 30 iterations through the Training panel's session,
# shows a different channel in every viewport and screenshots the window: every tile must be non-blank
# and differ from the others. Also a click (picked depth reported) and the photo slider. Screenshots stay
# in WORK as artefacts.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()
set(script "${WORK}/train_grid.txt")
file(WRITE "${script}" "# written by tests/gui/studio_train_grid.cmake
open ${RESOURCES}/default_scene
out ${WORK}/run
set random_init_points 3000
set resolution 64
set checkpoint_interval 0
set background [1,1,1]
train 30
channel main final
channel 0 normal
channel 1 depth
channel 2 alpha
channel 3 diffuse
compare off
snap 2
wait_frames 2
screenshot ${WORK}/grid.png
click 200 150
compare slider 0.5
screenshot ${WORK}/compare.png
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")
expect_text("${R_OUT}" "trained to iteration 30")
expect_text("${R_OUT}" "picked pixel (")
expect_text("${R_OUT}" "opacity")
foreach(f grid.png grid.layout.json compare.png run/config.json run/point_cloud.ply run/log.csv)
  if(NOT EXISTS "${WORK}/${f}")
    message(FATAL_ERROR "the scripted editor did not write ${f}\n${R_OUT}\n${R_ERR}")
  endif()
endforeach()
file(GLOB ckpts "${WORK}/run/checkpoints/*.ckpt")
if(NOT ckpts)
  message(FATAL_ERROR "no checkpoint in ${WORK}/run/checkpoints")
endif()
expect_tiles("${WORK}/grid.png" 5 "screenshot check failed")
if(NOT EXISTS "${WORK}/config/goris-studio/settings.json")
  message(FATAL_ERROR "the editor did not save its settings under XDG_CONFIG_HOME")
endif()
file(READ "${WORK}/config/goris-studio/settings.json" settings)
expect_text("${settings}" "default_scene")
expect_text("${settings}" "\"alpha\"")

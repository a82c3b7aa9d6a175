# A capture import from the scripted editor, through the Open panel's code path: a short orbit video of
# the shared lego scene (gui_capture_input, as the capture unit test makes it) imported with COLMAP as a
# background job: a first import cancelled (nothing written), then one to the end (a screenshot while it
# runs), the new data set opened, its report printed and a few training iterations run on it. Skipped
# with a message without COLMAP or without ../shared/datasets/lego (the embedded 128 px scene gives COLMAP
# too few features to start a model).
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()
find_program(COLMAP colmap)
if(NOT COLMAP)
  message("GORIS_TEST_SKIPPED: needs COLMAP (sudo apt-get install colmap, or ./dev setup)")
  return()
endif()
if(NOT EXISTS "${SHARED}/datasets/lego")
  message("GORIS_TEST_SKIPPED: needs ../shared/datasets/lego (absent on this machine)")
  return()
endif()

execute_process(COMMAND "${CAPTURE_INPUT}" "${SHARED}/datasets/lego" "${WORK}/orbit.mp4"
                RESULT_VARIABLE rc OUTPUT_VARIABLE frames ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "no input video:\n${err}")
endif()
message("input: ${WORK}/orbit.mp4, ${frames} frames")

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 160}\n")
set(script "${WORK}/import.txt")
file(WRITE "${script}" "# written by tests/gui/studio_import_capture.cmake
panels Open
import_capture_start ${WORK}/orbit.mp4 ${WORK}/cancelled_data --max-images 20
wait_frames 5
import_cancel
screenshot ${WORK}/import_cancelled.png
import_capture_start ${WORK}/orbit.mp4 ${WORK}/lego_data --max-images 20
wait_frames 20
screenshot_now ${WORK}/import_running.png
import_wait
screenshot ${WORK}/import_done.png
out ${WORK}/run
set resolution 64
set checkpoint_interval 0
train 10
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")
expect_text("${R_OUT}" "registered")
expect_text("${R_OUT}" "opened the imported data set ${WORK}/lego_data")
expect_text("${R_OUT}" "trained to iteration 10")
foreach(f capture_report.json capture_report.txt sparse/0 images)
  if(NOT EXISTS "${WORK}/lego_data/${f}")
    message(FATAL_ERROR "the imported data set has no ${f}")
  endif()
endforeach()
foreach(p .lego_data.capture-tmp cancelled_data .cancelled_data.capture-tmp)
  if(EXISTS "${WORK}/${p}")
    message(FATAL_ERROR "the imports left ${WORK}/${p}")
  endif()
endforeach()
expect_text("${R_OUT}" "import cancelled: cancelled: COLMAP stopped, nothing was written")

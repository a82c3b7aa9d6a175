# The removal's result in the main viewport: train the embedded scene briefly (radiance), select the
# target by the data set's object masks, remove it with a short fine-tune. The editor then shows the cleaned
# scene from the same view (the target's region differs from the screenshot before the removal), the
# before / after toggle brings the scene with the target back, and the slider compares the two.
# Screenshots stay in WORK as artefacts.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()

target_view()

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 160}\n")
set(script "${WORK}/before_after.txt")
file(WRITE "${script}" "# written by tests/gui/studio_before_after.cmake
open ${RESOURCES}/default_scene
out ${WORK}/run
set mode radiance
set random_init_points 3000
set random_init_box_ratio 0.15
set resolution 64
set checkpoint_interval 0
train 600
snap ${VIEW}
screenshot ${WORK}/with_target.png
select_masks
remove 10
screenshot ${WORK}/cleaned.png
before_after before
screenshot ${WORK}/toggled_before.png
before_after after
compare_with before
compare slider 0.5
screenshot ${WORK}/slider.png
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")
expect_text("${R_OUT}" "showing the cleaned scene ${WORK}/run/removal")
foreach(f with_target.png cleaned.png toggled_before.png slider.png)
  if(NOT EXISTS "${WORK}/${f}")
    message(FATAL_ERROR "the scripted editor did not write ${f}\n${R_OUT}\n${R_ERR}")
  endif()
endforeach()
execute_process(COMMAND "${SELECTION_CHECK}" removed "${WORK}/with_target.png" "${WORK}/cleaned.png"
                        "${WORK}/toggled_before.png" "${MASK}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "before / after:\n${out}\n${err}")
endif()
# The slider: the cleaned scene left of the split, the scene with the target right of it.
execute_process(COMMAND "${SELECTION_CHECK}" slider "${WORK}/with_target.png" "${WORK}/cleaned.png"
                        "${WORK}/slider.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "compare slider:\n${out}\n${err}")
endif()

# The guided two-click flow (the Two-click panel) on a short run of the embedded scene trained without its
# object masks: a plain mouse click on the target in the training view that shows it best, the click the
# flow offers in a view from another direction, the review of every view's mask, taking a click back and
# undoing that, then undo back to the start (nothing selected, the view as before). A second pass goes on
# to "use as target masks and remove" with a short schedule. The masks the flow wrote are scored against
# the data set's own object masks (their IoU is printed); the test fails below MIN_IOU.
#
# MIN_IOU, measured on this run (600 iterations at 64 px, 10000 initial points, trained without masks;
# the same clicks through `goris select --click ... --write-masks --masks-iou` give the same numbers):
# the flow's two clicks reach a mean IoU of 0.79 (its target masks, written from the same selection, too),
# as much as the selection voted by the exact masks themselves (0.79: what the mask writer can reach on this
# run); one click alone reaches 0.67. 0.7 passes a flow that found the torus from two views and fails one
# that found only what one click finds, or leaked.
set(MIN_IOU 0.7)
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()

execute_process(COMMAND "${GORIS}" train "${RESOURCES}/default_scene" --out "${WORK}/run" --iters 600 --resolution 64
                        --device cpu --init-points 10000 --checkpoint-every 0 --set use_object_masks=false
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "goris train failed:\n${out}\n${err}")
endif()

target_view()
message("first click: view ${VIEW} at ${CLICK_X} ${CLICK_Y} (${MASK})")

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 256}\n")
set(script "${WORK}/two_click.txt")
file(WRITE "${script}" "# written by tests/gui/studio_two_click.cmake
open ${WORK}/run
panels Two-click
select_tool click
snap ${VIEW}
screenshot ${WORK}/before.png
two_click start ${VIEW}
two_click expect first_click
drag ${CLICK_X} ${CLICK_Y} ${CLICK_X} ${CLICK_Y}
two_click expect second_click
screenshot ${WORK}/offered.png
two_click offered
two_click expect review
screenshot ${WORK}/review.png
two_click view ${VIEW}
screenshot ${WORK}/review_first_view.png
two_click take_back 2
two_click expect second_click
two_click undo
two_click expect review
two_click undo
two_click expect second_click
two_click undo
two_click expect first_click
expect_selected 0
snap ${VIEW}
screenshot ${WORK}/undone.png
two_click cancel
two_click expect off
two_click start ${VIEW}
drag ${CLICK_X} ${CLICK_Y} ${CLICK_X} ${CLICK_Y}
two_click offered
two_click expect review
two_click use 10
two_click expect done
expect_step_complete
screenshot ${WORK}/removed.png
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")

# Every step reported; the second pass clicked as the first (the same masks).
expect_text("${R_OUT}" "two-click: 1. click the object in")
expect_text("${R_OUT}" "two-click: 2. click the object in a second view: offered")
expect_text("${R_OUT}" "two-click: 3. review the masks of the 40 views")
expect_text("${R_OUT}" "two-click undo: at first click, 0 clicks")
expect_text("${R_OUT}" "two-click use: at done")
expect_text("${R_OUT}" "wrote 40 object masks to ${WORK}/run/target_masks")
file(READ "${WORK}/run/selection.json" sel)
string(JSON method GET "${sel}" method)
if(NOT method STREQUAL "masks")
  message(FATAL_ERROR "the removal's target should come from the target masks:\n${sel}")
endif()
string(REGEX MATCH "offered (r_[0-9]+) \\(([0-9]+), ([0-9]+)\\)" _ "${R_OUT}")
message("the flow offered ${CMAKE_MATCH_1} at (${CMAKE_MATCH_2}, ${CMAKE_MATCH_3}) for the second click")

# The review's mask overlay lies on the target; undo brought back the view of before.
check(tint "${WORK}/before.png" "${WORK}/review_first_view.png" "${MASK}")
check(same "${WORK}/before.png" "${WORK}/undone.png")
# The masks of both passes against the data set's own.
check(iou "${WORK}/run/two_click_masks" "${RESOURCES}/default_scene" ${MIN_IOU})
check(iou "${WORK}/run/target_masks" "${RESOURCES}/default_scene" ${MIN_IOU})

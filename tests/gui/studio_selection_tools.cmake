# The selection tools in the scripted editor, on a short run of the embedded scene snapped to the training
# view that shows the target best: rectangle (through the depth and through everything), lasso, brush,
# sphere, box, colour range, invert, grow / shrink steps, hide, lock and "Use as target masks". Each tool's
# tint must land inside the region it was given and nowhere else, and each undo must bring back the view
# and the count of before. Then the same tools with the mouse (`drag`): a rectangle and a lasso drawn on
# the view select what their script lines selected, a brush stroke selects, Alt+drag orbits instead, the
# sphere's centre handle follows the mouse, and its radius and the box's size handles resize them. Last
# the tool bar's buttons pressed with the mouse (`press`): the tools, the volume's Select, Invert, the
# grow / shrink steps, Hide / Unhide all, Lock / Unlock all. Screenshots stay in WORK as artefacts.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()

execute_process(COMMAND "${GORIS}" train "${RESOURCES}/default_scene" --out "${WORK}/run" --mode radiance --iters 600 --resolution 64
                        --device cpu --init-points 10000 --checkpoint-every 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "goris train failed:\n${out}\n${err}")
endif()

target_view()
execute_process(COMMAND "${SELECTION_CHECK}" bbox "${MASK}" RESULT_VARIABLE rc OUTPUT_VARIABLE box
                ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "no bounding box of ${MASK}:\n${err}")
endif()
separate_arguments(box)
list(GET box 0 X0)
list(GET box 1 Y0)
list(GET box 2 X1)
list(GET box 3 Y1)
message("view ${VIEW}: the target lies in ${X0} ${Y0} - ${X1} ${Y1} (${MASK})")
# The box's middle row and column (integer percent), for the lasso and the brush.
string(REGEX REPLACE "\\..*" "" x0 "${X0}")
string(REGEX REPLACE "\\..*" "" x1 "${X1}")
string(REGEX REPLACE "\\..*" "" y0 "${Y0}")
string(REGEX REPLACE "\\..*" "" y1 "${Y1}")
math(EXPR XM "(${x0} + ${x1}) / 2")
math(EXPR YM "(${y0} + ${y1}) / 2")
math(EXPR YB0 "${YM} - 2")  # the brush stroke's band (radius 2 %)
math(EXPR YB1 "${YM} + 2")

# The target of the embedded scene (resources/default_scene/scene.json): a torus of radius 0.34 lying on
# the table at about (0, 0.04, 0.1).
set(SPHERE "-0.01 0.04 0.1 0.3")
set(BOX "-0.01 0.04 0.12 0.36 0.36 0.1")

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 256}\n")
set(script "${WORK}/tools.txt")
file(WRITE "${script}" "# written by tests/gui/studio_selection_tools.cmake
open ${WORK}/run
snap ${VIEW}
select_tool rect
screenshot ${WORK}/before.png
select_rect ${X0} ${Y0} ${X1} ${Y1}
screenshot ${WORK}/rect.png
undo
expect_selected 0
screenshot ${WORK}/rect_undo.png
select_through all
select_rect ${X0} ${Y0} ${X1} ${Y1}
select_through visible
undo
select_polygon ${XM}% ${Y0} ${X1} ${YM}% ${XM}% ${Y1} ${X0} ${YM}%
screenshot ${WORK}/polygon.png
undo
select_brush 2% ${X0} ${YM}% ${X1} ${YM}%
screenshot ${WORK}/brush.png
undo
select_sphere ${SPHERE}
screenshot ${WORK}/sphere.png
select_box ${BOX}
screenshot ${WORK}/box.png
invert
undo
grow_step
shrink_step 2
undo
undo
hide
expect_selected 0
screenshot ${WORK}/hidden.png
undo
screenshot ${WORK}/hidden_undo.png
lock
select_box ${BOX}
expect_selected 0
unlock
select_colour 0.5 0.37 0.2 0.15
select_box ${BOX}
use_as_target_masks ${WORK}/target_masks
save_selection
select_tool rect
drag ${X0} ${Y0} ${X1} ${Y1}
select_tool lasso
drag ${XM}% ${Y0} ${X1} ${YM}% ${XM}% ${Y1} ${X0} ${YM}%
select_tool brush
drag ${X0} ${YM}% ${X1} ${YM}% shift
select_sphere 0 0 0.15 0.3
select_tool sphere
drag 50% 50% 60% 50%
select_tool rect
drag 10% 10% 30% 10% alt
expect_selected 1 100000000
screenshot ${WORK}/orbited.png
panels Selection
press Sphere
drag_handle radius 25 0
press Box
drag_handle x 20 0
drag_handle z -5 0
press volume Select
expect_selected 1 100000000
press Grow step
press Shrink step
press Hide
expect_selected 0
press Unhide all
press volume Select
press Lock
expect_selected 0
press Unlock all
press Invert
press Click
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")

# The counts the editor reported, in the order of the script's edits.
string(REGEX MATCHALL "[^\n]*: [0-9]+ of [0-9]+ Gaussians selected" lines "${R_OUT}")
set(counts)
foreach(l ${lines})
  string(REGEX REPLACE ".*: ([0-9]+) of [0-9]+ Gaussians selected" "\\1" n "${l}")
  string(REGEX REPLACE ":.*" "" what "${l}")
  list(APPEND counts "${what}=${n}")
endforeach()
string(REGEX MATCH "of ([0-9]+) Gaussians selected" _ "${R_OUT}")
set(total "${CMAKE_MATCH_1}")
message("selection counts: ${counts} (of ${total})")
# count(<regex of the line's start> <var>): the first reported count whose line starts like that.
function(count pattern var)
  foreach(c ${counts})
    if(c MATCHES "^${pattern}.*=([0-9]+)$")
      set(${var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "no selection count for '${pattern}' in ${counts}")
endfunction()
count("rect .*visible" rect_visible)
count("rect .*all" rect_all)
count("box " box)
count("inverted" inverted)
count("grown by 1" grown)
count("shrunk by 2" shrunk)
foreach(v rect_visible box grown)
  if(${v} EQUAL 0)
    message(FATAL_ERROR "${v} selected nothing: ${counts}")
  endif()
endforeach()
if(rect_all LESS_EQUAL rect_visible)
  message(FATAL_ERROR "through everything (${rect_all}) should select more than through the depth (${rect_visible})")
endif()
math(EXPR expect_inverted "${total} - ${box}")
if(NOT inverted EQUAL expect_inverted)
  message(FATAL_ERROR "invert selected ${inverted}, expected ${total} - ${box}")
endif()
if(grown LESS box OR shrunk GREATER grown)
  message(FATAL_ERROR "a grow step should add (${box} -> ${grown}), a shrink step remove (-> ${shrunk})")
endif()
expect_text("${R_OUT}" "undo: ${box} of ${total} Gaussians selected")  # the steps undone
expect_text("${R_OUT}" "hid ${box} Gaussians")
expect_text("${R_OUT}" "wrote 40 object masks to ${WORK}/target_masks")
expect_text("${R_OUT}" "saved the selection to ${WORK}/run/selection.json")
file(GLOB mask_files "${WORK}/target_masks/mask_*.png")
list(LENGTH mask_files n_masks)
if(NOT n_masks EQUAL 40)
  message(FATAL_ERROR "expected 40 target masks, found ${n_masks}")
endif()
file(READ "${WORK}/run/selection.json" sel)
string(JSON method GET "${sel}" method)
if(NOT method STREQUAL "masks")
  message(FATAL_ERROR "the removal's target should come from the target masks:\n${sel}")
endif()

# The mouse: the rectangle and the lasso drawn select as their script lines did; the brush stroke adds.
# The lasso's path is the mouse's, whole pixels along the script's edges: a Gaussian whose centre lies on
# an edge may fall either side, so the drawn lasso may differ by 2 (or 5 %) from the script's polygon.
count("polygon .*replace" polygon)
string(REGEX MATCHALL "rect [^\n]*visible, replace: [0-9]+" rects "${R_OUT}")
string(REGEX MATCHALL "polygon [^\n]*visible, replace: [0-9]+" polygons "${R_OUT}")
list(GET rects -1 dragged_rect)
list(GET polygons -1 dragged_polygon)
string(REGEX MATCH "[0-9]+$" dragged_polygon_count "${dragged_polygon}")
math(EXPR polygon_off "${dragged_polygon_count} - ${polygon}")
if(polygon_off LESS 0)
  math(EXPR polygon_off "-${polygon_off}")
endif()
math(EXPR polygon_slack "${polygon} / 20")
if(polygon_slack LESS 2)
  set(polygon_slack 2)
endif()
if(NOT dragged_rect MATCHES ": ${rect_visible}$" OR polygon_off GREATER polygon_slack)
  message(FATAL_ERROR "the dragged shapes should select as the script lines did (${rect_visible}, ${polygon}):\n"
                      "${dragged_rect}\n${dragged_polygon}")
endif()
expect_text("${R_OUT}" "visible, add: ")  # the shift-drag brush stroke
# The sphere's centre handle (placed at the training cameras' look-at point, the middle of the view) moved
# with the mouse.
string(REGEX MATCHALL "the sphere at \\([^)]*\\)" spheres "${R_OUT}")
list(GET spheres -1 sphere_dragged)
if(NOT spheres MATCHES "the sphere at \\(0, 0, 0.15\\)" OR sphere_dragged MATCHES "\\(0, 0, 0.15\\)")
  message(FATAL_ERROR "dragging the sphere's centre handle did not move it: ${spheres}")
endif()
# The size handles: dragged outward, the sphere's radius and the box's x half size grow; dragged inward,
# its z half size shrinks.
string(REGEX MATCHALL "the sphere at \\([^)]*\\), radius [0-9.e+-]+" radii "${R_OUT}")
list(GET radii -2 r_before)
list(GET radii -1 r_after)
string(REGEX REPLACE ".*radius " "" r_before "${r_before}")
string(REGEX REPLACE ".*radius " "" r_after "${r_after}")
string(REGEX MATCHALL "the box at \\([^)]*\\), half \\([^)]*\\)" halves "${R_OUT}")
list(LENGTH halves n_halves)
if(NOT n_halves EQUAL 2 OR r_after LESS_EQUAL r_before)
  message(FATAL_ERROR "dragging the size handles did not resize: sphere radius ${r_before} -> ${r_after}, box: ${halves}")
endif()
list(GET halves 0 half_x)
list(GET halves 1 half_z)
string(REGEX REPLACE ".*half \\(([^,]*), ([^,]*), ([^)]*)\\)" "\\1;\\2;\\3" half_x "${half_x}")
string(REGEX REPLACE ".*half \\(([^,]*), ([^,]*), ([^)]*)\\)" "\\1;\\2;\\3" half_z "${half_z}")
list(GET half_x 0 hx)
list(GET half_z 2 hz)
message("sphere radius ${r_before} -> ${r_after}; box half x 0.36 -> ${hx}, then half z 0.1 -> ${hz}")
if(hx LESS_EQUAL 0.36 OR hz GREATER_EQUAL 0.1)
  message(FATAL_ERROR "the box's size handles did not resize it: ${halves}")
endif()
# The tool bar's buttons, pressed: each made its edit.
foreach(b "Sphere" "Box" "volume Select" "Invert" "Grow step" "Shrink step" "Hide" "Unhide all" "Lock" "Unlock all")
  expect_text("${R_OUT}" "pressed ${b}")
endforeach()
string(FIND "${R_OUT}" "pressed Sphere" at)
string(SUBSTRING "${R_OUT}" ${at} -1 pressing)
string(REGEX MATCHALL "[^\n]*: [0-9]+ of [0-9]+ Gaussians selected" after_press "${pressing}")
foreach(what "box at .*replace" "inverted" "grown by 1 step" "shrunk by 1 step" "hid " "showing every Gaussian again"
        "locked " "unlocked every Gaussian")
  set(found FALSE)
  foreach(l ${after_press})
    if(l MATCHES "^${what}")
      set(found TRUE)
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "no selection edit '${what}' after pressing the tool bar's buttons")
  endif()
endforeach()

# Alt+drag orbits: the view left the snapped camera (so the main image changed), and selected nothing new.
execute_process(COMMAND "${SELECTION_CHECK}" same "${WORK}/before.png" "${WORK}/orbited.png" RESULT_VARIABLE rc
                OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "alt+drag did not orbit the view")
endif()

# Each tool's tint lies in its region; the target's mask for the volumes.
check(region "${WORK}/before.png" "${WORK}/rect.png" ${X0} ${Y0} ${X1} ${Y1})
check(region "${WORK}/before.png" "${WORK}/polygon.png" ${X0} ${Y0} ${X1} ${Y1})
check(region "${WORK}/before.png" "${WORK}/brush.png" ${X0} ${YB0}% ${X1} ${YB1}%)
check(tint "${WORK}/before.png" "${WORK}/sphere.png" "${MASK}")
check(tint "${WORK}/before.png" "${WORK}/box.png" "${MASK}")
# Hiding the box's Gaussians changes the view only where they were.
check(region "${WORK}/before.png" "${WORK}/hidden.png" ${X0} ${Y0} ${X1} ${Y1})
# Undo brings back the view of before.
check(same "${WORK}/before.png" "${WORK}/rect_undo.png")
check(same "${WORK}/box.png" "${WORK}/hidden_undo.png")

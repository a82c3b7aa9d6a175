# The Open panel's import refuses bad input and writes nothing (needs no COLMAP): an output folder inside
# the photo folder, and a video that cannot be read. The editor goes on after each refusal; the error is
# in the panel (screenshots stay in WORK) and the script's expect_import_error checks its words.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()

file(GLOB photos "${RESOURCES}/default_scene/train/r_00*.png")
list(SUBLIST photos 0 3 photos)
set(IN "${WORK}/in")  # the inputs, and where the refused outputs would go
file(MAKE_DIRECTORY "${IN}/photos")
file(COPY ${photos} DESTINATION "${IN}/photos")
file(WRITE "${IN}/broken.mp4" "not a video")
file(GLOB_RECURSE before LIST_DIRECTORIES true "${IN}/*")

set(script "${WORK}/refusals.txt")
file(WRITE "${script}" "# written by tests/gui/studio_import_refusals.cmake
panels Open
import_capture_start ${IN}/photos ${IN}/photos/data
expect_import_error lies inside the input folder
screenshot ${WORK}/inside_input.png
import_capture_start ${IN}/broken.mp4 ${IN}/broken_data
expect_import_error broken.mp4: cannot read the video
screenshot ${WORK}/unreadable_video.png
quit
")
studio_run_ok("${script}" R)
message("${R_OUT}")
expect_text("${R_OUT}" "import refused: ${IN}/photos/data: lies inside the input folder")
expect_text("${R_OUT}" "import refused: ${IN}/broken.mp4: cannot read the video")
file(GLOB_RECURSE after LIST_DIRECTORIES true "${IN}/*")
if(NOT before STREQUAL after)
  message(FATAL_ERROR "a refused import wrote something:\nbefore: ${before}\nafter: ${after}")
endif()

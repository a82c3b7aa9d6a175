# Shared by the GUI tests: how to run goris-studio in a window. Sets GUI_LAUNCH (a command prefix) or
# prints GORIS_TEST_SKIPPED and sets GUI_SKIP when no display can be had.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")  # expect_text()
# Every GUI test starts from an empty WORK folder (its artefacts: screenshots, run folders, settings).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(GUI_SKIP FALSE)
find_program(XVFB_RUN xvfb-run)
if(XVFB_RUN)
  set(GUI_LAUNCH ${XVFB_RUN} -a -s "-screen 0 1280x800x24")
elseif(DEFINED ENV{DISPLAY} AND NOT "$ENV{DISPLAY}" STREQUAL "")
  set(GUI_LAUNCH)  # the user's display
else()
  message("GORIS_TEST_SKIPPED: neither xvfb-run nor a DISPLAY to open the editor's window")
  set(GUI_SKIP TRUE)
endif()

# studio_run(<script file> <result var prefix>): runs the scripted editor with its settings and run folders
# in WORK; sets <prefix>_RC, <prefix>_OUT, <prefix>_ERR. Skips (GUI_SKIP) when the window cannot open.
function(studio_run script prefix)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env XDG_CONFIG_HOME=${WORK}/config XDG_DATA_HOME=${WORK}/data
            ${GUI_LAUNCH} "${STUDIO}" --script "${script}" --width 1280 --height 800
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
  set(${prefix}_RC "${rc}" PARENT_SCOPE)
  set(${prefix}_OUT "${out}" PARENT_SCOPE)
  set(${prefix}_ERR "${err}" PARENT_SCOPE)
  if(NOT rc EQUAL 0 AND err MATCHES "error: display:")
    message("GORIS_TEST_SKIPPED: no window could be opened:\n${err}")
    set(GUI_SKIP TRUE PARENT_SCOPE)
  endif()
endfunction()

# target_view(): the training view of the embedded scene whose target mask has the deepest interior point
# (the easiest click on the target). Sets VIEW (its index), CLICK_X, CLICK_Y (that point, in percent) and
# MASK (its object mask file).
macro(target_view)
  execute_process(COMMAND "${SELECTION_CHECK}" target "${RESOURCES}/default_scene"
                  RESULT_VARIABLE _rc OUTPUT_VARIABLE _target ERROR_VARIABLE _err OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "no view of the target:\n${_err}")
  endif()
  separate_arguments(_target)
  list(GET _target 0 VIEW)
  list(GET _target 1 CLICK_X)
  list(GET _target 2 CLICK_Y)
  math(EXPR _view3 "1000 + ${VIEW}")
  string(SUBSTRING "${_view3}" 1 3 _view3)
  set(MASK "${RESOURCES}/default_scene/train/mask_${_view3}.png")
endmacro()

# studio_run_ok(<script file> <result var prefix>): studio_run, then returns from the calling test when no
# window could be had (GUI_SKIP) and fails it when the editor exited non-zero.
macro(studio_run_ok script prefix)
  studio_run("${script}" ${prefix})
  if(GUI_SKIP)
    return()
  endif()
  if(NOT ${prefix}_RC EQUAL 0)
    message(FATAL_ERROR "goris-studio --script exited with ${${prefix}_RC}\n${${prefix}_OUT}\n${${prefix}_ERR}")
  endif()
endmacro()

# expect_tiles(<screenshot> <viewport count> <what>): gui_screenshot_check on it (every viewport non-blank,
# no two alike); prints its report and fails the test, naming `what`, when the check fails.
function(expect_tiles png count what)
  execute_process(COMMAND "${CHECK}" "${png}" --expect ${count} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}:\n${out}\n${err}")
  endif()
endfunction()

# check(<mode> <args...>): gui_selection_check (the selection tests' image and mask checks), its report
# printed; fails the test when it fails.
function(check)
  execute_process(COMMAND "${SELECTION_CHECK}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${ARGV0} ${ARGV2}: ${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "gui_selection_check ${ARGN}:\n${out}\n${err}")
  endif()
endfunction()

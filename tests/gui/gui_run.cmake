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

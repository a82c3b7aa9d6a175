# Script errors exit non-zero with a message naming the file and line: a parse error before any window
# opens, a bad script path, and (with a display) an action that fails at run time.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)

file(WRITE "${WORK}/bad_action.txt" "# a comment\nwait_frames 1\nfrobnicate 3\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CONFIG_HOME=${WORK}/config "${STUDIO}"
                        --script "${WORK}/bad_action.txt"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "an unknown script action was accepted")
endif()
expect_text("${err}" "bad_action.txt:3: unknown action 'frobnicate'")

file(WRITE "${WORK}/bad_number.txt" "train many\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CONFIG_HOME=${WORK}/config "${STUDIO}"
                        --script "${WORK}/bad_number.txt"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "'train many' was accepted")
endif()
expect_text("${err}" "bad_number.txt:1: train: iteration count 'many' is not a whole number")

execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CONFIG_HOME=${WORK}/config "${STUDIO}"
                        --script "${WORK}/missing.txt"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "a missing script file was accepted")
endif()
expect_text("${err}" "missing.txt: no such script file")

if(GUI_SKIP)
  return()
endif()
file(WRITE "${WORK}/bad_open.txt" "open ${WORK}/no_such_scene\nquit\n")
studio_run("${WORK}/bad_open.txt" R)
if(GUI_SKIP)
  return()
endif()
if(R_RC EQUAL 0)
  message(FATAL_ERROR "opening a missing path in a script succeeded\n${R_OUT}")
endif()
expect_text("${R_ERR}" "bad_open.txt:1: open: ")
expect_text("${R_ERR}" "no_such_scene: no such file or folder")

file(WRITE "${WORK}/bad_channel.txt" "open ${RESOURCES}/default_scene\nchannel 0 glossy\nquit\n")
studio_run("${WORK}/bad_channel.txt" R)
if(R_RC EQUAL 0)
  message(FATAL_ERROR "showing an unavailable channel succeeded\n${R_OUT}")
endif()
expect_text("${R_ERR}" "bad_channel.txt:2: channel: channel glossy: needs an intrinsic run")

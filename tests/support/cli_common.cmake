# Helpers for the CLI test scripts (tests/cli/*.cmake, run with -DGORIS=<goris binary>):
#   include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
# goris_ok(ARGS...)               runs goris, fails the test unless it exits 0; sets OUT and ERR
# goris_fails(EXPECTED ARGS...)   runs goris, fails the test unless it exits non-zero with EXPECTED in stderr
# expect_text(TEXT WHAT)          fails the test unless WHAT occurs in TEXT
function(goris_ok)
  execute_process(COMMAND "${GORIS}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "goris ${ARGN} exited with ${rc}\n${out}\n${err}")
  endif()
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

function(goris_fails expected)
  execute_process(COMMAND "${GORIS}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "goris ${ARGN} succeeded, expected an error containing '${expected}'\n${out}")
  endif()
  string(FIND "${err}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "goris ${ARGN}: expected '${expected}' in the error, got:\n${err}")
  endif()
endfunction()

function(expect_text text what)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected '${what}' in:\n${text}")
  endif()
endfunction()

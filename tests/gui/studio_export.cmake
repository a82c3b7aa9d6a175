# Exports from the scripted editor, through the Export dialog's code path: train the embedded scene a few
# dozen iterations in intrinsic mode, open the Export dialog, export the intrinsic PLY, a baked PLY (a short
# distillation) and orbit renders (started, screenshotted while it runs, waited for), check that the files
# read back (gui_export_check: PLY counts and properties, image sizes against cameras.json) and that the
# dialog shows in the screenshot; then an export to an unwritable path reports its error (the file and the
# problem) in the dialog and the status bar while the editor goes on, and as a script failure (exit 1 with
# the line) when a blocking `export` fails. Screenshots stay in WORK as artefacts.
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
if(GUI_SKIP)
  return()
endif()

file(WRITE "${WORK}/config/goris-studio/settings.json" "{\"display_max_side\": 160}\n")
file(WRITE "${WORK}/blocker.txt" "a file where the export wants a folder\n")
set(ex "${WORK}/exports")
set(script "${WORK}/export.txt")
file(WRITE "${script}" "# written by tests/gui/studio_export.cmake
open ${RESOURCES}/default_scene
out ${WORK}/run
set mode intrinsic
set random_init_points 3000
set random_init_box_ratio 0.15
set resolution 64
set checkpoint_interval 0
set intrinsic_env_resolution 8
train 30
grid 2
screenshot ${WORK}/no_dialog.png
export_dialog
export ply ${ex}/model.ply
export baked ${ex}/baked.ply 20
export_start renders ${ex}/renders orbit 6
screenshot_now ${WORK}/export_running.png
export_wait
screenshot ${WORK}/export_dialog.png
export_start ply ${WORK}/blocker.txt/model.ply
expect_export_error is not a folder
screenshot ${WORK}/export_error.png
export_dialog close
quit
")
string(TIMESTAMP t0 "%s")
studio_run("${script}" R)
string(TIMESTAMP t1 "%s")
if(GUI_SKIP)
  return()
endif()
math(EXPR seconds "${t1} - ${t0}")
message("${R_OUT}\n(the editor ran ${seconds} s)")
if(NOT R_RC EQUAL 0)
  message(FATAL_ERROR "goris-studio --script exited with ${R_RC}\n${R_OUT}\n${R_ERR}")
endif()
expect_text("${R_OUT}" "trained to iteration 30")
expect_text("${R_OUT}" "export done: exported ${ex}/model.ply")
expect_text("${R_OUT}" "export done: exported ${ex}/baked.ply")
expect_text("${R_OUT}" "export done: exported ${ex}/renders")
# The failure names the part, the file and the problem (stderr: the status bar's error messages).
expect_text("${R_ERR}" "export error: intrinsic PLY: ${WORK}/blocker.txt/model.ply: cannot write: ${WORK}/blocker.txt is not a folder")
if(EXISTS "${WORK}/blocker.txt/model.ply" OR NOT EXISTS "${WORK}/blocker.txt")
  message(FATAL_ERROR "the failed export touched ${WORK}/blocker.txt")
endif()
foreach(f no_dialog.png export_running.png export_dialog.png export_error.png exports/baked.json)
  if(NOT EXISTS "${WORK}/${f}")
    message(FATAL_ERROR "the scripted editor did not write ${f}\n${R_OUT}\n${R_ERR}")
  endif()
endforeach()
# Nothing half-written: no temporary files left among the exports.
file(GLOB_RECURSE leftovers "${ex}/*.tmp*" "${ex}/.*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

function(export_check)
  execute_process(COMMAND "${EXPORT_CHECK}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "gui_export_check ${ARGN}:\n${out}\n${err}")
  endif()
endfunction()
export_check(ply "${WORK}/run" "${ex}/model.ply" intrinsic)
export_check(ply "${WORK}/run" "${ex}/baked.ply" baked)
export_check(renders "${ex}/renders" 6)
export_check(dialog "${WORK}/export_dialog.png" "${WORK}/no_dialog.png")
export_check(dialog "${WORK}/export_error.png" "${WORK}/no_dialog.png")
file(READ "${ex}/baked.json" baked)
string(JSON iterations GET "${baked}" iterations)
if(NOT iterations EQUAL 20)
  message(FATAL_ERROR "the baked PLY was distilled for ${iterations} iterations, not 20:\n${baked}")
endif()
# The dialog's choices persist: the last export's part and path are in the saved settings.
file(READ "${WORK}/config/goris-studio/settings.json" settings)
string(JSON last_ply GET "${settings}" export_ply_path)
string(JSON baked_iters GET "${settings}" export_baked_iterations)
if(NOT last_ply STREQUAL "${WORK}/blocker.txt/model.ply" OR NOT baked_iters EQUAL 20)
  message(FATAL_ERROR "the export choices were not remembered:\n${settings}")
endif()

# A blocking `export` that fails ends the script with its line and the problem, exit status 1 (no crash:
# a signal shows as a text or a status above 128; xvfb-run itself may turn a status into 5 when it cannot
# clean up its temporary folder, so the message printed on the way out is what is checked).
file(WRITE "${WORK}/export_fails.txt" "open ${WORK}/run\nexport ply ${WORK}/blocker.txt/again.ply\nquit\n")
studio_run("${WORK}/export_fails.txt" F)
if(NOT F_RC MATCHES "^[0-9]+$" OR F_RC EQUAL 0 OR F_RC GREATER 127)
  message(FATAL_ERROR "a failing export should exit with status 1, got ${F_RC}\n${F_OUT}\n${F_ERR}")
endif()
expect_text("${F_ERR}" "error: ${WORK}/export_fails.txt:2: export: the export ended error (expected done): intrinsic PLY: ${WORK}/blocker.txt/again.ply: cannot write: ${WORK}/blocker.txt is not a folder")

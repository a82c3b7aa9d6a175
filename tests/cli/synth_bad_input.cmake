# `goris synth` bad input: a missing Blender names the apt command, an unknown preset lists the presets, a
# table roughness out of [0, 1] or for a preset without a table, an unknown table shape and too many objects
# are refused, and nothing is written under
# --out; neither --out nor --train-after, both, or --train-after of a folder that is no synth output are
# refused by name. Needs no Blender.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
function(expect_fail what)
  execute_process(COMMAND "${GORIS}" synth ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "goris synth ${ARGN} succeeded")
  endif()
  string(FIND "${out}${err}" "${what}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected '${what}' in:\n${out}${err}")
  endif()
endfunction()
expect_fail("sudo apt-get install blender" --out "${WORK}/a" --blender "${WORK}/no-blender")
expect_fail("twin-mirrors" --preset nope --out "${WORK}/b")
expect_fail("--table-roughness" --table-roughness 1.5 --out "${WORK}/c")
expect_fail("preset 'lambert-room' has no table top" --preset lambert-room --table-roughness 0 --out "${WORK}/d")
expect_fail("--table-shape: unknown value 'hexagon' (round, rect, floor)" --table-shape hexagon --out "${WORK}/e")
expect_fail("--objects must be between 0 and 6" --objects 9 --out "${WORK}/f")
expect_fail("--out (or --train-after DATA)")
expect_fail("excludes" --out "${WORK}/g" --train-after "${WORK}")
expect_fail("${WORK}: is not a `goris synth` data set (no scene.json)" --train-after "${WORK}")
if(EXISTS "${WORK}/train_after" OR EXISTS "${WORK}/train_after.synth-tmp" OR EXISTS "${WORK}/g")
  message(FATAL_ERROR "a refused --train-after left files behind")
endif()
if(EXISTS "${WORK}/a" OR EXISTS "${WORK}/b" OR EXISTS "${WORK}/c" OR EXISTS "${WORK}/d" OR EXISTS "${WORK}/e"
   OR EXISTS "${WORK}/f")
  message(FATAL_ERROR "a failed goris synth left files under --out")
endif()

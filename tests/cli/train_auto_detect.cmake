# `goris train --mode auto` on the embedded default scene: with its glossy masks (they mark the table:
# intrinsic from the start, the same model as --mode intrinsic), and with them hidden (radiance through the warm-up, then the glossy
# detection decides; the masks and summary land in RUN/detected_gloss, config.json carries the decision,
# and --resume continues in the decided mode).
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(DATA "${RESOURCES}/default_scene")
# 40 iterations at 32 px; the warm-up (15000 of 30000, scaled) ends after iteration 20, and the detection
# does not wait for settled geometry (intrinsic_detect_settled, tried at the end).
set(common --resolution 32 --device cpu --init-points 3000 --iters 40 --set intrinsic_warmup=15000
    --set intrinsic_env_resolution=8 --set intrinsic_net_hidden_layers=1 --set intrinsic_detect_settled=0)

goris_ok(train "${DATA}" --out "${WORK}/masks" --mode auto ${common})
expect_text("${OUT}" "--mode auto: intrinsic (the glossy masks mark")
# ... and then trains exactly what --mode intrinsic trains: CPU training repeats bit for bit, so the two
# models are the same file (a glossy scene's `auto` costs and scores what `full` does).
goris_ok(train "${DATA}" --out "${WORK}/intrinsic" --mode intrinsic ${common})
file(SHA256 "${WORK}/masks/point_cloud.ply" auto_ply)
file(SHA256 "${WORK}/intrinsic/point_cloud.ply" intrinsic_ply)
if(NOT auto_ply STREQUAL intrinsic_ply)
  message(FATAL_ERROR "--mode auto with glossy masks and --mode intrinsic trained different models")
endif()

set(RUN "${WORK}/detect")
goris_ok(train "${DATA}" --out "${RUN}" --mode auto ${common} --set use_glossy_masks=false)
expect_text("${OUT}" "--mode auto: radiance (no glossy masks")
expect_text("${OUT}" "--mode auto after iteration 20:")
expect_text("${OUT}" "done: 40 iterations")
file(READ "${RUN}/detected_gloss/summary.json" summary)
string(JSON decision GET "${summary}" decision)
string(JSON covered GET "${summary}" covered_pixels)
string(JSON seconds GET "${summary}" seconds)
if(NOT covered GREATER 0)
  message(FATAL_ERROR "the detection saw no covered pixels:\n${summary}")
endif()
if(NOT EXISTS "${RUN}/detected_gloss/gloss_r_000.png")
  message(FATAL_ERROR "no detected mask written")
endif()
file(READ "${RUN}/config.json" cfg)
string(JSON mode GET "${cfg}" mode)
string(JSON pending GET "${cfg}" auto_detect_glossy)
if(NOT mode STREQUAL decision OR NOT pending STREQUAL "OFF")
  message(FATAL_ERROR "config.json: mode ${mode}, auto_detect_glossy ${pending}; the detection decided ${decision}")
endif()
if(decision STREQUAL "intrinsic")
  expect_text("${OUT}" "-> intrinsic from now on")
  set(env_expected TRUE)
else()
  expect_text("${OUT}" "-> radiance to the end")
  set(env_expected FALSE)
endif()
if(EXISTS "${RUN}/environment.png")
  set(env_found TRUE)
else()
  set(env_found FALSE)
endif()
if(NOT env_found STREQUAL env_expected)
  message(FATAL_ERROR "environment.png written: ${env_found}, decision ${decision}")
endif()

# Resumed: the decided mode without a second detection.
goris_ok(train "${DATA}" --out "${RUN}" --resume --iters 44 --device cpu)
expect_text("${OUT}" "resuming")
expect_text("${OUT}" "done: 44 iterations")
string(FIND "${OUT}" "--mode auto" again)
if(NOT again EQUAL -1)
  message(FATAL_ERROR "the resumed run decided again:\n${OUT}")
endif()
file(READ "${RUN}/config.json" cfg)
string(JSON mode2 GET "${cfg}" mode)
if(NOT mode2 STREQUAL decision)
  message(FATAL_ERROR "resumed run is ${mode2}, the detection decided ${decision}")
endif()

# Forced to intrinsic (every scored pixel counts): the switch through the CLI, and its resume.
set(RUN2 "${WORK}/forced")
goris_ok(train "${DATA}" --out "${RUN2}" --mode auto ${common} --set use_glossy_masks=false
         --set intrinsic_detect_threshold=0 --set intrinsic_detect_fraction=0)
expect_text("${OUT}" "-> intrinsic from now on")
if(NOT EXISTS "${RUN2}/environment.png")
  message(FATAL_ERROR "the switched run wrote no environment.png")
endif()
goris_ok(train "${DATA}" --out "${RUN2}" --resume --iters 42 --device cpu)
expect_text("${OUT}" "intrinsic mode: 40/40 views with glossy masks")

# Decided late (the geometry "settles" at 40, the run's end), forced glossy: the run grows by the planned
# 20 shading iterations.
set(RUN3 "${WORK}/late")
goris_ok(train "${DATA}" --out "${RUN3}" --mode auto ${common} --set use_glossy_masks=false
         --set intrinsic_detect_threshold=0 --set intrinsic_detect_fraction=0 --set intrinsic_detect_settled=40)
expect_text("${OUT}" "--mode auto after iteration 40:")
expect_text("${OUT}" "the run grows by 20 iterations")
expect_text("${OUT}" "done: 60 iterations")
file(READ "${RUN3}/config.json" cfg)
string(JSON iters GET "${cfg}" iterations)
if(NOT iters EQUAL 60)
  message(FATAL_ERROR "config.json of the lengthened run says ${iters} iterations")
endif()

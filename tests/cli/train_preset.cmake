# Presets and config.json versions end to end on the embedded default scene: `goris train --preset NAME` and
# `--preset FILE` put the preset's settings in config.json (later --set lines win); a bad preset file is
# refused naming the file and the problem; a run folder whose config.json an older version wrote (no
# config_version, a removed setting at its off value) still renders, with a note; `goris config --reference`
# is the committed docs/reference/train-options.md.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(common --iters 2 --resolution 32 --device cpu --init-points 500 --checkpoint-every 0)

goris_ok(train "${RESOURCES}/default_scene" --out "${WORK}/named" --preset planar-glossy
         --set intrinsic_env_distance=1.2 ${common})
file(READ "${WORK}/named/config.json" cfg)
foreach(expected "\"intrinsic_glossy_plane\": true" "\"intrinsic_glossy_plane_align\": true"
                 "\"intrinsic_material_losses_in_warmup\": false" "\"intrinsic_trace_glossy_transparent\": 0.5"
                 "\"intrinsic_env_distance\": 1.2" "\"config_version\": 3")
  expect_text("${cfg}" "${expected}")
endforeach()

file(WRITE "${WORK}/mine.json" "{\"description\": \"mine\", \"settings\": {\"alpha_weight\": 0.5, \"max_sh_degree\": 1}}")
goris_ok(train "${RESOURCES}/default_scene" --out "${WORK}/file" --preset "${WORK}/mine.json" ${common})
file(READ "${WORK}/file/config.json" cfg)
expect_text("${cfg}" "\"alpha_weight\": 0.5")
expect_text("${cfg}" "\"max_sh_degree\": 1")

file(WRITE "${WORK}/typo.json" "{\"description\": \"x\", \"settings\": {\"alpha_wieght\": 0.5}}")
file(WRITE "${WORK}/value.json" "{\"description\": \"x\", \"settings\": {\"max_sh_degree\": \"high\"}}")
file(WRITE "${WORK}/broken.json" "{\"description\": \"x\", \"settings\": {")
goris_fails("unknown setting 'alpha_wieght'" train "${RESOURCES}/default_scene" --out "${WORK}/bad" --preset "${WORK}/typo.json")
goris_fails("${WORK}/typo.json" train "${RESOURCES}/default_scene" --out "${WORK}/bad" --preset "${WORK}/typo.json")
goris_fails("'max_sh_degree' must be a whole number" train "${RESOURCES}/default_scene" --out "${WORK}/bad"
            --preset "${WORK}/value.json")
goris_fails("${WORK}/broken.json: malformed JSON" train "${RESOURCES}/default_scene" --out "${WORK}/bad"
            --preset "${WORK}/broken.json")
goris_fails("unknown preset" train "${RESOURCES}/default_scene" --out "${WORK}/bad" --preset shiny)

# The first run's config.json as a version-1 file with a setting removed since (off): render opens it.
file(READ "${WORK}/named/config.json" cfg)
string(REPLACE "\"config_version\": 3," "\"intrinsic_prune_mirror_world_plane\": false," cfg "${cfg}")
file(WRITE "${WORK}/named/config.json" "${cfg}")
goris_ok(render "${WORK}/named" --out "${WORK}/renders" --device cpu)
expect_text("${ERR}" "written by an older version (config_version 1)")
expect_text("${ERR}" "'intrinsic_prune_mirror_world_plane' dropped")

goris_ok(config --presets)
expect_text("${OUT}" "planar-glossy")
goris_ok(config)
expect_text("${OUT}" "iterations")
goris_ok(config --reference)
file(READ "${RESOURCES}/../docs/reference/train-options.md" committed)
if(NOT OUT STREQUAL committed)
  message(FATAL_ERROR "docs/reference/train-options.md differs from `goris config --reference`; regenerate it:\n"
                      "  build/bin/goris config --reference > docs/reference/train-options.md")
endif()

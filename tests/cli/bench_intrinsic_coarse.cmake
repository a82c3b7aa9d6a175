# Coarse tracing end to end on the embedded default scene: a short intrinsic `goris train` with
# intrinsic_coarse_tracing=true reports the rays it traced and saved, and `goris bench intrinsic
# --coarse-tracing both` times the fully traced and the coarse frame of the same view with their ray counts,
# the PSNR between them and the pixels its roughness net ran on; --resolution renders the same view at another
# width (the frame-rate line names it) and --kernels adds the time of each launch site (parallel_for, the blend, the CPU tracer); a bad
# key value is refused.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(RUN "${WORK}/run")

goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode intrinsic --iters 40 --resolution 48 --device cpu
         --init-points 3000 --checkpoint-every 0 --set intrinsic_coarse_tracing=true)
expect_text("${OUT}" "done: 40 iterations")
expect_text("${OUT}" "reflection rays:")
expect_text("${OUT}" "saved by coarse tracing")
file(READ "${RUN}/config.json" cfg)
expect_text("${cfg}" "\"intrinsic_coarse_tracing\": true")

goris_ok(bench intrinsic "${RUN}" --repeats 1 --coarse-tracing both --device cpu)
expect_text("${OUT}" "coarse tracing off:")
expect_text("${OUT}" "coarse tracing on:")
expect_text("${OUT}" "| coarse tracing | rays traced | rays saved |")
expect_text("${OUT}" "PSNR of the coarse frame against the fully traced one")
string(REGEX MATCH "\\| off \\| ([0-9]+) / ([0-9]+) \\| 0\\.0 %" off_row "${OUT}")
if(NOT off_row OR NOT CMAKE_MATCH_1 EQUAL CMAKE_MATCH_2 OR CMAKE_MATCH_2 EQUAL 0)
  message(FATAL_ERROR "fully traced row: every glossy pixel should be traced\n${OUT}")
endif()
# The roughness net runs on the surface pixels' window: some pixels, at most all of them.
string(REGEX MATCH "roughness net on ([0-9]+) of ([0-9]+) pixels" net_line "${OUT}")
if(NOT net_line OR CMAKE_MATCH_1 EQUAL 0 OR CMAKE_MATCH_1 GREATER CMAKE_MATCH_2 OR NOT CMAKE_MATCH_2 EQUAL 2304)
  message(FATAL_ERROR "the roughness net's window line: 1 to 2304 (48 x 48) pixels expected\n${OUT}")
endif()
string(REGEX MATCH "\\| on \\| ([0-9]+) / ([0-9]+) \\|" on_row "${OUT}")
if(NOT on_row OR NOT CMAKE_MATCH_1 LESS CMAKE_MATCH_2)
  message(FATAL_ERROR "coarse row: fewer rays than glossy pixels expected\n${OUT}")
endif()

goris_ok(bench intrinsic "${RUN}" --repeats 1 --resolution 96 --device cpu)
expect_text("${OUT}" "at 96x96")
expect_text("${OUT}" "traced shading frame at 96x96, coarse tracing on:")

goris_ok(bench intrinsic "${RUN}" --repeats 1 --kernels --device cpu)
expect_text("${OUT}" "launch sites over the 1 timed iterations")
expect_text("${OUT}" "| launch site | where | calls | total ms |")
expect_text("${OUT}" "goris::shading::ops::shade<float> | shading_ops.h:")
expect_text("${OUT}" "goris::raster::forward_cpu<float> | raster_forward_cpu.cpp:")
expect_text("${OUT}" "goris::trace::forward_cpu<float, lambda> | trace_cpu.h:")

goris_fails("intrinsic_coarse_max_level" train "${RESOURCES}/default_scene" --out "${WORK}/bad" --mode intrinsic
            --iters 5 --set intrinsic_coarse_max_level=7)

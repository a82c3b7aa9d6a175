# `goris export --spz --compressed-ply --splat --glb` on tiny runs of the embedded scene: an intrinsic run (the
# formats hold the distilled model, one distillation shared with --baked) and a radiance run (the model
# itself); `goris info` names each format and its count, `info --against` measures the quantization against
# the baked PLY, `goris render --model` renders an export with the run's cameras; a bad name or a damaged
# file is refused with a message naming it.
file(REMOVE_RECURSE "${WORK}")
set(RUN "${WORK}/run")
set(OUTD "${WORK}/out")
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(MAKE_DIRECTORY "${OUTD}")  # outputs go into existing folders

goris_fails("needs a file name ending in .spz" export "${WORK}/no_such_run" --spz "${OUTD}/a.ply")
goris_fails("needs a file name ending in .compressed.ply" export "${WORK}/no_such_run" --compressed-ply "${OUTD}/a.ply")

goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode intrinsic --iters 30 --resolution 48 --device cpu
         --init-points 2000 --checkpoint-every 0 --set intrinsic_env_resolution=8)
goris_ok(export "${RUN}" --baked "${OUTD}/baked.ply" --spz "${OUTD}/m.spz" --compressed-ply "${OUTD}/m.compressed.ply"
         --splat "${OUTD}/m.splat" --glb "${OUTD}/m.glb" --iters 10 --device cpu)
expect_text("${OUT}" "spz: wrote ${OUTD}/m.spz (Niantic SPZ")
expect_text("${OUT}" "compressed-ply: wrote")
expect_text("${OUT}" "splat: wrote")
expect_text("${OUT}" "glb: wrote")

goris_ok(info "${OUTD}/baked.ply")
string(REGEX MATCH "([0-9]+) Gaussians" m "${OUT}")
set(count "${CMAKE_MATCH_1}")
foreach(f m.spz m.compressed.ply m.splat m.glb)
  goris_ok(info "${OUTD}/${f}" --against "${OUTD}/baked.ply")
  expect_text("${OUT}" "${count} Gaussians")
  expect_text("${OUT}" "against ${OUTD}/baked.ply")
  expect_text("${OUT}" "rotation  max")
endforeach()
goris_ok(info "${OUTD}/m.spz")
expect_text("${OUT}" "Niantic SPZ version 3")
goris_ok(info "${OUTD}/m.compressed.ply")
expect_text("${OUT}" "PlayCanvas compressed PLY")

goris_ok(render "${RUN}" --model "${OUTD}/m.spz" --out "${OUTD}/spz_renders" --device cpu)
file(GLOB pngs "${OUTD}/spz_renders/*.png")
list(LENGTH pngs n)
if(n LESS 1)
  message(FATAL_ERROR "goris render --model m.spz wrote no PNG")
endif()

# A radiance run: the formats hold its model without a distillation.
goris_ok(train "${RESOURCES}/default_scene" --out "${WORK}/radiance" --mode radiance --iters 20 --resolution 48 --device cpu
         --init-points 2000 --checkpoint-every 0)
goris_ok(export "${WORK}/radiance" --spz "${OUTD}/r.spz" --splat "${OUTD}/r.splat" --device cpu)
string(FIND "${OUT}" "distill" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "a radiance run's standard formats needed no distillation:\n${OUT}")
endif()
goris_ok(info "${OUTD}/r.spz" --against "${WORK}/radiance/point_cloud.ply")

# Damaged files: the error names the file and the problem.
execute_process(COMMAND head -c 100 "${OUTD}/m.spz" OUTPUT_FILE "${WORK}/cut.spz" RESULT_VARIABLE rc)  # CMake cannot cut binaries
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK}/cut.spz")
  message(FATAL_ERROR "could not write ${WORK}/cut.spz")
endif()
goris_fails("${WORK}/cut.spz: the gzip stream is truncated" info "${WORK}/cut.spz")
file(WRITE "${WORK}/odd.splat" "0123456789")
goris_fails("${WORK}/odd.splat: truncated or corrupt: 10 bytes is not a multiple of 32" info "${WORK}/odd.splat")
goris_fails("${WORK}/odd.splat" render "${RUN}" --model "${WORK}/odd.splat" --out "${OUTD}/x" --device cpu)

# Videos: a turntable of seconds * fps frames and a before | after one, each read back by OpenCV before it is
# renamed into place (write_video fails when the count or size read back differs); a bad name is refused.
goris_ok(export "${WORK}/radiance" --video "${OUTD}/orbit.mp4" --seconds 1 --fps 6 --device cpu)
expect_text("${OUT}" "video: 6 orbit frames at 48x")
if(NOT EXISTS "${OUTD}/orbit.mp4" OR EXISTS "${OUTD}/.orbit.partial.mp4")
  message(FATAL_ERROR "goris export --video left no orbit.mp4, or its temporary file")
endif()
goris_ok(export "${WORK}/radiance" --video "${OUTD}/ba.mp4" --before "${RUN}" --path test --fps 4 --device cpu)
expect_text("${OUT}" "test frames at 96x")
expect_text("${OUT}" "before | after")
goris_fails("the name must end in .mp4" export "${WORK}/radiance" --video "${OUTD}/orbit.avi" --device cpu)

# Channels (--channel): the intrinsic run's glossy term as a video, the radiance run's depth as PNG frames
# (cameras.json names the channel); an intrinsic channel of a radiance run, a removal mask, an unknown name
# and --channel without --renders or --video are refused.
goris_ok(export "${RUN}" --video "${OUTD}/glossy.mp4" --channel glossy --seconds 1 --fps 4 --device cpu)
expect_text("${OUT}" "video: 4 orbit frames of glossy at")
goris_ok(export "${WORK}/radiance" --renders "${OUTD}/depth" --channel depth --frames 2 --device cpu)
expect_text("${OUT}" "renders: 2 test frames of depth")
file(READ "${OUTD}/depth/cameras.json" cams)
string(FIND "${cams}" "\"channel\": \"depth\"" at)
if(at EQUAL -1)
  message(FATAL_ERROR "cameras.json of --channel depth does not name its channel:\n${cams}")
endif()
goris_fails("channel 'glossy' needs an intrinsic run" export "${WORK}/radiance" --video "${OUTD}/g.mp4" --channel glossy --device cpu)
goris_fails("channel 'inpaint_mask' is a mask of the training views" export "${RUN}" --renders "${OUTD}/m" --channel inpaint_mask --device cpu)
goris_fails("unknown channel 'shiny'" export "${RUN}" --video "${OUTD}/s.mp4" --channel shiny --device cpu)
goris_fails("--channel chooses what --renders and --video show" export "${RUN}" --ply "${OUTD}/c.ply" --channel depth --device cpu)

# Training from an exported model (--init): the run starts from its Gaussians, so one iteration from the
# radiance run's SPZ renders the test views far better than one from random points; a missing file and
# --init on a resume are refused.
goris_ok(info "${OUTD}/r.spz")
string(REGEX MATCH "([0-9]+) Gaussians" m "${OUT}")
set(r_count "${CMAKE_MATCH_1}")
goris_ok(train "${RESOURCES}/default_scene" --out "${WORK}/from_spz" --init "${OUTD}/r.spz" --iters 1 --resolution 48
         --device cpu --checkpoint-every 0)
expect_text("${OUT}" "initial model: ${r_count} Gaussians from ${OUTD}/r.spz")
goris_ok(train "${RESOURCES}/default_scene" --out "${WORK}/from_random" --iters 1 --resolution 48 --device cpu
         --init-points 2000 --checkpoint-every 0)
foreach(run from_spz from_random)
  goris_ok(eval "${WORK}/${run}" --split test --device cpu)
  string(REGEX MATCH "PSNR ([0-9.]+) dB" m "${OUT}")
  set(psnr_${run} "${CMAKE_MATCH_1}")
endforeach()
if(NOT psnr_from_spz GREATER psnr_from_random)  # both parse as real numbers
  message(FATAL_ERROR "one iteration from the SPZ (${psnr_from_spz} dB) is not better than from random points (${psnr_from_random} dB)")
endif()
message("one iteration: from the SPZ ${psnr_from_spz} dB, from random points ${psnr_from_random} dB")
goris_fails("no_such.spz: --init: model file not found" train "${RESOURCES}/default_scene" --out "${WORK}/nothing"
            --init "${WORK}/no_such.spz" --iters 1 --device cpu)
goris_fails("settings cannot change when resuming (the run keeps its settings): init_model" train "${RESOURCES}/default_scene" --out "${WORK}/from_random"
            --resume --init "${OUTD}/r.spz" --iters 2 --device cpu)

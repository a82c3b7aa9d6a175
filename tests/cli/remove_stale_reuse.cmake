# A finished fine-tune in RUN/removal is reused only for the same inputs: after a new selection or other
# options, `goris remove` starts the fine-tune over (saying what changed) instead of resuming the old
# checkpoint, so report.json's counts add up and the result is the new one. A measurement run with
# --fill-truth is one more change of inputs.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(RUN "${WORK}/run")
set(R "${RUN}/removal")

# The fine-tune neither adds nor removes Gaussians: after = before - selected + added by the lift.
function(expect_counts_add_up)
  file(READ "${R}/report.json" report)
  string(JSON before GET "${report}" gaussians_before)
  string(JSON selected GET "${report}" selected)
  string(JSON added GET "${report}" added_by_lift)
  string(JSON after GET "${report}" gaussians_after)
  math(EXPR want "${before} - ${selected} + ${added}")
  if(NOT after EQUAL want)
    message(FATAL_ERROR "report.json: ${after} Gaussians after, expected ${before} - ${selected} + ${added} = ${want} "
                        "(a stale fine-tune was resumed?)\n${report}")
  endif()
endfunction()

goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode radiance --iters 20 --resolution 64 --device cpu
         --init-points 2000 --checkpoint-every 0)
goris_ok(select "${RUN}" --masks --device cpu)
goris_ok(remove "${RUN}" --iters 10 --device cpu)
expect_counts_add_up()
file(READ "${R}/report.json" first)
string(JSON first_selected GET "${first}" selected)
file(SHA256 "${R}/point_cloud.ply" first_ply)

# The same inputs again: nothing starts over.
goris_ok(remove "${RUN}" --iters 10 --device cpu)
string(FIND "${OUT}" "started over" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "the same inputs restarted the fine-tune:\n${OUT}")
endif()

# A different selection: the fine-tune starts over and says the selection changed.
goris_ok(select "${RUN}" --masks --dilate 1 --device cpu)
goris_ok(remove "${RUN}" --iters 10 --device cpu)
expect_text("${OUT}" "the fine-tune started over")
expect_text("${OUT}" "selection")
expect_counts_add_up()
file(READ "${R}/report.json" second)
string(JSON second_selected GET "${second}" selected)
if(second_selected EQUAL first_selected)
  message(FATAL_ERROR "the test needs a different selection: --dilate 1 selected ${second_selected} again")
endif()
file(SHA256 "${R}/point_cloud.ply" second_ply)
if(second_ply STREQUAL first_ply)
  message(FATAL_ERROR "removal/point_cloud.ply is the previous result after a new selection")
endif()

# Other options: the same, naming the option.
goris_ok(remove "${RUN}" --iters 10 --device cpu --ablate shadows)
expect_text("${OUT}" "the fine-tune started over")
expect_text("${OUT}" "options.ablate")
expect_counts_add_up()

# A map of the 2D inpainting removed by hand: its record is no cache any more; the maps are made again and the
# removal finishes with the same result.
file(SHA256 "${R}/point_cloud.ply" ablated_ply)
file(GLOB maps "${R}/inpainted/*_rgb.npy")
list(LENGTH maps n_maps)
if(n_maps EQUAL 0)
  message(FATAL_ERROR "no inpainted colour maps in ${R}/inpainted")
endif()
list(GET maps 0 gone)
file(REMOVE "${gone}")
goris_ok(remove "${RUN}" --iters 10 --device cpu --ablate shadows)
if(NOT EXISTS "${gone}")
  message(FATAL_ERROR "${gone} was not made again")
endif()
file(SHA256 "${R}/point_cloud.ply" again_ply)
if(NOT again_ply STREQUAL ablated_ply)
  message(FATAL_ERROR "removal/point_cloud.ply changed when only the inpainted maps were made again")
endif()

# --fill-truth (the fills' measurement): a folder without the views' images is refused before any work, by
# the missing file's name, and the removal there stays as it was; with one (here the training photos stand in
# for renders without the target) the fine-tune starts over naming the option, and report.json counts the
# pixels it replaced.
goris_fails("${WORK}/no-truth/r_000.png: missing" remove "${RUN}" --iters 10 --device cpu --fill-truth "${WORK}/no-truth")
file(SHA256 "${R}/point_cloud.ply" kept_ply)
if(NOT kept_ply STREQUAL again_ply)
  message(FATAL_ERROR "a refused --fill-truth changed removal/point_cloud.ply")
endif()
file(GLOB photos "${RESOURCES}/default_scene/train/r_*.png")
file(COPY ${photos} DESTINATION "${WORK}/truth")
goris_ok(remove "${RUN}" --iters 10 --device cpu --ablate shadows --fill-truth "${WORK}/truth")
expect_text("${OUT}" "the fine-tune started over")
expect_text("${OUT}" "options.fill_truth")
expect_counts_add_up()
file(READ "${R}/report.json" truth_report)
string(JSON replaced GET "${truth_report}" fill_truth_pixels)
if(NOT replaced GREATER 0)
  message(FATAL_ERROR "--fill-truth replaced no pixel:\n${truth_report}")
endif()
# ... and measures the photos it trains on against those images: here they are the photos themselves.
string(JSON trained GET "${truth_report}" photo_targets_against_truth trained_pixels)
string(JSON taken GET "${truth_report}" photo_targets_against_truth photos_as_taken)
if(NOT trained GREATER 0 OR NOT taken MATCHES "^0(\\.0+)?$")
  message(FATAL_ERROR "photos against themselves as the truth: ${trained} pixels, error ${taken}:\n${truth_report}")
endif()
# goris info says that this removal folder is a measurement, not a cleaned scene.
goris_ok(info "${RUN}")
expect_text("${OUT}" "a measurement, not a removal: fine-tuned with the true images")
expect_text("${OUT}" "the photos it trains on carry 0.000 of the target's imprint as taken")

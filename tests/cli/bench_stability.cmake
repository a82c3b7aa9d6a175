# `goris bench stability` on the embedded scene (as the glossy scene: no Blender, no ../shared) with the
# hidden seconds-long `tiny` schedule: three cases and their reference each run in child processes (the
# single-view one stage 1 only); results.csv / results.md carry the finite-output verdict, the metrics and
# the differences to the reference; a second run reuses them; bad names and missing inputs are refused; a
# case that cannot finish is recorded and makes the bench exit non-zero.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(OUTDIR "${WORK}/bench")
set(SCENE "${RESOURCES}/default_scene")

goris_fails("unknown case 'nope'" bench stability --out "${OUTDIR}" --cases reference,nope --schedule tiny
            --device cpu --glossy-data "${SCENE}")
goris_fails("no normal-prior maps" bench stability --out "${OUTDIR}" --cases no_normal_prior --schedule tiny
            --device cpu --glossy-data "${SCENE}")
goris_fails("no data set 'lambert_room'" bench stability --out "${OUTDIR}" --cases lambert_room --schedule tiny
            --device cpu --datasets "${WORK}/no-datasets")
if(EXISTS "${OUTDIR}")
  message(FATAL_ERROR "a refused bench created ${OUTDIR}")
endif()

goris_ok(bench stability --out "${OUTDIR}" --cases weights_x5,no_glossy_mask,single_view --schedule tiny
         --device cpu --glossy-data "${SCENE}")
foreach(f results.csv results.md runs/reference/result.json runs/weights_x5/run/removal/metrics.json)
  if(NOT EXISTS "${OUTDIR}/${f}")
    message(FATAL_ERROR "bench stability wrote no ${f}:\n${OUT}")
  endif()
endforeach()

file(READ "${OUTDIR}/results.csv" csv)
expect_text("${csv}" "case,scene,reference,status,finished,finite,nan_skips,device,train_iters,gaussians,psnr,ssim,m_psnr,m_ssim,d_psnr,d_ssim,d_m_psnr,d_m_ssim,verdict,")
string(REGEX MATCHALL "\n[a-z_0-9.]+," rows "${csv}")
if(NOT rows STREQUAL "\nreference,;\nweights_x5,;\nno_glossy_mask,;\nsingle_view,")
  message(FATAL_ERROR "results.csv: expected the rows reference, weights_x5, no_glossy_mask, single_view (the "
                      "reference is "
                      "added by the bench), got ${rows}:\n${csv}")
endif()
# Finished, finite, no skipped steps, PSNR / SSIM / M-PSNR / M-SSIM after removal and the stage-1 PSNR / SSIM
# (against the views with the target); the cases also the differences to the reference and a verdict.
set(num "[0-9]+\\.[0-9]+")
set(dif "-?[0-9]+\\.[0-9]+")
if(NOT csv MATCHES "\nreference,glossy_table,,ok,yes,yes,0,cpu,30,[0-9]+,${num},${num},${num},${num},,,,,reference,${num},${num},,")
  message(FATAL_ERROR "reference row incomplete:\n${csv}")
endif()
foreach(c weights_x5 no_glossy_mask)
  if(NOT csv MATCHES "\n${c},glossy_table,reference,ok,yes,yes,0,cpu,30,[0-9]+,${num},${num},${num},${num},${dif},${dif},${dif},${dif},(stable|degrades),${num},${num},${dif},")
    message(FATAL_ERROR "${c} row incomplete:\n${csv}")
  endif()
endforeach()
# The single-view case is stage 1 only (nothing can be selected without masks): no removal metrics.
if(NOT csv MATCHES "\nsingle_view,glossy_table,reference,ok,yes,yes,0,cpu,30,[0-9]+,,,,,,,,,(stable|degrades),${num},${num},${dif},[0-9.]+,0.00,0.00,")
  message(FATAL_ERROR "single_view row incomplete:\n${csv}")
endif()

file(READ "${OUTDIR}/results.md" md)
expect_text("${md}" "| case | scene | status | finite | NaN skips | PSNR |")
expect_text("${md}" "| reference | glossy_table | ok | yes | 0 |")
expect_text("${md}" "| weights_x5 | glossy_table | ok | yes | 0 |")
expect_text("${md}" "| no_glossy_mask | glossy_table | ok | yes | 0 |")
expect_text("${md}" "| single_view | glossy_table | ok | yes | 0 |")
expect_text("${md}" "`weights_x5` (glossy_table, vs `reference`): normal-prior and smoothness loss weights x5")
expect_text("${md}" "Degrading cases (worst first):")
# The weights case trained with 5x the default weights (0.5 decaying to 0.001, 0.05); the embedded scene
# has no normal-prior maps, which the table notes.
file(READ "${OUTDIR}/runs/weights_x5/run/config.json" cfg)
expect_text("${cfg}" "\"intrinsic_smoothness\": 0.25")
expect_text("${cfg}" "\"intrinsic_normal_prior\": 2.5")
expect_text("${cfg}" "\"intrinsic_normal_prior_final\": 0.004999999")  # float 0.005
expect_text("${md}" "`weights_x5`: no normal prior: the scene has no train/gt/normal_*.exr")
# eval counted the non-finite rendered values (none), after removal and of stage 1.
file(READ "${OUTDIR}/runs/no_glossy_mask/run/removal/metrics.json" metrics)
expect_text("${metrics}" "\"non_finite_values\": 0")
file(READ "${OUTDIR}/runs/single_view/run/metrics_full.json" metrics)
expect_text("${metrics}" "\"non_finite_values\": 0")
expect_text("${metrics}" "full: test views with the target")

# Same options again: nothing reruns.
goris_ok(bench stability --out "${OUTDIR}" --cases weights_x5,no_glossy_mask,single_view --schedule tiny
         --device cpu --glossy-data "${SCENE}")
expect_text("${OUT}" "reference: reused")
expect_text("${OUT}" "no_glossy_mask: reused")
string(FIND "${OUT}" "goris train" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "a reused bench trained again:\n${OUT}")
endif()

# Without object masks `goris select --masks` fails: both cases are recorded as failed with the reason, the
# bench goes on, writes its tables and exits non-zero.
file(COPY "${SCENE}/" DESTINATION "${WORK}/nomask")
file(GLOB masks "${WORK}/nomask/train/mask_*.png")
file(REMOVE ${masks})
execute_process(COMMAND "${GORIS}" bench stability --out "${WORK}/failing" --cases no_glossy_mask --schedule tiny
                        --device cpu --glossy-data "${WORK}/nomask"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "a bench with failed cases exited 0:\n${out}")
endif()
file(READ "${WORK}/failing/results.csv" csv)
expect_text("${csv}" "\nreference,glossy_table,,failed,no,yes,")
expect_text("${csv}" "\nno_glossy_mask,glossy_table,reference,failed,no,yes,")
expect_text("${csv}" "select failed (exit code 1): error: masks:")
file(READ "${WORK}/failing/results.md" md)
expect_text("${md}" "`no_glossy_mask`: **failed**: select failed")

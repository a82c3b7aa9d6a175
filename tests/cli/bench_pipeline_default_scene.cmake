# `goris bench pipeline` on the embedded scene with the hidden seconds-long `tiny` schedule: two rungs of the
# ladder (baseline, full) each trained, selected, removed and evaluated in child processes; results.csv,
# results.md and the charts are written; a second run reuses both results, a copy of the folder its stage-1
# runs; bad names are refused.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(OUTDIR "${WORK}/bench")

goris_fails("unknown configuration 'nope'" bench pipeline --data "${RESOURCES}/default_scene" --configs baseline,nope
            --out "${OUTDIR}" --schedule tiny --device cpu)
goris_fails("not a data set folder" bench pipeline --data "${WORK}/missing" --configs baseline --out "${OUTDIR}"
            --schedule tiny --device cpu)
goris_fails("unknown suite 'nope' (generalization, fast, heldout)" bench pipeline --suite nope --out "${OUTDIR}")
goris_fails("give --data DIR... or --suite NAME" bench pipeline --out "${OUTDIR}")

goris_ok(bench pipeline --data "${RESOURCES}/default_scene" --configs baseline,full --out "${OUTDIR}"
         --schedule tiny --device cpu)
foreach(f results.csv results.md chart.svg chart.png chart_default_scene.svg chart_default_scene.png)
  if(NOT EXISTS "${OUTDIR}/${f}")
    message(FATAL_ERROR "bench pipeline wrote no ${f}:\n${OUT}")
  endif()
endforeach()

file(STRINGS "${OUTDIR}/results.csv" lines)
list(LENGTH lines n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "results.csv: expected a header and 2 rows, got ${n}:\n${lines}")
endif()
list(GET lines 0 header)
expect_text("${header}" "scene,config,schedule,status,device,train_iters,remove_iters,gaussians,psnr,ssim,m_psnr,m_ssim")
expect_text("${header}" "total_s,cpu_s,peak_host_mib,peak_device_mib")
list(GET lines 1 baseline)
list(GET lines 2 full)
expect_text("${baseline}" "default_scene,baseline,tiny,ok,cpu,30,10,")
expect_text("${full}" "default_scene,full,tiny,ok,cpu,30,10,")
# PSNR and the steps' CPU seconds are numbers (not empty) in both rows; on the CPU no step used GPU
# memory, so the device peak is empty.
cmake_policy(SET CMP0007 NEW)  # empty cells (a radiance run's G share) stay list elements: columns keep their index
string(REPLACE "," ";" header_cells "${header}")
list(FIND header_cells "cpu_s" cpu_col)
foreach(row "${baseline}" "${full}")
  string(REPLACE "," ";" cells "${row}")
  list(GET cells 8 psnr)
  list(GET cells ${cpu_col} cpu)
  if(NOT psnr MATCHES "^[0-9]+\\.[0-9]+$" OR NOT cpu MATCHES "^[0-9]+\\.[0-9]+$")
    message(FATAL_ERROR "no PSNR or CPU time in row: ${row}")
  endif()
  if(NOT row MATCHES ",[0-9]+,,(yes|no),")  # peak_host_mib, an empty peak_device_mib, reused
    message(FATAL_ERROR "a CPU run reported device memory, or no host peak: ${row}")
  endif()
endforeach()
# Where the reflections live: the intrinsic stage 1's share of the glossy colour in G is a fraction; a radiance
# stage 1 has none.
list(FIND header_cells "stage1_glossy_share" share_col)
string(REPLACE "," ";" cells "${baseline}")
list(GET cells ${share_col} share_baseline)
string(REPLACE "," ";" cells "${full}")
list(GET cells ${share_col} share_full)
if(share_col EQUAL -1 OR NOT share_baseline STREQUAL "" OR NOT share_full MATCHES "^0\\.[0-9]+$")
  message(FATAL_ERROR "results.csv: G share '${share_baseline}' (baseline) and '${share_full}' (full):\n${header}\n${baseline}\n${full}")
endif()
# Every step's child was asked for its device peak (written only by processes that used GPU memory).
if(NOT OUT MATCHES "peak [0-9]+ MiB")
  message(FATAL_ERROR "no per-step peak in the output:\n${OUT}")
endif()

file(READ "${OUTDIR}/results.md" md)
expect_text("${md}" "| default_scene | baseline | tiny | ok |")
expect_text("${md}" "| host MiB | device MiB |")
expect_text("${md}" "| default_scene | full | tiny | ok |")
expect_text("${md}" "![PSNR against time](chart.png)")
expect_text("${md}" "The chart and the ratios below use CPU time")  # auto: every step ran on the CPU
file(READ "${OUTDIR}/chart.svg" svg)
expect_text("${svg}" "<svg xmlns=")
expect_text("${svg}" "Pareto front")
expect_text("${svg}" "</svg>")
file(SIZE "${OUTDIR}/chart.png" png_size)
if(png_size LESS 5000)
  message(FATAL_ERROR "chart.png is only ${png_size} bytes")
endif()

# Same options again: nothing reruns.
goris_ok(bench pipeline --data "${RESOURCES}/default_scene" --configs baseline,full --out "${OUTDIR}"
         --schedule tiny --device cpu)
expect_text("${OUT}" "default_scene / tiny / baseline: reused")
expect_text("${OUT}" "default_scene / tiny / full: reused")
string(FIND "${OUT}" "goris train" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "a reused bench trained again:\n${OUT}")
endif()

# The choices beyond the ladder: baseline and full are reused, default (--mode auto) and sh1 run, and the
# table of each choice against full and baseline names them with their time ratios; default says what
# --mode auto decided.
goris_ok(bench pipeline --data "${RESOURCES}/default_scene" --configs baseline,full,default,sh1 --out "${OUTDIR}"
         --schedule tiny --device cpu)
expect_text("${OUT}" "default_scene / tiny / full: reused")
file(READ "${OUTDIR}/results.md" md)
expect_text("${md}" "| time vs full | ΔPSNR vs full | time vs baseline | ΔPSNR vs baseline |")
expect_text("${md}" "| default_scene | tiny | default |")
expect_text("${md}" "| default_scene | tiny | sh1 |")
expect_text("${md}" "default_scene / default / tiny: stage 1 finished as intrinsic")
expect_text("${md}" "Stage-1 runs (from their logs):")
expect_text("${md}" "default_scene / tiny / stage 1 `default`: --mode auto: intrinsic (the glossy masks mark")
expect_text("${md}" "default_scene / tiny / stage 1 `intrinsic`: reflection rays: ")
file(READ "${OUTDIR}/runs/default_scene/tiny/sh1/run/config.json" sh1_config)
expect_text("${sh1_config}" "\"max_sh_degree\": 1")

# A copy of the bench folder elsewhere keeps its stage-1 runs: a configuration not yet measured there trains
# nothing when its stage 1 (default's) is in the copy.
file(COPY "${OUTDIR}/" DESTINATION "${WORK}/bench_copy")
goris_ok(bench pipeline --data "${RESOURCES}/default_scene" --configs default-nofill --out "${WORK}/bench_copy"
         --schedule tiny --device cpu)
expect_text("${OUT}" "train    reused ${WORK}/bench_copy/runs/default_scene/tiny/stage1_default/run")
string(FIND "${OUT}" "goris train" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "a copied bench folder trained its stage 1 again:\n${OUT}")
endif()

# --report-only: tables from what is there; a configuration without a result is listed, nothing runs.
goris_ok(bench pipeline --data "${RESOURCES}/default_scene" --configs baseline,full,coarse --out "${OUTDIR}"
         --schedule tiny --device cpu --report-only)
expect_text("${OUT}" "default_scene / tiny / coarse: not run (--report-only)")
string(FIND "${OUT}" "goris train" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "--report-only trained:\n${OUT}")
endif()
file(READ "${OUTDIR}/results.md" md)
expect_text("${md}" "| default_scene | coarse | tiny | not run |")
expect_text("${md}" "| default_scene | full | tiny | ok (reused) |")

# A configuration that fails (here: a copy of the scene without its training masks, so `goris select --masks`
# fails) is recorded with its error; the bench goes on, writes its tables and exits non-zero.
file(COPY "${RESOURCES}/default_scene/" DESTINATION "${WORK}/nomask")
file(GLOB masks "${WORK}/nomask/train/mask_*.png")
file(REMOVE ${masks})
execute_process(COMMAND "${GORIS}" bench pipeline --data "${WORK}/nomask" --configs baseline,full
                        --out "${WORK}/failing" --schedule tiny --device cpu
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "a bench with failed configurations exited 0:\n${out}")
endif()
file(STRINGS "${WORK}/failing/results.csv" lines)
list(LENGTH lines n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "the failed configurations are not both in results.csv:\n${lines}")
endif()
list(GET lines 2 row)
expect_text("${row}" "nomask,full,tiny,failed,")
expect_text("${row}" "select failed (exit code 1): error: masks:")
file(READ "${WORK}/failing/results.md" md)
expect_text("${md}" "**failed**: select failed")

# `goris select` on a tiny run of the embedded scene (50 iterations, 64 px): --masks and --click write
# selection.json + selection.npy + previews; background clicks, absurd selections and bad arguments are
# errors that say what to change.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(RUN "${WORK}/run")

# The random initial points fill only the middle of the views, so the image corners show background.
goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode radiance --iters 50 --resolution 64 --device cpu
         --init-points 3000 --checkpoint-every 0 --set random_init_box_ratio=0.15)

# --masks: the data set's train mask_XXX.png.
goris_ok(select "${RUN}" --masks --device cpu)
expect_text("${OUT}" "voting with the object masks of 40 training views")
file(READ "${RUN}/selection.json" sel)
string(JSON method GET "${sel}" method)
string(JSON count GET "${sel}" gaussian_count)
string(JSON selected GET "${sel}" selected)
string(JSON source GET "${sel}" model_source)
string(JSON volume GET "${sel}" summary volume)
if(NOT method STREQUAL "masks" OR NOT count EQUAL 3000 OR selected LESS 1 OR selected GREATER 1500)
  message(FATAL_ERROR "selection.json after --masks:\n${sel}")
endif()
expect_text("${source}" "checkpoints/")
expect_text("${volume}" "convex hull")
file(SIZE "${RUN}/selection.npy" npy_size)
if(NOT npy_size EQUAL 3128)  # the header padded to 128 bytes (NumPy 1.0 format) + 3000 bytes
  message(FATAL_ERROR "selection.npy is ${npy_size} bytes")
endif()
file(GLOB previews "${RUN}/selection_preview/*.png")
list(LENGTH previews n_previews)
if(NOT n_previews EQUAL 4)
  message(FATAL_ERROR "expected 4 previews, got: ${previews}")
endif()

# --masks DIR: masks from another folder, matched by view name.
file(MAKE_DIRECTORY "${WORK}/masks")
foreach(i 000 001 002)
  file(COPY "${RESOURCES}/default_scene/train/mask_${i}.png" DESTINATION "${WORK}/masks")
endforeach()
file(MAKE_DIRECTORY "${WORK}/dirmasks")  # an output file's folder must exist
goris_ok(select "${RUN}" --masks "${WORK}/masks" --previews 0 --device cpu --out "${WORK}/dirmasks/sel.json")
expect_text("${OUT}" "voting with the object masks of 3 training views")

# --click: the Gaussian under a pixel of a training view (by name or index), into another file.
file(MAKE_DIRECTORY "${WORK}/click")
goris_ok(select "${RUN}" --click r_000 32 33 --grow 0 --device cpu --out "${WORK}/click/sel.json")
expect_text("${OUT}" "picked Gaussian")
file(READ "${WORK}/click/sel.json" sel)
string(JSON method GET "${sel}" method)
string(JSON selected GET "${sel}" selected)
string(JSON view GET "${sel}" parameters view)
if(NOT method STREQUAL "click" OR NOT selected EQUAL 1 OR NOT view STREQUAL "r_000")
  message(FATAL_ERROR "sel.json after --click:\n${sel}")
endif()
foreach(f sel.npy sel_preview/r_000.png)
  if(NOT EXISTS "${WORK}/click/${f}")
    message(FATAL_ERROR "--click --out did not write ${f}")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK}/click0")
goris_ok(select "${RUN}" --click 0 32 33 --grow 0 --device cpu --previews 0 --out "${WORK}/click0/sel.json")

# Regions, alone and combined with a rule; masks of every training view from the selection, scored.
file(MAKE_DIRECTORY "${WORK}/region")
goris_ok(select "${RUN}" --rect r_000 16,16,48,48 --through all --max-fraction 1 --previews 0 --device cpu
         --out "${WORK}/region/sel.json")
expect_text("${OUT}" "in the regions")
goris_ok(select "${RUN}" --masks --sphere 0,0,0,0.3 --box 0,0,0,0.1,0.1,0.1,0,0,45 --combine subtract --dilate 1
         --previews 0 --device cpu --out "${WORK}/region/sel.json" --write-masks "${WORK}/region/masks" --masks-iou)
expect_text("${OUT}" "wrote 40 object masks")
expect_text("${OUT}" "masks IoU against the exact masks")
foreach(f masks/mask_000.png masks/mask_039.png masks/iou.json)
  if(NOT EXISTS "${WORK}/region/${f}")
    message(FATAL_ERROR "--write-masks did not write ${f}")
  endif()
endforeach()

# Errors that explain themselves; nothing already written is lost.
file(READ "${RUN}/selection.json" before)
goris_fails("shows background" select "${RUN}" --click r_000 0 0 --device cpu)
goris_fails("more than 50.0% of the scene" select "${RUN}" --click r_000 32 33 --grow 1 --device cpu)
# An untrained label channel (0.5 everywhere) selects everything: refused.
goris_fails("raise --threshold" select "${RUN}" --labels --device cpu)
goris_fails("no Gaussian has a label above" select "${RUN}" --labels --threshold 0.9 --device cpu)
goris_fails("choose one of" select "${RUN}" --labels --masks --device cpu)
goris_fails("choose one of" select "${RUN}" --device cpu)
goris_fails("has 2 numbers, expected 6 or 9" select "${RUN}" --box 1,2 --device cpu)
goris_fails("odd count of numbers" select "${RUN}" --polygon r_000 1,1,2 --device cpu)
goris_fails("no training view 'r_999'" select "${RUN}" --rect r_999 1,1,2,2 --device cpu)
goris_fails("needs --write-masks" select "${RUN}" --masks --masks-iou --device cpu)
goris_fails("no training view 'r_999'" select "${RUN}" --click r_999 1 1 --device cpu)
goris_fails("outside view r_000" select "${RUN}" --click r_000 64 3 --device cpu)
goris_fails("mask folder not found" select "${RUN}" --masks "${WORK}/no_such_masks" --device cpu)
goris_fails("config.json" select "${WORK}/not_a_run" --masks --device cpu)
file(READ "${RUN}/selection.json" after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "a failed selection changed selection.json")
endif()

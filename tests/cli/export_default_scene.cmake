# `goris export` on a tiny intrinsic run of the embedded scene (64 px, 40 iterations): the intrinsic PLY has
# the standard 3DGS properties plus the intrinsic ones, the baked PLY only the standard ones and a json with a
# finite fidelity PSNR, orbit renders give one PNG per frame plus a contact sheet; bad input is refused
# before any work with a message naming the problem.
file(REMOVE_RECURSE "${WORK}")
set(RUN "${WORK}/run")
set(OUTD "${WORK}/out")

include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")

# The PLY header (up to end_header) of a file.
function(ply_header path var)
  file(READ "${path}" head LIMIT 4000)
  string(FIND "${head}" "end_header" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${path}: no PLY header")
  endif()
  string(SUBSTRING "${head}" 0 ${at} head)
  set(${var} "${head}" PARENT_SCOPE)
endfunction()

file(MAKE_DIRECTORY "${OUTD}")

# Bad input first (no run needed to be refused).
goris_fails("--ply OUT.ply" export "${WORK}/no_such_run")
goris_fails("config.json" export "${WORK}/no_such_run" --ply "${OUTD}/a.ply")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/a_file" "x")
goris_fails("${WORK}/a_file/x.ply" export "${WORK}/no_such_run" --ply "${WORK}/a_file/x.ply")
goris_fails("--renders" export "${WORK}/no_such_run" --ply "${OUTD}/a.ply" --path orbit)

goris_ok(train "${RESOURCES}/default_scene" --out "${RUN}" --mode intrinsic --iters 40 --resolution 64 --device cpu
         --init-points 3000 --checkpoint-every 0 --set intrinsic_env_resolution=8)
# An output file's folder must exist (a mistyped path is refused, not created).
goris_fails("${WORK}/missing does not exist" export "${RUN}" --ply "${WORK}/missing/x.ply")
if(EXISTS "${WORK}/missing")
  message(FATAL_ERROR "a refused export created ${WORK}/missing")
endif()
goris_fails("same file" export "${RUN}" --ply "${OUTD}/x.ply" --baked "${OUTD}/x.ply")

goris_ok(export "${RUN}" --ply "${OUTD}/intrinsic.ply" --baked "${OUTD}/baked.ply" --iters 30
         --renders "${OUTD}/orbit" --path orbit --frames 4 --device cpu)
expect_text("${OUT}" "fidelity on")
expect_text("${OUT}" "renders: 4 orbit frames")

# Intrinsic PLY: standard layout (SH degree 3) plus the intrinsic attributes; `goris info` reads it back.
ply_header("${OUTD}/intrinsic.ply" h)
foreach(p x y z nx ny nz f_dc_0 f_dc_2 f_rest_0 f_rest_44 opacity scale_0 scale_2 rot_0 rot_3
          diffuse_0 fresnel_2 roughness region label)
  expect_text("${h}" "property float ${p}\n")
endforeach()
goris_ok(info "${OUTD}/intrinsic.ply")
expect_text("${OUT}" "SH degree 3")

# Baked PLY: the standard properties only.
ply_header("${OUTD}/baked.ply" h)
foreach(p x y z nx ny nz f_dc_0 f_rest_44 opacity scale_2 rot_3)
  expect_text("${h}" "property float ${p}\n")
endforeach()
foreach(p diffuse_0 fresnel_0 roughness region label)
  string(FIND "${h}" "property float ${p}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the baked PLY carries the intrinsic property ${p}:\n${h}")
  endif()
endforeach()
goris_ok(info "${OUTD}/baked.ply")
file(READ "${OUTD}/baked.json" j)
string(JSON psnr GET "${j}" psnr)
string(JSON iters GET "${j}" iterations)
string(JSON distilled GET "${j}" distilled)
string(JSON holdout GET "${j}" holdout)
if(NOT psnr MATCHES "^[0-9]+(\\.[0-9]+)?([eE][-+]?[0-9]+)?$" OR psnr LESS 5 OR NOT iters EQUAL 30
   OR NOT distilled STREQUAL "ON" OR NOT holdout STREQUAL "test")
  message(FATAL_ERROR "baked.json: psnr ${psnr}, iterations ${iters}, distilled ${distilled}, holdout ${holdout}\n${j}")
endif()

# Orbit renders: one PNG per frame, the contact sheet, the cameras.
foreach(f frame_000.png frame_001.png frame_002.png frame_003.png contact_sheet.png cameras.json)
  if(NOT EXISTS "${OUTD}/orbit/${f}")
    message(FATAL_ERROR "--renders did not write ${f}")
  endif()
endforeach()
file(GLOB frames "${OUTD}/orbit/frame_*.png")
list(LENGTH frames n)
if(NOT n EQUAL 4)
  message(FATAL_ERROR "expected 4 orbit frames, found ${n}")
endif()
file(READ "${OUTD}/orbit/cameras.json" cams)
string(JSON ncams LENGTH "${cams}" cameras)
if(NOT ncams EQUAL 4)
  message(FATAL_ERROR "cameras.json lists ${ncams} cameras")
endif()

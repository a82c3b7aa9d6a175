# `goris capture` refuses bad input before any COLMAP work, exits non-zero and names the file and the
# problem: a missing input, too few photos, a video that does not decode, COLMAP missing (with the apt
# command), an output that exists, lies inside the input folder or inside a data set. Needs no COLMAP.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/two")
file(GLOB photos "${RESOURCES}/default_scene/train/r_00*.png")
list(GET photos 0 p0)
list(GET photos 1 p1)
list(GET photos 2 p2)
file(COPY "${p0}" "${p1}" DESTINATION "${WORK}/two")
file(MAKE_DIRECTORY "${WORK}/three")
file(COPY "${p0}" "${p1}" "${p2}" DESTINATION "${WORK}/three")
file(WRITE "${WORK}/broken.mp4" "not a video")

goris_fails("${WORK}/missing: not found" capture "${WORK}/missing" --out "${WORK}/out")
goris_fails("only 2 photos: a capture needs at least 3" capture "${WORK}/two" --out "${WORK}/out")
goris_fails("broken.mp4: cannot read the video" capture "${WORK}/broken.mp4" --out "${WORK}/out")
goris_fails("sudo apt-get install colmap" capture "${WORK}/three" --out "${WORK}/out" --colmap "${WORK}/no_colmap")
goris_fails("exists already" capture "${WORK}/three" --out "${WORK}/two")
goris_fails("lies inside the input folder" capture "${WORK}/three" --out "${WORK}/three/out")
goris_fails("inside the data set" capture "${WORK}/three" --out "${RESOURCES}/default_scene/captured" --colmap /bin/true)
goris_fails("--matcher" capture "${WORK}/three" --out "${WORK}/out" --matcher nearest)
foreach(p "${WORK}/out" "${WORK}/.out.capture-tmp" "${WORK}/three/out" "${WORK}/three/.out.capture-tmp"
          "${RESOURCES}/default_scene/captured"
          "${RESOURCES}/default_scene/.captured.capture-tmp")
  if(EXISTS "${p}")
    message(FATAL_ERROR "a refused capture left ${p}")
  endif()
endforeach()

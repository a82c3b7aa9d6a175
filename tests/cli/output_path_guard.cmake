# Outputs never land on inputs: every command refuses to write into a data set or over a run's own files,
# and a file's folder must exist (nothing is created at a mistyped path). Number flags and settings are
# range-checked without wrapping, and a FIFO is refused by type instead of blocking `goris info`.
include("${CMAKE_CURRENT_LIST_DIR}/../support/cli_common.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
# A copy of the embedded data set, so that a failure of the guard cannot damage the repository's.
set(DATA "${WORK}/data")
file(COPY "${RESOURCES}/default_scene/" DESTINATION "${DATA}")
set(RUN "${WORK}/run")
goris_ok(train "${DATA}" --out "${RUN}" --mode radiance --iters 5 --resolution 32 --device cpu --init-points 500
         --checkpoint-every 0)
file(SHA256 "${RUN}/config.json" config_hash)
file(SHA256 "${RUN}/point_cloud.ply" model_hash)
file(GLOB photos "${DATA}/test/*.png")
list(GET photos 0 photo)
file(SHA256 "${photo}" photo_hash)

goris_fails("inside the data set" render "${RUN}" --out "${DATA}/test" --device cpu)
goris_fails("inside the data set" train "${DATA}" --out "${DATA}" --iters 5 --device cpu)
goris_fails("inside the data set" train "${DATA}" --out "${DATA}/run" --iters 5 --device cpu)
goris_fails("${RUN}/point_cloud.ply: would overwrite" eval "${RUN}" --out "${RUN}/point_cloud.ply" --device cpu)
goris_fails("${RUN}/config.json: would overwrite" select "${RUN}" --masks --out "${RUN}/config.json" --device cpu)
goris_fails("would overwrite" export "${RUN}" --ply "${RUN}/point_cloud.ply")
goris_fails("would overwrite" export "${RUN}" --baked "${RUN}/config.ply")  # its json beside would be config.json
goris_fails("/nonexistent_goris_dir does not exist" export "${RUN}" --ply /nonexistent_goris_dir/x.ply)
if(EXISTS /nonexistent_goris_dir)
  message(FATAL_ERROR "a refused export created /nonexistent_goris_dir")
endif()
file(SHA256 "${RUN}/config.json" h1)
file(SHA256 "${RUN}/point_cloud.ply" h2)
file(SHA256 "${photo}" h3)
if(NOT h1 STREQUAL config_hash OR NOT h2 STREQUAL model_hash OR NOT h3 STREQUAL photo_hash)
  message(FATAL_ERROR "a refused command changed the run or the data set")
endif()
if(EXISTS "${DATA}/run")
  message(FATAL_ERROR "a refused train left ${DATA}/run")
endif()
# Outputs beside the run are fine.
goris_ok(eval "${RUN}" --out "${WORK}/metrics.json" --device cpu)

# Numbers: no wrapping, the limit in the message, NaN named.
goris_fails("2147483647" train "${DATA}" --out "${WORK}/n1" --set random_init_points=10000000000)
goris_fails("from 0 to 18446744073709551615" train "${DATA}" --out "${WORK}/n2" --seed -1)
goris_fails("NaN" train "${DATA}" --out "${WORK}/n3" --set lambda_ssim=nan)
goris_fails("from 1 to 2147483647" train "${DATA}" --out "${WORK}/n4" --iters 0)
foreach(n n1 n2 n3 n4)
  if(EXISTS "${WORK}/${n}")
    message(FATAL_ERROR "a refused train left ${WORK}/${n}")
  endif()
endforeach()

# A FIFO is refused by type (opening it would wait for a writer forever).
execute_process(COMMAND mkfifo "${WORK}/pipe.ply" RESULT_VARIABLE rc)
if(rc EQUAL 0)
  execute_process(COMMAND "${GORIS}" info "${WORK}/pipe.ply" RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 20)
  if(rc EQUAL 0 OR NOT err MATCHES "FIFO")
    message(FATAL_ERROR "goris info on a FIFO: exit ${rc}, expected a refusal naming the FIFO\n${err}")
  endif()
endif()

# The folder-dependency check: the repository passes; a made-up tree with an undeclared include, a folder
# missing from the table, or a cyclic table fails, naming what is wrong.
# cmake -DSOURCE_DIR=<root> -DWORK=<scratch folder> -P check_folder_dependencies_test.cmake
set(check ${SOURCE_DIR}/cmake/check_folder_dependencies.cmake)

function(run_check root table out_rc out_text)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${root} -DTABLE=${table} -P ${check}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  set(${out_rc} "${rc}" PARENT_SCOPE)
  set(${out_text} "${o}${e}" PARENT_SCOPE)
endfunction()

function(expect_pass root table what)
  run_check(${root} ${table} rc text)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}:\n${text}")
  endif()
endfunction()

function(expect_failure root table pattern)
  run_check(${root} ${table} rc text)
  if(rc EQUAL 0)
    message(FATAL_ERROR "the check passed ${root} with ${table}; expected a failure matching '${pattern}'")
  endif()
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "the check failed without naming '${pattern}':\n${text}")
  endif()
endfunction()

expect_pass(${SOURCE_DIR} ${SOURCE_DIR}/cmake/folder_dependencies.cmake
            "the repository fails its own folder-dependency check")

file(REMOVE_RECURSE ${WORK})
file(WRITE ${WORK}/tree/core/util/a.h "#pragma once\n#include <vector>\n")
file(WRITE ${WORK}/tree/core/io/b.h "#pragma once\n#include \"core/util/a.h\"\n")
file(WRITE ${WORK}/table.cmake "set(GORIS_FOLDER_DEPENDENCIES \"core/util:\" \"core/io:core/util\")\n")
expect_pass(${WORK}/tree ${WORK}/table.cmake "a declared include was refused")

# An include upwards (core/util -> core/io) that the table does not declare.
file(WRITE ${WORK}/tree/core/util/c.cpp "#include \"core/util/a.h\"\n  #  include \"core/io/b.h\"\n")
expect_failure(${WORK}/tree ${WORK}/table.cmake "core/util/c.cpp: includes core/io/b.h, but core/util does not declare core/io")
file(REMOVE ${WORK}/tree/core/util/c.cpp)

# A folder the table does not know.
file(WRITE ${WORK}/tree/core/extra/d.cpp "#include \"core/util/a.h\"\n")
expect_failure(${WORK}/tree ${WORK}/table.cmake "core/extra is not in the table")
file(REMOVE_RECURSE ${WORK}/tree/core/extra)

# A cycle in the table, even with no source using it.
file(WRITE ${WORK}/cyclic.cmake
     "set(GORIS_FOLDER_DEPENDENCIES \"core/util:core/scene\" \"core/io:core/util\" \"core/scene:core/io\")\n")
expect_failure(${WORK}/tree ${WORK}/cyclic.cmake "cycle: core/util -> core/scene -> core/io -> core/util")

# tools/: its code folders are checked like the engine's (its node_modules are not walked), and an engine
# folder that includes a tool fails.
file(WRITE ${WORK}/tree/tools/report/e.h "#pragma once\n#include \"core/util/a.h\"\n")
file(WRITE ${WORK}/tree/tools/node_modules/pkg/f.h "#include \"core/io/b.h\"\n")
file(WRITE ${WORK}/tools_table.cmake
     "set(GORIS_FOLDER_DEPENDENCIES \"core/util:\" \"core/io:core/util\" \"tools/report:core/util\")\n")
expect_pass(${WORK}/tree ${WORK}/tools_table.cmake "a declared include of tools/ was refused, or node_modules was walked")
file(WRITE ${WORK}/tree/core/io/g.cpp "#include \"tools/report/e.h\"\n")
expect_failure(${WORK}/tree ${WORK}/tools_table.cmake "core/io/g.cpp: includes tools/report/e.h, but core/io does not declare tools/report")
file(REMOVE ${WORK}/tree/core/io/g.cpp)
file(WRITE ${WORK}/tree/tools/report/h.cpp "#include \"core/io/b.h\"\n")
expect_failure(${WORK}/tree ${WORK}/tools_table.cmake "tools/report/h.cpp: includes core/io/b.h, but tools/report does not declare core/io")

# ui/: its folders are two levels deep too (ui/gl, ui/shell), each with its own row.
file(REMOVE ${WORK}/tree/tools/report/h.cpp)
file(WRITE ${WORK}/tree/ui/gl/i.h "#pragma once\n#include \"core/util/a.h\"\n")
file(WRITE ${WORK}/tree/ui/shell/j.h "#pragma once\n#include \"ui/gl/i.h\"\n")
file(WRITE ${WORK}/ui_table.cmake
     "set(GORIS_FOLDER_DEPENDENCIES \"core/util:\" \"core/io:core/util\" \"tools/report:core/util\" \"ui/gl:core/util\" \"ui/shell:ui/gl\")\n")
expect_pass(${WORK}/tree ${WORK}/ui_table.cmake "a declared include between ui/ folders was refused")
file(WRITE ${WORK}/tree/ui/gl/k.cpp "#include \"ui/shell/j.h\"\n")
expect_failure(${WORK}/tree ${WORK}/ui_table.cmake "ui/gl/k.cpp: includes ui/shell/j.h, but ui/gl does not declare ui/shell")

# A cycle between top-level folders (core -> render -> core) with none between folders: each top-level
# folder is one library, so this fails too.
file(WRITE ${WORK}/top_cycle.cmake
     "set(GORIS_FOLDER_DEPENDENCIES \"core/util:\" \"core/io:render/raster\" \"render/raster:core/util\")\n")
expect_failure(${WORK}/tree ${WORK}/top_cycle.cmake "cycle between top-level folders: core -> render -> core")

# train/, removal/ and export/ are walked like core/ and render/: removal over train, not the other way.
file(REMOVE ${WORK}/tree/ui/gl/k.cpp)
file(WRITE ${WORK}/tree/train/loop/l.h "#pragma once\n#include \"core/util/a.h\"\n")
file(WRITE ${WORK}/tree/removal/lift/m.h "#pragma once\n#include \"train/loop/l.h\"\n")
file(WRITE ${WORK}/layers_table.cmake
     "set(GORIS_FOLDER_DEPENDENCIES \"core/util:\" \"core/io:core/util\" \"tools/report:core/util\" \"ui/gl:core/util\" \"ui/shell:ui/gl\" \"train/loop:core/util\" \"removal/lift:train/loop\")\n")
expect_pass(${WORK}/tree ${WORK}/layers_table.cmake "a declared include of train/ from removal/ was refused")
file(WRITE ${WORK}/tree/train/loop/n.cpp "#include \"removal/lift/m.h\"\n")
expect_failure(${WORK}/tree ${WORK}/layers_table.cmake "train/loop/n.cpp: includes removal/lift/m.h, but train/loop does not declare removal/lift")

message(STATUS "folder dependencies: the repository passes; undeclared includes, unknown folders and cycles fail")

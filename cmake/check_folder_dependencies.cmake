# cmake -DSOURCE_DIR=<repository root> [-DTABLE=<a table file>] -P check_folder_dependencies.cmake
# Fails (with every offending file and include named) when a source under core/, render/, train/, removal/,
# export/, ui/, tools/ or app/ includes a folder its own folder does not declare in folder_dependencies.cmake,
# when a folder is missing from that table, or when the table has a cycle, between folders or between the
# top-level folders (core, render, train, ...: one library each) its rows imply.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_folder_dependencies: pass -DSOURCE_DIR=<repository root>")
endif()
if(NOT TABLE)
  set(TABLE ${CMAKE_CURRENT_LIST_DIR}/folder_dependencies.cmake)
endif()
include(${TABLE})

set(tops "core|render|train|removal|export|ui|tools|app")

# The folder a path (relative to the root) belongs to: core/io, train/loop, ui/document, tools/synth, app/goris.
function(folder_of path out)
  string(REGEX MATCH "^(${tops})/[^/]+" f "${path}")
  set(${out} "${f}" PARENT_SCOPE)
endfunction()

set(folders "")
foreach(entry IN LISTS GORIS_FOLDER_DEPENDENCIES)
  string(REGEX MATCH "^[^:]+" name "${entry}")
  string(REGEX REPLACE "^[^:]*:" "" deps "${entry}")
  separate_arguments(deps UNIX_COMMAND "${deps}")
  set(deps_${name} "${deps}")
  list(APPEND folders "${name}")
endforeach()

# find_cycle(NODES PREFIX OUT): a cycle among NODES, whose edges are the lists ${PREFIX}${node}, as
# "a;b;...;a" in OUT (empty when acyclic). Depth-first search with an explicit stack of (node, state).
function(find_cycle nodes prefix out)
  set(cycle "")
  foreach(start IN LISTS nodes)
    if(done_${start})
      continue()
    endif()
    set(stack "${start}")
    set(path "")
    while(stack)
      list(POP_BACK stack top)
      if(top MATCHES "^/")  # the marker that `top` is finished
        string(SUBSTRING "${top}" 1 -1 f)
        set(done_${f} TRUE)
        list(POP_BACK path)
        continue()
      endif()
      if(done_${top})
        continue()
      endif()
      if(top IN_LIST path)
        set(cycle "${path};${top}")
        break()
      endif()
      list(APPEND path "${top}")
      list(APPEND stack "/${top}")
      foreach(d IN LISTS ${prefix}${top})
        if(NOT done_${d})
          list(APPEND stack "${d}")
        endif()
      endforeach()
    endwhile()
    if(cycle)
      break()
    endif()
  endforeach()
  set(${out} "${cycle}" PARENT_SCOPE)
endfunction()

set(problems "")
find_cycle("${folders}" deps_ cycle)
if(cycle)
  string(REPLACE ";" " -> " cycle "${cycle}")
  string(APPEND problems "  the table has a cycle: ${cycle}\n")
endif()

# The top-level folders the rows imply (core/io: render/raster makes core -> render) must be acyclic too:
# each is one library, and a library cannot link one that links it.
set(top_folders "")
foreach(name IN LISTS folders)
  string(REGEX MATCH "^[^/]+" from "${name}")
  list(APPEND top_folders "${from}")
  foreach(d IN LISTS deps_${name})
    string(REGEX MATCH "^[^/]+" to "${d}")
    if(NOT to STREQUAL from)
      list(APPEND top_deps_${from} "${to}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES top_folders)
find_cycle("${top_folders}" top_deps_ cycle)
if(cycle)
  string(REPLACE ";" " -> " cycle "${cycle}")
  string(APPEND problems "  the table has a cycle between top-level folders: ${cycle}\n")
endif()

# tools/ also holds scripts and the node_modules of ./dev setup: only its folders with code are walked.
file(GLOB tool_folders LIST_DIRECTORIES true "${SOURCE_DIR}/tools/*")
list(FILTER tool_folders EXCLUDE REGEX "/node_modules$")
set(tool_patterns "")
foreach(d IN LISTS tool_folders)
  if(IS_DIRECTORY "${d}")
    list(APPEND tool_patterns "${d}/*.h" "${d}/*.cpp" "${d}/*.cu" "${d}/*.cuh")
  endif()
endforeach()
file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}"
     "${SOURCE_DIR}/core/*.h" "${SOURCE_DIR}/core/*.cpp" "${SOURCE_DIR}/core/*.cu" "${SOURCE_DIR}/core/*.cuh"
     "${SOURCE_DIR}/render/*.h" "${SOURCE_DIR}/render/*.cpp" "${SOURCE_DIR}/render/*.cu" "${SOURCE_DIR}/render/*.cuh"
     "${SOURCE_DIR}/train/*.h" "${SOURCE_DIR}/train/*.cpp" "${SOURCE_DIR}/train/*.cu" "${SOURCE_DIR}/train/*.cuh"
     "${SOURCE_DIR}/removal/*.h" "${SOURCE_DIR}/removal/*.cpp" "${SOURCE_DIR}/removal/*.cu" "${SOURCE_DIR}/removal/*.cuh"
     "${SOURCE_DIR}/export/*.h" "${SOURCE_DIR}/export/*.cpp" "${SOURCE_DIR}/export/*.cu" "${SOURCE_DIR}/export/*.cuh"
     "${SOURCE_DIR}/ui/*.h" "${SOURCE_DIR}/ui/*.cpp" "${SOURCE_DIR}/ui/*.cu"
     ${tool_patterns}
     "${SOURCE_DIR}/app/*.h" "${SOURCE_DIR}/app/*.cpp")
foreach(src IN LISTS sources)
  folder_of("${src}" from)
  if(NOT from)
    continue()
  endif()
  if(NOT from IN_LIST folders)
    string(APPEND problems "  ${src}: its folder ${from} is not in the table\n")
    set(folders "${folders};${from}")  # named once
    continue()
  endif()
  file(STRINGS "${SOURCE_DIR}/${src}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"(${tops})/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    folder_of("${header}" to)
    if(to AND NOT to STREQUAL from AND NOT to IN_LIST deps_${from})
      string(APPEND problems "  ${src}: includes ${header}, but ${from} does not declare ${to}\n")
    endif()
  endforeach()
endforeach()

if(problems)
  message(FATAL_ERROR "folder dependencies (cmake/folder_dependencies.cmake):\n${problems}")
endif()

# The arrows between the layers, checked on every build (cmake -P, from CMakeLists.txt's
# `layering` target, on which every library depends): a file in src/<layer>/ may include headers
# of its own layer and of the layers below it, never one above. The libraries link the same way,
# so an include that breaks the order fails here with the file and line, before it can link by
# accident through a library that happens to be there.
#
#   cmake -DSOURCE_DIR=<repo> -P cmake/check_layers.cmake
cmake_minimum_required(VERSION 3.20)  # IN_LIST
set(below_core "")
set(below_geometry core)
set(below_scenes core geometry)
set(below_image core)
set(below_paths core geometry)
set(below_integrators core geometry scenes paths image)
set(below_evaluation core geometry scenes paths image integrators)
set(below_python core geometry scenes paths image integrators evaluation)
set(below_apps core geometry scenes paths image integrators evaluation)

set(violations "")
foreach(layer core geometry scenes image paths integrators evaluation python apps)
  if(layer STREQUAL "python" OR layer STREQUAL "apps")
    set(dir "${SOURCE_DIR}/${layer}")
  else()
    set(dir "${SOURCE_DIR}/src/${layer}")
  endif()
  file(GLOB files "${dir}/*.h" "${dir}/*.cpp")
  foreach(file ${files})
    file(STRINGS "${file}" lines REGEX "^#include \"[a-z_]+/")
    foreach(line ${lines})
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" target "${line}")
      if(NOT target STREQUAL layer AND NOT target IN_LIST below_${layer})
        file(RELATIVE_PATH rel "${SOURCE_DIR}" "${file}")
        string(REPLACE ";" " " allowed "${layer};${below_${layer}}")
        string(APPEND violations "\n  ${rel}: ${line} (${layer} may include only: ${allowed})")
      endif()
    endforeach()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "layering: an include runs against the arrows (apps -> evaluation -> integrators -> paths -> geometry -> core):${violations}")
endif()

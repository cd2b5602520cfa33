# cmake -DSOURCE_DIR=... [-DCPU_ONLY_TESTS=a;b] [-DNO_LOADER_BINARIES=c;d] -P CheckLayers.cmake
# Fails (exit 1, naming the file and the include) when a layer includes what it must not:
#   cpu_raster/exact/    model/ and itself only
#   cpu_raster/methods/  model/ and itself only
#   cpu_raster/fast/, spec/, classic/: model/, exact/ and itself (classic/ also methods/); never the
#                        façade cpu_raster/cpu_raster.hpp and never each other
#   compare/             the renderers (cpu_raster/, vk_reference/) only from case_run.* (which
#                        renders) and explain_text.* (which traces on the exact path); report.hpp
#                        and run_outputs.{hpp,cpp} do not include each other
# and, for each binary in CPU_ONLY_TESTS and NO_LOADER_BINARIES (the rastercmp executable, which
# opens the loader at run time: vk_reference/vk_loader.hpp), that it has no NEEDED libvulkan; the
# NO_LOADER_BINARIES also no NEEDED libOpenImageIO (model/image_codec.hpp).
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckLayers.cmake: pass -DSOURCE_DIR=<source tree>")
endif()
set(_errors "")

# _check(DIR ALLOWED_REGEX [FILES...]): every #include "..." in DIR's sources must match.
function(_check dir allowed)
  file(GLOB _files ${SOURCE_DIR}/${dir}/*.cpp ${SOURCE_DIR}/${dir}/*.hpp ${SOURCE_DIR}/${dir}/*.inl)
  foreach(_f ${_files})
    file(STRINGS ${_f} _lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(_l ${_lines})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*" "\\1" _inc "${_l}")
      if(NOT _inc MATCHES "${allowed}")
        file(RELATIVE_PATH _rel ${SOURCE_DIR} ${_f})
        set(_errors "${_errors}\n  ${_rel} includes \"${_inc}\" (allowed: ${allowed})" PARENT_SCOPE)
        set(_errors "${_errors}\n  ${_rel} includes \"${_inc}\" (allowed: ${allowed})")
      endif()
    endforeach()
  endforeach()
endfunction()

_check(cpu_raster/exact "^(model|cpu_raster/exact)/")
_check(cpu_raster/methods "^(model|cpu_raster/methods)/")
_check(cpu_raster/fast "^(model|cpu_raster/exact|cpu_raster/fast)/")
_check(cpu_raster/spec "^(model|cpu_raster/exact|cpu_raster/spec)/")
_check(cpu_raster/classic "^(model|cpu_raster/exact|cpu_raster/methods|cpu_raster/classic)/")

file(GLOB _compare ${SOURCE_DIR}/compare/*.cpp ${SOURCE_DIR}/compare/*.hpp)
foreach(_f ${_compare})
  get_filename_component(_name ${_f} NAME)
  file(STRINGS ${_f} _lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(_l ${_lines})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*" "\\1" _inc "${_l}")
    if(_inc MATCHES "^(cpu_raster|vk_reference)/" AND NOT _name MATCHES "^(case_run|explain_text)\\.")
      set(_errors "${_errors}\n  compare/${_name} includes \"${_inc}\" (only case_run.* and explain_text.* use the renderers)")
    endif()
    if((_name STREQUAL "report.hpp" AND _inc MATCHES "^compare/run_outputs")
       OR (_name MATCHES "^run_outputs\\." AND _inc MATCHES "^compare/report"))
      set(_errors "${_errors}\n  compare/${_name} includes \"${_inc}\" (report and run_outputs are independent)")
    endif()
  endforeach()
endforeach()

foreach(_bin ${CPU_ONLY_TESTS})
  execute_process(COMMAND readelf -d ${_bin} OUTPUT_VARIABLE _dyn RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    set(_errors "${_errors}\n  readelf -d ${_bin} failed")
  elseif(_dyn MATCHES "libvulkan")
    set(_errors "${_errors}\n  ${_bin} links the Vulkan loader although it tests the CPU path alone")
  endif()
endforeach()

foreach(_bin ${NO_LOADER_BINARIES})
  execute_process(COMMAND readelf -d ${_bin} OUTPUT_VARIABLE _dyn RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    set(_errors "${_errors}\n  readelf -d ${_bin} failed")
  elseif(_dyn MATCHES "NEEDED[^\n]*libvulkan")
    set(_errors "${_errors}\n  ${_bin} links the Vulkan loader; it must open it at run time (vk_loader.hpp)")
  elseif(_dyn MATCHES "NEEDED[^\n]*libOpenImageIO")
    set(_errors "${_errors}\n  ${_bin} links OpenImageIO; it must open the image codec at run time (model/image_codec.hpp)")
  endif()
endforeach()

if(_errors)
  message(FATAL_ERROR "layering violations:${_errors}")
endif()
message(STATUS "layers: ok")

# rastercmp_module(NAME SOURCES a.cpp b.cpp ... PUBLIC libs... PRIVATE libs...): a static library
# of the listed sources (one module, one job). Sources are listed by hand, not globbed, so that a
# new file is a visible change to the build and a stray one is not compiled in.
function(rastercmp_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  if(NOT M_SOURCES)
    message(FATAL_ERROR "rastercmp_module(${name}): no SOURCES")
  endif()
  add_library(${name} STATIC ${M_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE})
endfunction()

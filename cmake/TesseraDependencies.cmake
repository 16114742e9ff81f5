# Imports of Debian bookworm packages as plain INTERFACE IMPORTED targets (tessera::<name>), found with
# find_path and find_library, so that a consumer of the installed static libraries needs no package
# config of theirs:
# - OpenImageIO 2.4 (libopenimageio-dev): its exported target lists /usr/include/opencv4 as an include
#   directory, which does not exist unless libopencv-dev is installed.
# - OpenSubdiv (libosd-dev): its CMake config is broken too (it references files the package does not
#   ship); osdCPU holds Far, Bfr, Sdc and Vtr.
# - tinygltf (libtinygltf-dev), Embree 3 (libembree-dev), meshoptimizer (libmeshoptimizer-dev): a header
#   and a library each.

# tessera_import(NAME HEADER LIBRARIES... [SYSTEM]): tessera::NAME from the directory holding HEADER and
# the LIBRARIES; SYSTEM marks the headers as system headers (no warnings from them).
function(tessera_import name header)
  if(TARGET tessera::${name})
    return()
  endif()
  cmake_parse_arguments(PARSE_ARGV 2 ARG "SYSTEM" "" "LIBRARIES")
  string(TOUPPER ${name} upper)
  find_path(TESSERA_${upper}_INCLUDE_DIR ${header} REQUIRED)
  set(libraries)
  foreach(library IN LISTS ARG_LIBRARIES)
    find_library(TESSERA_${upper}_${library}_LIBRARY ${library} REQUIRED)
    list(APPEND libraries ${TESSERA_${upper}_${library}_LIBRARY})
  endforeach()
  add_library(tessera::${name} INTERFACE IMPORTED)
  if(ARG_SYSTEM)
    target_include_directories(tessera::${name} SYSTEM INTERFACE ${TESSERA_${upper}_INCLUDE_DIR})
  else()
    target_include_directories(tessera::${name} INTERFACE ${TESSERA_${upper}_INCLUDE_DIR})
  endif()
  target_link_libraries(tessera::${name} INTERFACE ${libraries})
endfunction()

tessera_import(oiio OpenImageIO/imagebuf.h LIBRARIES OpenImageIO OpenImageIO_Util)
tessera_import(osd opensubdiv/bfr/surface.h LIBRARIES osdCPU SYSTEM)
tessera_import(tinygltf tiny_gltf.h LIBRARIES tinygltf SYSTEM)
tessera_import(embree embree3/rtcore.h LIBRARIES embree3 SYSTEM)
tessera_import(meshoptimizer meshoptimizer.h LIBRARIES meshoptimizer SYSTEM)

# Imports of Debian bookworm packages whose CMake configs are broken there.
#
# OpenImageIO 2.4 (libopenimageio-dev): its exported target lists /usr/include/opencv4 as an
# include directory, which does not exist unless libopencv-dev is installed; import it by hand.
# OpenSubdiv (libosd-dev): its CMake config is broken too (it references files the package does not
# ship); import osdCPU (Far, Bfr, Sdc, Vtr) with find_library as tessera::osd.
if(NOT TARGET tessera::oiio)
  find_path(TESSERA_OIIO_INCLUDE_DIR OpenImageIO/imagebuf.h REQUIRED)
  find_library(TESSERA_OIIO_LIBRARY OpenImageIO REQUIRED)
  find_library(TESSERA_OIIO_UTIL_LIBRARY OpenImageIO_Util REQUIRED)
  add_library(tessera::oiio INTERFACE IMPORTED)
  target_include_directories(tessera::oiio INTERFACE ${TESSERA_OIIO_INCLUDE_DIR})
  target_link_libraries(tessera::oiio INTERFACE ${TESSERA_OIIO_LIBRARY} ${TESSERA_OIIO_UTIL_LIBRARY})
endif()

if(NOT TARGET tessera::osd)
  find_path(TESSERA_OSD_INCLUDE_DIR opensubdiv/bfr/surface.h REQUIRED)
  find_library(TESSERA_OSD_CPU_LIBRARY osdCPU REQUIRED)
  add_library(tessera::osd INTERFACE IMPORTED)
  target_include_directories(tessera::osd SYSTEM INTERFACE ${TESSERA_OSD_INCLUDE_DIR})
  target_link_libraries(tessera::osd INTERFACE ${TESSERA_OSD_CPU_LIBRARY})
endif()

# tinygltf (libtinygltf-dev): a plain header and shared library; imported the same way so a consumer of
# the installed static libraries needs no TinyGLTF config of its own.
if(NOT TARGET tessera::tinygltf)
  find_path(TESSERA_TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
  find_library(TESSERA_TINYGLTF_LIBRARY tinygltf REQUIRED)
  add_library(tessera::tinygltf INTERFACE IMPORTED)
  target_include_directories(tessera::tinygltf SYSTEM INTERFACE ${TESSERA_TINYGLTF_INCLUDE_DIR})
  target_link_libraries(tessera::tinygltf INTERFACE ${TESSERA_TINYGLTF_LIBRARY})
endif()

# Embree 3 (libembree-dev): imported the same way, so the installed static tessera_bake needs no Embree
# config of its own.
if(NOT TARGET tessera::embree)
  find_path(TESSERA_EMBREE_INCLUDE_DIR embree3/rtcore.h REQUIRED)
  find_library(TESSERA_EMBREE_LIBRARY embree3 REQUIRED)
  add_library(tessera::embree INTERFACE IMPORTED)
  target_include_directories(tessera::embree SYSTEM INTERFACE ${TESSERA_EMBREE_INCLUDE_DIR})
  target_link_libraries(tessera::embree INTERFACE ${TESSERA_EMBREE_LIBRARY})
endif()

# meshoptimizer (libmeshoptimizer-dev): imported the same way, for the installed static tessera_optimize.
if(NOT TARGET tessera::meshoptimizer)
  find_path(TESSERA_MESHOPT_INCLUDE_DIR meshoptimizer.h REQUIRED)
  find_library(TESSERA_MESHOPT_LIBRARY meshoptimizer REQUIRED)
  add_library(tessera::meshoptimizer INTERFACE IMPORTED)
  target_include_directories(tessera::meshoptimizer SYSTEM INTERFACE ${TESSERA_MESHOPT_INCLUDE_DIR})
  target_link_libraries(tessera::meshoptimizer INTERFACE ${TESSERA_MESHOPT_LIBRARY})
endif()

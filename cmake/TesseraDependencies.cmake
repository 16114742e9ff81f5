# Imports of Debian bookworm packages whose CMake configs are broken there.
#
# OpenImageIO 2.4 (libopenimageio-dev): its exported target lists /usr/include/opencv4 as an
# include directory, which does not exist unless libopencv-dev is installed; import it by hand.
# OpenSubdiv (libosd-dev): its config is broken too; link osdCPU with find_library (issue 4).
if(NOT TARGET tessera::oiio)
  find_path(TESSERA_OIIO_INCLUDE_DIR OpenImageIO/imagebuf.h REQUIRED)
  find_library(TESSERA_OIIO_LIBRARY OpenImageIO REQUIRED)
  find_library(TESSERA_OIIO_UTIL_LIBRARY OpenImageIO_Util REQUIRED)
  add_library(tessera::oiio INTERFACE IMPORTED)
  target_include_directories(tessera::oiio INTERFACE ${TESSERA_OIIO_INCLUDE_DIR})
  target_link_libraries(tessera::oiio INTERFACE ${TESSERA_OIIO_LIBRARY} ${TESSERA_OIIO_UTIL_LIBRARY})
endif()

# `cmake --install`: the tessera binary, the libraries with their public headers (include/tessera/),
# and a CMake package whose Tessera:: targets another project finds with find_package(Tessera).
include(CMakePackageConfigHelpers)
set(_tessera_libraries tessera_tessellator tessera_pipeline tessera_image_io tessera_cage tessera_animation tessera_gltf tessera_subdiv tessera_displacement
  tessera_optimize tessera_lod tessera_shaders tessera_debug tessera_bake tessera_verify tessera_measure)
# tessera_options carries no usage requirements a consumer sees (its flags are PRIVATE to each
# library); it is exported only because static libraries name their private link dependencies.
set_target_properties(tessera_options PROPERTIES EXPORT_NAME options)
install(TARGETS tessera_options ${_tessera_libraries} EXPORT TesseraTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tessera)
install(EXPORT TesseraTargets NAMESPACE Tessera:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Tessera)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TesseraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/TesseraConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Tessera)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/TesseraConfig.cmake ${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/TesseraDependencies.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Tessera)

# Installs the library, its headers and a CMake package:
#   find_package(osd_cull REQUIRED)
#   target_link_libraries(app PRIVATE osd_cull::osd_cull osd_cull::adapters)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS osd_cull osd_cull_adapters EXPORT osd_cull-targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Headers: include/osd_cull/... only, so that consumers write <osd_cull/...> and no generic
# folder lands on their include path. The library's headers keep their paths
# (<osd_cull/patch/...>), the loaders go to <osd_cull/adapters/...>, the shared C++/GLSL
# layouts of shaders/shared to <osd_cull/shared/...>, the generated <osd_cull/version.h>.
# osd_cull/vk/glsl/ is the run-time compiler, which is not installed (shaders are embedded
# as SPIR-V).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/osd_cull/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/osd_cull FILES_MATCHING PATTERN "*.h"
  REGEX "/vk/glsl($|/)" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/adapters/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/osd_cull/adapters FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/shared/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/osd_cull/shared FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/osd_cull/version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/osd_cull)

set(_cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/osd_cull)
install(EXPORT osd_cull-targets NAMESPACE osd_cull:: DESTINATION ${_cfgdir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/osd_cull-config.cmake.in
  ${PROJECT_BINARY_DIR}/osd_cull-config.cmake INSTALL_DESTINATION ${_cfgdir})
# find_package(osd_cull 0.1) accepts 0.1.x: before 1.0 a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/osd_cull-config-version.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/osd_cull-config.cmake
  ${PROJECT_BINARY_DIR}/osd_cull-config-version.cmake
  ${PROJECT_SOURCE_DIR}/cmake/OsdCullDependencies.cmake
  DESTINATION ${_cfgdir})

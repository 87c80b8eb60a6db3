# `cmake --install` puts the library, headers and a package config in place so
# an embedder writes find_package(quadra) and links quadra::quadra.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
install(TARGETS quadra_engine quadra_warnings EXPORT quadraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS quadra RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/ ${PROJECT_SOURCE_DIR}/simd
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/quadra FILES_MATCHING PATTERN "*.h")
install(EXPORT quadraTargets NAMESPACE quadra:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/quadraConfig.cmake.in
  ${CMAKE_BINARY_DIR}/quadraConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/quadraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/quadraConfig.cmake ${CMAKE_BINARY_DIR}/quadraConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)

# `cmake --install` puts the library, the headers an embedder includes and a
# package config (and quadra.pc) in place, so an embedder writes
# find_package(quadra) and links quadra::quadra, including only <quadra/...>.
# The lab (references, ground truth, test scenes), the kernels and the
# engine's internal headers are not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The public headers only (include/quadra and the generated version.h); the
# engine's own headers stay in the tree. libquadra.so is the facade over the
# engine (engine/CMakeLists.txt): its dependencies are private, so the
# package config finds none of them.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/quadra ${PROJECT_BINARY_DIR}/include/quadra
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS quadra_shared EXPORT quadraTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# pkg-config, relocatable: paths relative to where quadra.pc is installed.
configure_file(${PROJECT_SOURCE_DIR}/cmake/quadra.pc.in ${PROJECT_BINARY_DIR}/quadra.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/quadra.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
# The command-line tool, for offline users of the installed package, with the
# program its `report` runs from beside it (tools/CMakeLists.txt).
install(TARGETS quadra quadra-report RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# And the OpenImageIO module its `report textures` loads, where it was built
# (tools/CMakeLists.txt), in the folder that tools/CMakeLists.txt tells
# quadra-report to look in (QUADRA_OIIO_PEER_INSTALL_DIR).
if(TARGET quadra_oiio_peer)
  install(TARGETS quadra_oiio_peer LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/quadra)
endif()
install(EXPORT quadraTargets NAMESPACE quadra:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/quadraConfig.cmake.in
  ${CMAKE_BINARY_DIR}/quadraConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/quadraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/quadraConfig.cmake ${CMAKE_BINARY_DIR}/quadraConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/quadra)

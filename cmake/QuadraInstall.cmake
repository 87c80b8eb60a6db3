# `cmake --install` puts the library, the headers an embedder includes and a
# package config in place, so an embedder writes find_package(quadra) and links
# quadra::quadra. The lab (references, ground truth, test scenes), the kernels
# and the stages' internals are not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The API and the records it takes and returns, with everything they include
# (the InstallAndFindPackage test compiles each installed header on its own,
# so one missing here fails there).
set(QUADRA_PUBLIC_HEADERS
    api/renderer.h api/camera.h
    scene/scene.h scene/gltf_loader.h scene/animation.h
    io/frame.h io/image_io.h
    texture/texture.h texture/image.h texture/sampler_state.h texture/texel_format.h
    texture/texture_sampler.h texture/texture_view.h
    window/window_space.h window/sample_pattern.h
    core/error.h core/memory_budget.h
    simd/isa.h)
foreach(header ${QUADRA_PUBLIC_HEADERS})
  get_filename_component(folder ${header} DIRECTORY)
  if(EXISTS ${PROJECT_SOURCE_DIR}/engine/${header})
    install(FILES ${PROJECT_SOURCE_DIR}/engine/${header}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/quadra/${folder})
  else()
    install(FILES ${PROJECT_SOURCE_DIR}/${header}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/quadra/${folder})
  endif()
endforeach()

install(TARGETS quadra_engine EXPORT quadraTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The command-line tool, for offline users of the installed package.
install(TARGETS quadra RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# And the OpenImageIO module its `report textures` loads, where it was built
# (tools/CMakeLists.txt), in the folder that tools/CMakeLists.txt tells
# quadra to look in (QUADRA_OIIO_PEER_INSTALL_DIR).
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

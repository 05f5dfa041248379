# Installation and packaging: `cmake --install` puts the `tellus` command, the static libraries
# (the shaders are compiled into libtellus_shaders.a), the public headers (include/tellus/:
# the API of include/tellus/tellus.hpp; the library's own headers are not installed), a CMake package
# (find_package(tellus CONFIG) -> tellus::tellus) and a pkg-config file (tellus.pc) under the
# prefix; `cpack -G DEB` (or `make deb`) makes a Debian package of the same files.
#
# The libraries are static, so the package's config file finds their dependencies for the user
# (tellusConfig.cmake.in): an embedder links tellus::tellus and nothing else.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TELLUS_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/tellus")

# Every library tellus::tellus pulls in (the viewer is the command's own and stays out).
set(_tellus_libraries
  tellus_api tellus_core tellus_dem tellus_tile_format tellus_tiles tellus_shaders tellus_gl tellus_render
  tellus_lod tellus_stacks tellus_bdam tellus_eval tellus_export)
set_target_properties(tellus_all PROPERTIES EXPORT_NAME tellus)

install(TARGETS ${_tellus_libraries} tellus_all
        EXPORT tellusTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS tellus RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/tellus
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT development
        FILES_MATCHING PATTERN "*.hpp")
# The GLSL sources, for reference: the libraries carry them embedded.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/
        DESTINATION ${CMAKE_INSTALL_DATADIR}/tellus/shaders
        COMPONENT development
        FILES_MATCHING PATTERN "*.vert" PATTERN "*.frag" PATTERN "*.geom" PATTERN "*.comp"
                       PATTERN "*.glsl")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/embed
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        COMPONENT development)

install(EXPORT tellusTargets
        NAMESPACE tellus::
        FILE tellusTargets.cmake
        DESTINATION ${TELLUS_INSTALL_CMAKEDIR}
        COMPONENT development)
configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/tellusConfig.cmake.in
  ${PROJECT_BINARY_DIR}/tellusConfig.cmake
  INSTALL_DESTINATION ${TELLUS_INSTALL_CMAKEDIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/tellusConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tellusConfig.cmake ${PROJECT_BINARY_DIR}/tellusConfigVersion.cmake
        DESTINATION ${TELLUS_INSTALL_CMAKEDIR}
        COMPONENT development)

# pkg-config: the libraries in link order (users of a later library first), their
# dependencies as pkg-config modules where Debian ships a .pc file, the rest as flags.
set(TELLUS_PC_LIBS
  "-ltellus_api -ltellus_eval -ltellus_export -ltellus_render -ltellus_lod -ltellus_bdam -ltellus_stacks -ltellus_tiles -ltellus_tile_format -ltellus_gl -ltellus_shaders -ltellus_dem -ltellus_core")
configure_file(${PROJECT_SOURCE_DIR}/cmake/tellus.pc.in ${PROJECT_BINARY_DIR}/tellus.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/tellus.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT development)

# The Debian package: one package with the command, the libraries and the headers. Depends
# on the shared libraries the command links (dpkg-shlibdeps) and on the -dev packages whose
# headers and CMake files the installed package's users need.
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "tellus")
set(CPACK_PACKAGE_VENDOR "Tellus")
set(CPACK_PACKAGE_CONTACT "Tellus engineers <tellus@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Real-time rendering of very large terrains: tile pyramids, GPU level-of-detail renderers")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libgdal-dev, libproj-dev, libglm-dev, libtbb-dev, libspdlog-dev, libfmt-dev, nlohmann-json3-dev, libepoxy-dev, libegl-dev, libglfw3-dev, libstb-dev, libzstd-dev, libxxhash-dev, liblerc-dev, libmeshoptimizer-dev, libtinygltf-dev, libcurl4-openssl-dev, libabsl-dev, pkg-config")
set(CPACK_DEB_COMPONENT_INSTALL OFF)
include(CPack)

# `cmake --install`: the `pbrt_ext` command, the library, every header, and a package config so
# that another project writes find_package(pbrt_ext) and links
#   pbrt_ext::fabric    the fabric BxDFs, header-only (C++20), for any renderer
#   pbrt_ext::pbrt_ext  the renderer as a static library (scene loading, rendering)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PBRT_EXT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pbrt_ext)

install(TARGETS pbrt_ext fabric pbrt_ext_cli
        EXPORT pbrt_extTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Where images/imagecodec.cpp looks for it from an installed executable (bin/../<libdir>/pbrt_ext).
install(TARGETS pbrt_ext_imagecodec LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/pbrt_ext)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/pbrt_ext/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pbrt_ext
        FILES_MATCHING PATTERN "*.h")
install(EXPORT pbrt_extTargets
        NAMESPACE pbrt_ext::
        DESTINATION ${PBRT_EXT_INSTALL_CMAKEDIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/pbrt_extConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/pbrt_extConfig.cmake
                              INSTALL_DESTINATION ${PBRT_EXT_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pbrt_extConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pbrt_extConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/pbrt_extConfigVersion.cmake
        DESTINATION ${PBRT_EXT_INSTALL_CMAKEDIR})

# Install rules and the exported CMake package (included at the end of the top-level CMakeLists).
#
#   <prefix>/include/mvcl/...                       public headers
#   <prefix>/${CMAKE_INSTALL_LIBDIR}/libmvcl.so*    the framework
#   <prefix>/lib/mvcl/plugins/mvcl-lens-*.so        lens plugins (fixed path, see MvclLensPlugin.cmake)
#   <prefix>/bin/mvcl-render                        finds libmvcl through its RPATH and the
#                                                   plugins as <exe dir>/../lib/mvcl/plugins
#   <prefix>/${CMAKE_INSTALL_LIBDIR}/cmake/mvcl/    mvclConfig.cmake, mvclConfigVersion.cmake,
#                                                   mvclTargets.cmake, MvclLensPlugin.cmake
#
# and the testing component (MVCL_BUILD_TESTING_LIBRARY, find_package(mvcl COMPONENTS testing)):
#
#   <prefix>/include/mvcl/testing/...               conformance suite and LensTestScene headers
#   <prefix>/${CMAKE_INSTALL_LIBDIR}/libmvcl_testing.a
#   <prefix>/bin/mvcl-lens-conformance              the suite on plugin modules
#   <prefix>/${CMAKE_INSTALL_LIBDIR}/cmake/mvcl/mvclTestingTargets.cmake
#                                                   mvcl::testing, mvcl::mvcl-lens-conformance

include(CMakePackageConfigHelpers)

set(MVCL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/mvcl)

install(TARGETS mvcl EXPORT mvclTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/framework/include/mvcl
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    FILES_MATCHING PATTERN "*.h")

# The installed app finds libmvcl.so in a non-system prefix without LD_LIBRARY_PATH.
set_target_properties(mvcl-render PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")

install(EXPORT mvclTargets NAMESPACE mvcl:: DESTINATION ${MVCL_INSTALL_CMAKEDIR})

if(TARGET mvcl_testing)
    install(TARGETS mvcl_testing mvcl-lens-conformance EXPORT mvclTestingTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/testing/include/mvcl/testing
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/mvcl
        FILES_MATCHING PATTERN "*.h")
    set_target_properties(mvcl-lens-conformance PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
    install(EXPORT mvclTestingTargets NAMESPACE mvcl:: DESTINATION ${MVCL_INSTALL_CMAKEDIR})
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mvclConfig.cmake.in
    ${PROJECT_BINARY_DIR}/mvclConfig.cmake
    INSTALL_DESTINATION ${MVCL_INSTALL_CMAKEDIR}
    PATH_VARS MVCL_LENS_PLUGIN_INSTALL_DIR)
# The plugin ABI may change between minor versions before 1.0.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mvclConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES
    ${PROJECT_BINARY_DIR}/mvclConfig.cmake
    ${PROJECT_BINARY_DIR}/mvclConfigVersion.cmake
    ${PROJECT_SOURCE_DIR}/cmake/MvclLensPlugin.cmake
    DESTINATION ${MVCL_INSTALL_CMAKEDIR})

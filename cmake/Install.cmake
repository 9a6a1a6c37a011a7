# Installs the library, the command and a CMake package: find_package(depthtrack) then
# target_link_libraries(app PRIVATE depthtrack::depthtrack).
include(CMakePackageConfigHelpers)
# The installed command finds the installed library beside it, without LD_LIBRARY_PATH. Third-party
# libraries are found as the system finds them (INSTALL_RPATH_USE_LINK_PATH would not help where a
# package folder is on gcc's LIBRARY_PATH, as on the GPU machine: CMake counts it as implicit).
file(RELATIVE_PATH _depthtrack_bin_to_lib ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
set_target_properties(depthtrack_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${_depthtrack_bin_to_lib}")
install(TARGETS depthtrack depthtrack_cli EXPORT depthtrackTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/depthtrack DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT depthtrackTargets NAMESPACE depthtrack:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/depthtrack)
# The static branch of the package config finds OSMesa when the library links it.
if(DEPTHTRACK_WITH_GL AND OSMESA_FOUND)
  set(DEPTHTRACK_PACKAGE_OSMESA ON)
else()
  set(DEPTHTRACK_PACKAGE_OSMESA OFF)
endif()
get_property(DEPTHTRACK_BACKEND_PACKAGES GLOBAL PROPERTY DEPTHTRACK_BACKEND_PACKAGES)
configure_package_config_file(cmake/depthtrackConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/depthtrackConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/depthtrack)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/depthtrackConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/depthtrackConfig.cmake ${PROJECT_BINARY_DIR}/depthtrackConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/depthtrack)

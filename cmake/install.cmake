# cmake --install: headers, the static library and the CMake package (find_package(drillwave) ->
# drillwave::drillwave); apps/CMakeLists.txt installs the tool.
include(CMakePackageConfigHelpers)
set(DRILLWAVE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/drillwave)
install(TARGETS drillwave EXPORT drillwaveTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/include/drillwave DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT drillwaveTargets NAMESPACE drillwave:: DESTINATION ${DRILLWAVE_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/drillwaveConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/drillwaveConfig.cmake INSTALL_DESTINATION ${DRILLWAVE_CMAKE_DIR})
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/drillwaveConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/drillwaveConfig.cmake ${PROJECT_BINARY_DIR}/drillwaveConfigVersion.cmake
        DESTINATION ${DRILLWAVE_CMAKE_DIR})

# `cmake --install build --prefix P` lays out:
#   P/bin/lccp                                  the tool (RPATH $ORIGIN/../lib)
#   P/lib/liblccp_stream.so*                    the library (RPATH $ORIGIN)
#   P/lib/libOpenNI2.so.0 -> the system's       so that OpenNI2 loads its drivers from
#   P/lib/OpenNI2/Drivers/                      here: the virtual sensor, links to the
#                                               stock file and PS1080 drivers
#   P/include/lccp/                             the public headers
#   P/lib/cmake/LccpStream/                     find_package(LccpStream CONFIG): LccpStream::lccp
#   P/lib/python3.X/dist-packages/lccp_stream*  the Python module (src/python)
#   P/bin/lccp_ros, P/lib/liblccp_ros_nodelet.so, P/share/lccp_ros/
#                                               with ROS: node, nodelet, ROS package folder (src/ros)
# Every path the programs use is relative to their own file, so P can be moved.
include(CMakePackageConfigHelpers)
set(LCCP_INSTALL_CMAKEDIR lib/cmake/LccpStream)

set_target_properties(lccp PROPERTIES INSTALL_RPATH "$ORIGIN/../lib")
set_target_properties(lccp_stream PROPERTIES INSTALL_RPATH "$ORIGIN")
install(TARGETS lccp RUNTIME DESTINATION bin)
install(TARGETS lccp_stream EXPORT LccpStreamTargets LIBRARY DESTINATION lib)
install(TARGETS lccp_virtual_sensor LIBRARY DESTINATION lib/OpenNI2/Drivers)
# The links to the system's libOpenNI2 and stock drivers are installed as links.
install(FILES ${LCCP_OPENNI2_FOLDER}/libOpenNI2.so.0 DESTINATION lib)
install(DIRECTORY ${LCCP_OPENNI2_DRIVERS}/ DESTINATION lib/OpenNI2/Drivers
        FILES_MATCHING PATTERN "libOniFile.so.0" PATTERN "libPS1080.so.0")
install(DIRECTORY include/lccp DESTINATION include)

install(EXPORT LccpStreamTargets NAMESPACE LccpStream:: DESTINATION ${LCCP_INSTALL_CMAKEDIR})
configure_package_config_file(cmake/LccpStreamConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/generated/LccpStreamConfig.cmake
                              INSTALL_DESTINATION ${LCCP_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/generated/LccpStreamConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/generated/LccpStreamConfig.cmake
              ${CMAKE_BINARY_DIR}/generated/LccpStreamConfigVersion.cmake
        DESTINATION ${LCCP_INSTALL_CMAKEDIR})

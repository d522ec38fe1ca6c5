# ROS 1 from Debian 12's packages (ros-core, librosbag-dev, libnodeletlib-dev, ...):
# the rosbag frame source in lccp_capture (src/capture/rosbag/) and the node in src/ros.
#
# Debian's pkg-config files for rosbag_storage and nodelet require a pluginlib.pc
# that its pluginlib-dev (the ament flavour) does not ship, and pluginlib's CMake
# config needs ament's Python tooling, so headers and libraries are found
# directly. pluginlib, class_loader and the ROS 2 utilities they include keep
# their headers one folder deeper (/usr/include/pluginlib/pluginlib/...).
#
# ROS 1's generated messages and roscpp's serialization use
# std::allocator<T>::rebind, which C++20 removed: every file that includes a ROS
# header is compiled as C++17 (lccp_ros_cxx17) and talks to the rest through
# plain types (src/capture/rosbag/ros_frames.hpp).
set(LCCP_HAVE_ROS OFF)
if(NOT LCCP_BUILD_ROS)
  message(STATUS "ROS 1: off (LCCP_BUILD_ROS=OFF); the rosbag source and the lccp_ros node are skipped")
  return()
endif()

set(LCCP_ROS_HEADERS
  ros/ros.h rosbag/bag.h nodelet/nodelet.h sensor_msgs/PointCloud2.h sensor_msgs/CameraInfo.h
  std_msgs/String.h visualization_msgs/MarkerArray.h diagnostic_msgs/DiagnosticArray.h)
set(LCCP_ROS_NESTED_HEADERS  # folder/header.hpp under /usr/include/folder
  pluginlib/class_list_macros.hpp class_loader/class_loader.hpp rcpputils/shared_library.hpp
  rcutils/logging_macros.h ament_index_cpp/get_package_prefix.hpp)
set(LCCP_ROS_LIBRARY_NAMES
  rosbag_storage nodeletlib class_loader roscpp rosconsole roscpp_serialization xmlrpcpp rostime cpp_common
  console_bridge)

set(LCCP_ROS_MISSING "")
set(LCCP_ROS_INCLUDE_DIRS "")
foreach(header ${LCCP_ROS_HEADERS} ${LCCP_ROS_NESTED_HEADERS})
  string(MAKE_C_IDENTIFIER "LCCP_ROS_HEADER_${header}" variable)
  get_filename_component(folder ${header} DIRECTORY)
  find_path(${variable} ${header} PATH_SUFFIXES ${folder})
  if(${variable})
    list(APPEND LCCP_ROS_INCLUDE_DIRS ${${variable}})
  else()
    list(APPEND LCCP_ROS_MISSING ${header})
  endif()
endforeach()
set(LCCP_ROS_LIBRARIES "")
foreach(name ${LCCP_ROS_LIBRARY_NAMES})
  find_library(LCCP_ROS_LIBRARY_${name} ${name})
  if(LCCP_ROS_LIBRARY_${name})
    list(APPEND LCCP_ROS_LIBRARIES ${LCCP_ROS_LIBRARY_${name}})
  else()
    list(APPEND LCCP_ROS_MISSING lib${name})
  endif()
endforeach()
find_program(LCCP_ROSCORE roscore)
if(NOT LCCP_ROSCORE)
  list(APPEND LCCP_ROS_MISSING roscore)
endif()
if(LCCP_ROS_MISSING)
  list(JOIN LCCP_ROS_MISSING ", " missing)
  message(STATUS "ROS 1 not found (missing ${missing}): the rosbag source and the lccp_ros node are skipped "
                 "(scripts/install-deps.sh installs ROS)")
  return()
endif()
list(REMOVE_DUPLICATES LCCP_ROS_INCLUDE_DIRS)
set(LCCP_HAVE_ROS ON)
message(STATUS "ROS 1 found: the rosbag source and the lccp_ros node are built")

# Compiles `sources` (of the current folder) as C++17 with ROS's headers as system
# headers, so -Wall -Wextra -Werror holds for our code only.
function(lccp_ros_cxx17 target)
  # No precompiled headers there: they are C++20 (LCCP_PRECOMPILE_HEADERS).
  set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS "-std=c++17" SKIP_PRECOMPILE_HEADERS ON)
  target_include_directories(${target} SYSTEM PRIVATE ${LCCP_ROS_INCLUDE_DIRS})
endfunction()

set(LCCP_ROSBAG_DIR ${PROJECT_SOURCE_DIR}/src/capture/rosbag)
target_sources(lccp_capture PRIVATE ${LCCP_ROSBAG_DIR}/rosbag_source.cpp ${LCCP_ROSBAG_DIR}/bag_file.cpp
                                    ${LCCP_ROSBAG_DIR}/ros_messages.cpp)
lccp_ros_cxx17(lccp_capture ${LCCP_ROSBAG_DIR}/bag_file.cpp ${LCCP_ROSBAG_DIR}/ros_messages.cpp)
# PUBLIC: the tests (tests/rosbag_source_test.cpp) are built with it too.
target_compile_definitions(lccp_capture PUBLIC LCCP_HAVE_ROSBAG)
target_link_libraries(lccp_capture PRIVATE ${LCCP_ROS_LIBRARIES})
target_link_libraries(lccp_stream PRIVATE ${LCCP_ROS_LIBRARIES})

add_subdirectory(src/ros)

# The optional ROS 1 part (AMOS_WITH_ROS): Debian 12's ROS 1 packages (scripts/install_ros_deps.sh). Their catkin
# CMake packages pull in ROS 2's ament machinery through pluginlib (and need its Python modules), so the headers and
# libraries are found directly instead. Defines, when the option is on:
#   amos_ros_bag   reading and writing bag files (rosbag_storage; no ROS master): src/amos/rosbag
#   amos_ros_node  a node's client library, messages and transforms (roscpp, tf2_ros): apps/amos_slam_node
set(amos_ros_found ON)
find_path(AMOS_ROSBAG_INCLUDE_DIR rosbag/bag.h)
find_path(AMOS_ROS_MSGS_INCLUDE_DIR NAMES sensor_msgs/Image.h nav_msgs/OccupancyGrid.h)
# rosbag/bag.h includes pluginlib's headers, and they ROS 2's class_loader, rcpputils, rcutils and ament_index_cpp:
# each in a folder of its own name under /usr/include.
set(amos_ros_nested_dirs)
foreach(header pluginlib/class_loader.hpp class_loader/class_loader.hpp rcpputils/shared_library.hpp
               rcutils/types.h ament_index_cpp/get_resource.hpp)
  get_filename_component(package ${header} DIRECTORY)
  string(TOUPPER ${package} upper)
  find_path(AMOS_ROS_${upper}_INCLUDE_DIR ${header} PATH_SUFFIXES ${package})
  if(NOT AMOS_ROS_${upper}_INCLUDE_DIR)
    set(amos_ros_found OFF)
  endif()
  list(APPEND amos_ros_nested_dirs ${AMOS_ROS_${upper}_INCLUDE_DIR})
endforeach()
set(amos_ros_bag_libs rosbag_storage roscpp_serialization rostime cpp_common console_bridge boost_filesystem)
set(amos_ros_node_libs roscpp rosconsole xmlrpcpp tf2_ros tf2 boost_system boost_chrono boost_thread)
foreach(dir AMOS_ROSBAG_INCLUDE_DIR AMOS_ROS_MSGS_INCLUDE_DIR)
  if(NOT ${dir})
    set(amos_ros_found OFF)
  endif()
endforeach()
foreach(lib IN LISTS amos_ros_bag_libs amos_ros_node_libs)
  find_library(AMOS_ROS_LIB_${lib} NAMES ${lib})
  if(NOT AMOS_ROS_LIB_${lib})
    set(amos_ros_found OFF)
  endif()
endforeach()
option(AMOS_WITH_ROS "Build the ROS 1 bag source (run --sequence X.bag) and node (amos_slam_node)" ${amos_ros_found})
if(AMOS_WITH_ROS AND NOT amos_ros_found)
  message(FATAL_ERROR "AMOS_WITH_ROS=ON but the ROS 1 packages were not found: run scripts/install_ros_deps.sh, or "
                      "configure with -DAMOS_WITH_ROS=OFF")
elseif(NOT AMOS_WITH_ROS)
  message(STATUS "ROS: bag source and node off (scripts/install_ros_deps.sh installs them)")
  return()
endif()
function(amos_ros_target target)
  set(paths)
  foreach(lib IN LISTS ARGN)
    list(APPEND paths ${AMOS_ROS_LIB_${lib}})
  endforeach()
  add_library(${target} INTERFACE IMPORTED)
  # The ROS 1 headers are in /usr/include (always searched), the nested ones above one folder deeper. An imported
  # target's folders are system folders: their headers' warnings are not this project's.
  set_target_properties(${target} PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${amos_ros_nested_dirs}"
    INTERFACE_LINK_LIBRARIES "${paths}")
endfunction()
amos_ros_target(amos_ros_bag ${amos_ros_bag_libs})
amos_ros_target(amos_ros_node ${amos_ros_node_libs} ${amos_ros_bag_libs})
message(STATUS "ROS: ${AMOS_ROSBAG_INCLUDE_DIR} (bag source and node on)")

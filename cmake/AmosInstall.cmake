# The installed package (issue 44): `cmake --install build --prefix P` puts in P
#   bin/amos-slam
#   lib/amos/libamos_dense_plugin.so                           the dense map's module that amos-slam loads (Open3D)
#   include/amos/{slam.h,dense_map.h,sequence_folder.h,logging.h,version.h}  the public API (nothing of src/amos/)
#   lib/libamos_*.a                                            amos_slam and the modules it links (static)
#   lib/cmake/AmosSlam/                                        find_package(AmosSlam) -> AmosSlam::amos_slam
#   lib/pkgconfig/amos-slam.pc
#   share/amos-slam/models/, share/amos-slam/configs/          the networks, the ORB vocabulary, the settings files
#   lib/python3/dist-packages/amos_slam*.so                    with AMOS_BUILD_PYTHON (python/CMakeLists.txt)
include(CMakePackageConfigHelpers)

# The project's libraries that `target` links, itself included, in link order: each before every library it uses
# (what a static link needs; the pkg-config file lists them so).
function(amos_link_closure target out)
  # The closure, with each library's direct project dependencies in deps_<name>.
  set(closure "")
  set(stack ${target})
  while(stack)
    list(POP_FRONT stack t)
    get_target_property(aliased ${t} ALIASED_TARGET)
    if(aliased)
      set(t ${aliased})
    endif()
    if(t IN_LIST closure)
      continue()
    endif()
    list(APPEND closure ${t})
    set(deps_${t} "")
    get_target_property(links ${t} LINK_LIBRARIES)
    foreach(d IN LISTS links)
      if(TARGET ${d} AND d MATCHES "^amos(::|_)")
        get_target_property(imported ${d} IMPORTED)
        get_target_property(aliased_d ${d} ALIASED_TARGET)
        if(aliased_d)
          set(d ${aliased_d})
        endif()
        if(NOT imported)
          list(APPEND deps_${t} ${d})
          list(APPEND stack ${d})
        endif()
      endif()
    endforeach()
  endwhile()
  # Kahn's order: a library is placed once no library left needs it.
  set(order "")
  set(left ${closure})
  while(left)
    set(placed "")
    foreach(t IN LISTS left)
      set(needed OFF)
      foreach(u IN LISTS left)
        if(t IN_LIST deps_${u})
          set(needed ON)
        endif()
      endforeach()
      if(NOT needed)
        list(APPEND placed ${t})
      endif()
    endforeach()
    if(NOT placed)
      message(FATAL_ERROR "amos_link_closure: a dependency cycle among ${left}")
    endif()
    list(APPEND order ${placed})
    list(REMOVE_ITEM left ${placed})
  endwhile()
  set(${out} ${order} PARENT_SCOPE)
endfunction()

amos_link_closure(amos_api AMOS_INSTALLED_LIBRARIES)
set(AMOS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/AmosSlam)
install(TARGETS ${AMOS_INSTALLED_LIBRARIES} EXPORT AmosSlamTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS amos-slam RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The dense plugin, where amos-slam looks for it from its own folder (../lib/amos/: run/dense_plugin_loader.h),
# whatever CMAKE_INSTALL_LIBDIR is.
if(TARGET amos_dense_plugin)
  install(TARGETS amos_dense_plugin LIBRARY DESTINATION lib/amos)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/include/amos/slam.h ${PROJECT_SOURCE_DIR}/include/amos/sequence_folder.h
  ${PROJECT_SOURCE_DIR}/include/amos/logging.h ${PROJECT_SOURCE_DIR}/include/amos/dense_map.h
  ${PROJECT_BINARY_DIR}/include/amos/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/amos)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/ DESTINATION ${CMAKE_INSTALL_DATADIR}/amos-slam/models)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/amos-slam/configs
  FILES_MATCHING PATTERN "*.yaml" PATTERN "README.md")
install(EXPORT AmosSlamTargets NAMESPACE AmosSlam:: DESTINATION ${AMOS_CMAKE_DIR})

# The optional libraries are imported targets of this build (AmosOptionalLibrary.cmake): the package makes them
# again from the same files.
set(AMOS_PACKAGE_IMPORTED "")
foreach(t amos_libdeflate amos_openni2 amos_ros_bag)
  if(TARGET ${t})
    get_target_property(lib ${t} INTERFACE_LINK_LIBRARIES)
    string(APPEND AMOS_PACKAGE_IMPORTED
      "if(NOT TARGET ${t})\n  add_library(${t} INTERFACE IMPORTED)\n"
      "  set_target_properties(${t} PROPERTIES INTERFACE_LINK_LIBRARIES \"${lib}\")\nendif()\n")
  endif()
endforeach()
# The packages only some builds' libraries link (the dense map's Open3D and OpenMP, the synthetic sequences' PNG):
# found by the package when an installed library links their targets.
set(AMOS_PACKAGE_OPTIONAL "")
set(amos_optional_packages "Open3D::Open3D=Open3D CONFIG" "OpenMP::OpenMP_CXX=OpenMP COMPONENTS CXX" "PNG::PNG=PNG"
    "JPEG::JPEG=JPEG")
foreach(entry IN LISTS amos_optional_packages)
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 imported)
  list(GET pair 1 arguments)
  foreach(t IN LISTS AMOS_INSTALLED_LIBRARIES)
    get_target_property(links ${t} LINK_LIBRARIES)
    if(imported IN_LIST links)
      string(APPEND AMOS_PACKAGE_OPTIONAL "find_dependency(${arguments})\n")
      break()
    endif()
  endforeach()
endforeach()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/AmosSlamConfig.cmake.in
  ${PROJECT_BINARY_DIR}/AmosSlamConfig.cmake INSTALL_DESTINATION ${AMOS_CMAKE_DIR} PATH_VARS CMAKE_INSTALL_DATADIR)
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/AmosSlamConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/AmosSlamConfig.cmake ${PROJECT_BINARY_DIR}/AmosSlamConfigVersion.cmake
  DESTINATION ${AMOS_CMAKE_DIR})

# pkg-config: the static libraries in link order, then what they use.
set(AMOS_PC_LIBS "")
foreach(t IN LISTS AMOS_INSTALLED_LIBRARIES)
  get_target_property(name ${t} OUTPUT_NAME)
  if(NOT name)
    set(name ${t})
  endif()
  string(APPEND AMOS_PC_LIBS " -l${name}")
endforeach()
string(APPEND AMOS_PC_LIBS " -lpng16 -ljpeg")  # io's image codecs
if(TARGET amos_libdeflate)
  string(APPEND AMOS_PC_LIBS " -ldeflate")
endif()
if(TARGET amos_dense)
  string(APPEND AMOS_PC_LIBS " -lOpen3D -lgomp")
endif()
if(TARGET amos_ros_bag)  # amos::SequenceFolder's bags (src/amos/rosbag)
  get_target_property(ros_bag_libs amos_ros_bag INTERFACE_LINK_LIBRARIES)
  foreach(lib IN LISTS ros_bag_libs)
    string(APPEND AMOS_PC_LIBS " ${lib}")
  endforeach()
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/amos-slam.pc.in ${PROJECT_BINARY_DIR}/amos-slam.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/amos-slam.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

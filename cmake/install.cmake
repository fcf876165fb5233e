# install.cmake - what `cmake --install` puts where (included from the top
# CMakeLists.txt once the targets exist):
#   bin/rtcl                                the tool (library linked in statically)
#   include/rtcl/rt.h                       the public API (self-contained)
#   lib/librtcl.a, lib/librtcl.so*          the library, static and shared
#   lib/librtcl_image.so                    the image module (PNG, EXR), when built
#   lib/librtcl_gltf.so                     the glTF module (tinygltf), when built
#   lib/cmake/rtcl/                         find_package(rtcl): rtcl::rtcl (shared)
#                                           and rtcl::rtcl_static
#   lib/pkgconfig/rtcl.pc                   pkg-config rtcl (--static for the archive)
# Neither Embree nor TBB is a dependency of any of them: only rtcl bench
# links the benchmark peer, inside the rtcl program.
include(CMakePackageConfigHelpers)

set_target_properties(rt PROPERTIES EXPORT_NAME rtcl_static)
set_target_properties(rt_shared PROPERTIES EXPORT_NAME rtcl)
install(TARGETS rt rt_shared EXPORT rtclTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rtcl)
install(TARGETS rtcl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET rtcl_image)
  install(TARGETS rtcl_image LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
if(TARGET rtcl_gltf)
  install(TARGETS rtcl_gltf LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
install(FILES ${CMAKE_SOURCE_DIR}/host/rt.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rtcl)

set(rt_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rtcl)
install(EXPORT rtclTargets NAMESPACE rtcl:: DESTINATION ${rt_cmake_dir})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/rtclConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/rtclConfig.cmake INSTALL_DESTINATION ${rt_cmake_dir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/rtclConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/rtclConfig.cmake
              ${CMAKE_BINARY_DIR}/package/rtclConfigVersion.cmake DESTINATION ${rt_cmake_dir})

# pkg-config: the static archive's own dependencies go in Libs.private.
set(RT_PC_PRIVATE "-lm -ldl -pthread")
if(RT_HAVE_JANSSON)
  string(APPEND RT_PC_PRIVATE " -ljansson")
endif()
if(RT_HAVE_OPENCL)
  string(APPEND RT_PC_PRIVATE " -lOpenCL")
endif()
if(RT_HAVE_VULKAN)
  string(APPEND RT_PC_PRIVATE " -lvulkan")
endif()
file(RELATIVE_PATH RT_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" RT_PC_TO_PREFIX "${RT_PC_TO_PREFIX}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/rtcl.pc.in ${CMAKE_BINARY_DIR}/package/rtcl.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/package/rtcl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

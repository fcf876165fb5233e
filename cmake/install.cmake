# SPDX-License-Identifier: Apache-2.0
# install.cmake - what `cmake --install` puts where (included from the top
# CMakeLists.txt once the targets exist):
#   bin/rtcl                                the tool (library linked in statically)
#   include/rtcl/rt.h, rtcl_version.h       the public API: #include <rtcl/rt.h>
#                                           (include/ is on the targets' and pkg-config's path)
#   lib/librtcl.a, lib/librtcl.so*          the library, static and shared
#   lib/librtcl_image.so                    the image module (PNG, EXR), when built
#   lib/librtcl_gltf.so                     the glTF module (tinygltf), when built
#   lib/cmake/rtcl/                         find_package(rtcl): rtcl::rtcl (shared)
#                                           and rtcl::rtcl_static
#   lib/pkgconfig/rtcl.pc                   pkg-config rtcl (--static for the archive)
#   share/man/man1/rtcl*.1.gz               a manual page per command (help2man, where found)
#   share/bash-completion/completions/rtcl  bash completion
#   share/doc/rtcl/examples/                examples/, to build against the install
# Neither Embree nor TBB is a dependency of any of them: only rtcl bench
# links the benchmark peer, inside the rtcl program.
# Two components, the two Debian packages of cmake/package.cmake: runtime
# (librtcl.so.*, rtcl, the image module, manual pages, completion) and dev
# (headers, librtcl.a, the librtcl.so link, pkg-config, the CMake package,
# the examples). A plain cmake --install installs both.
include(CMakePackageConfigHelpers)

set_target_properties(rt PROPERTIES EXPORT_NAME rtcl_static)
set_target_properties(rt_shared PROPERTIES EXPORT_NAME rtcl)
install(TARGETS rt rt_shared EXPORT rtclTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS rtcl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
if(TARGET rtcl_image)
  install(TARGETS rtcl_image LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
endif()
install(FILES ${CMAKE_SOURCE_DIR}/host/rt.h ${CMAKE_BINARY_DIR}/version/rtcl_version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rtcl COMPONENT dev)
install(FILES ${CMAKE_SOURCE_DIR}/examples/CMakeLists.txt ${CMAKE_SOURCE_DIR}/examples/orbit.c
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples COMPONENT dev)

# The manual pages and the bash completion, generated from rtcl's own help
# (tools/gen_cli_docs.sh: help2man, where installed, and 'rtcl help
# --synopsis'); rtcl runs on the build machine, so not in a cross build.
if(NOT CMAKE_CROSSCOMPILING)
  find_program(RT_HELP2MAN help2man)
  message(STATUS "Manual pages (help2man): ${RT_HELP2MAN}")
  set(rt_cli_docs ${CMAKE_BINARY_DIR}/cli_docs)
  add_custom_command(
    OUTPUT ${rt_cli_docs}/completion/rtcl
    COMMAND bash ${CMAKE_SOURCE_DIR}/tools/gen_cli_docs.sh $<TARGET_FILE:rtcl> ${PROJECT_VERSION} ${rt_cli_docs}
    DEPENDS rtcl ${CMAKE_SOURCE_DIR}/tools/gen_cli_docs.sh
    COMMENT "Writing rtcl's manual pages and bash completion from its help")
  add_custom_target(rtcl_cli_docs ALL DEPENDS ${rt_cli_docs}/completion/rtcl)
  install(DIRECTORY ${rt_cli_docs}/man1 DESTINATION ${CMAKE_INSTALL_MANDIR} COMPONENT runtime)
  install(FILES ${rt_cli_docs}/completion/rtcl
          DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions COMPONENT runtime)
endif()
if(TARGET rtcl_gltf)
  install(TARGETS rtcl_gltf LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
endif()

set(rt_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rtcl)
install(EXPORT rtclTargets NAMESPACE rtcl:: DESTINATION ${rt_cmake_dir} COMPONENT dev)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/rtclConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/rtclConfig.cmake INSTALL_DESTINATION ${rt_cmake_dir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/rtclConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY ${RTCL_COMPATIBILITY}) # the policy in CMakeLists.txt
install(FILES ${CMAKE_BINARY_DIR}/package/rtclConfig.cmake
              ${CMAKE_BINARY_DIR}/package/rtclConfigVersion.cmake DESTINATION ${rt_cmake_dir}
        COMPONENT dev)

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
install(FILES ${CMAKE_BINARY_DIR}/package/rtcl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)

include(${CMAKE_SOURCE_DIR}/cmake/package.cmake)

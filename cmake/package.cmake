# SPDX-License-Identifier: Apache-2.0
# package.cmake - Debian packages from the build (CPack DEB), included at the
# end of cmake/install.cmake:
#   cd build && cpack -G DEB
# writes two packages, one per install component:
#   rtcl_VERSION_ARCH.deb         runtime: librtcl.so.0.MINOR, rtcl, the image
#                                 module, manual pages, bash completion
#   librtcl-dev_VERSION_ARCH.deb  dev: <rtcl/rt.h>, librtcl.a, the librtcl.so
#                                 link, pkg-config, the CMake package, examples
# installed under /usr. The runtime package's dependencies are read from its
# binaries by dpkg-shlibdeps; the -dev package depends on the same version of
# the runtime. Only the .deb is made by default (CPACK_GENERATOR).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rtcl)
set(CPACK_PACKAGE_VENDOR "rtcl")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "ray tracing of dynamic triangle scenes, exact on every backend")
set(CPACK_PACKAGE_CONTACT "rtcl maintainers <rtcl@invalid>")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://invalid/rtcl")

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME rtcl)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS "pocl-opencl-icd, mesa-vulkan-drivers, ffmpeg")
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION "the rtcl library (librtcl.so), the rtcl tool and its image module
Ray queries and Whitted-style rendering of dynamic triangle scenes on the CPU,
OpenCL and Vulkan, with the same bits on every backend.")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME librtcl-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "rtcl (= ${PROJECT_VERSION})")
# Linking the static archive needs its dependencies' -dev packages.
set(rt_dev_suggests "pkg-config, cmake")
if(RT_HAVE_JANSSON)
  string(APPEND rt_dev_suggests ", libjansson-dev")
endif()
if(RT_HAVE_OPENCL)
  string(APPEND rt_dev_suggests ", ocl-icd-opencl-dev")
endif()
if(RT_HAVE_VULKAN)
  string(APPEND rt_dev_suggests ", libvulkan-dev")
endif()
set(CPACK_DEBIAN_DEV_PACKAGE_SUGGESTS "${rt_dev_suggests}")
set(CPACK_COMPONENT_DEV_DESCRIPTION "development files of rtcl: <rtcl/rt.h>, librtcl.a, pkg-config, CMake
Headers, the static library, the pkg-config file rtcl.pc, the CMake package
(find_package(rtcl): rtcl::rtcl, rtcl::rtcl_static) and examples.")
include(CPack)

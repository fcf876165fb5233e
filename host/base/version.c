/* SPDX-License-Identifier: Apache-2.0 */
/* version.c - rt_version(): the version the library was built as
 * (rtcl_version.h, written by CMake from project()'s version). */
#include "rt.h"

const char *rt_version(void) {
    return RTCL_VERSION_STRING;
}

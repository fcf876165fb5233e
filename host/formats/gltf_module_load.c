/* SPDX-License-Identifier: Apache-2.0 */
/* gltf_module_load.c - finding and loading the glTF module (gltf_module.h),
 * by the image module's rules (image_load.c).
 *
 * Where it is looked for, in order:
 *  1. beside the binary that holds this code (dladdr): the shared library
 *     librtcl.so, or the program itself when it links the static library
 *     (rtcl in the build folder, where the module is built beside it);
 *  2. from there, the relative path from the install's bin to its lib folder
 *     (an installed rtcl, linked statically, in PREFIX/bin);
 *  3. by bare name, as the dynamic loader finds it (the program's RUNPATH,
 *     which the build gives every program of the build tree, then
 *     LD_LIBRARY_PATH and the loader's cache);
 *  4. the install's lib folder as configured (a user program linked with the
 *     installed static library, anywhere).
 * A module that exists but does not load (libtinygltf missing)
 * is reported with the loader's reason, not skipped silently. */
#define _GNU_SOURCE /* dladdr */
#include "formats/gltf_module.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"

#ifndef RT_GLTF_MODULE_BIN_TO_LIB
#define RT_GLTF_MODULE_BIN_TO_LIB "../lib"
#endif

static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const rt_gltf_module *module_table;
static rt_status module_status = RT_ERROR_UNSUPPORTED;
static char module_reason[768];

#ifdef RT_HAVE_GLTF_MODULE
/* Tries one candidate. 1: loaded; 0: not there (keep looking); -1: there
 * but unusable (the reason is kept and the search stops). */
static int try_module(const char *path, int must_exist) {
    if (must_exist && access(path, F_OK) != 0) return 0;
    void *handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *why = dlerror();
        /* by bare name: not found is not an error, but found and unloadable is */
        if (!must_exist && (!why || strstr(why, "cannot open shared object file"))) return 0;
        snprintf(module_reason, sizeof module_reason, "%.400s does not load: %.300s", path,
                 why ? why : "no reason given");
        module_status = RT_ERROR_UNSUPPORTED;
        return -1;
    }
    rt_gltf_module_entry entry = NULL;
    void *symbol = dlsym(handle, RT_GLTF_MODULE_SYMBOL);
    memcpy(&entry, &symbol, sizeof entry); /* object to function pointer, as POSIX allows */
    const rt_gltf_module *table = entry ? entry() : NULL;
    if (!table || table->abi != RT_GLTF_MODULE_ABI || table->doc_size != sizeof(rt_gltf_doc) ||
        table->error_size != sizeof(rt_error) || !table->read || !table->free_doc) {
        snprintf(module_reason, sizeof module_reason,
                 "%.500s is not this version's glTF module (interface %d, expected %d): "
                 "reinstall rtcl",
                 path, table ? table->abi : 0, RT_GLTF_MODULE_ABI);
        dlclose(handle);
        module_status = RT_ERROR_UNSUPPORTED;
        return -1;
    }
    module_table = table; /* never closed: documents it made may still be freed */
    module_status = RT_OK;
    return 1;
}

static void load_module(void) {
    char here[4096] = "", path[4200];
    Dl_info info;
    if (dladdr((void *)&rt_gltf_module_get, &info) && info.dli_fname) {
        snprintf(here, sizeof here, "%s", info.dli_fname);
        char *slash = strrchr(here, '/');
        if (slash)
            *slash = '\0';
        else
            here[0] = '\0'; /* a bare name: the program was found through PATH */
    }
    if (here[0]) {
        snprintf(path, sizeof path, "%s/%s", here, RT_GLTF_MODULE_FILE);
        if (try_module(path, 1)) return;
        snprintf(path, sizeof path, "%s/%s/%s", here, RT_GLTF_MODULE_BIN_TO_LIB,
                 RT_GLTF_MODULE_FILE);
        if (try_module(path, 1)) return;
    }
    if (try_module(RT_GLTF_MODULE_FILE, 0)) return;
#ifdef RT_GLTF_MODULE_INSTALL_DIR
    snprintf(path, sizeof path, "%s/%s", RT_GLTF_MODULE_INSTALL_DIR, RT_GLTF_MODULE_FILE);
    if (try_module(path, 1)) return;
#endif
    snprintf(module_reason, sizeof module_reason,
             "the glTF module " RT_GLTF_MODULE_FILE " (tinygltf) was not found beside %.300s"
#ifdef RT_GLTF_MODULE_INSTALL_DIR
             " nor in " RT_GLTF_MODULE_INSTALL_DIR
#endif
             " nor on the library path: install it with rtcl; .obj and .json scenes need no module",
             here[0] ? here : "the program");
    module_status = RT_ERROR_UNSUPPORTED;
}
#else
static void load_module(void) {
    snprintf(module_reason, sizeof module_reason,
             "this build has no glTF support: tinygltf was not found when it was configured "
             "(install libtinygltf-dev nlohmann-json3-dev libstb-dev and configure again); .obj "
             "and .json scenes load without it");
    module_status = RT_ERROR_UNSUPPORTED;
}
#endif

const rt_gltf_module *rt_gltf_module_get(rt_error *err) {
    pthread_once(&module_once, load_module);
    if (!module_table) rt_fail(err, module_status, "%s", module_reason);
    return module_table;
}

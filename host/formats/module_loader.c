/* SPDX-License-Identifier: Apache-2.0 */
/* module_loader.c - the search of module_loader.h. */
#define _GNU_SOURCE /* dladdr */
#include "formats/module_loader.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#ifndef RT_MODULE_BIN_TO_LIB
#define RT_MODULE_BIN_TO_LIB "../lib"
#endif

/* Tries one candidate. 1: loaded (*table set); 0: not there (keep looking);
 * -1: there but unusable (the reason is written and the search stops). */
static int try_path(const rt_module_spec *spec, const char *path, int must_exist,
                    const void **table, char *reason, size_t cap) {
    if (must_exist && access(path, F_OK) != 0) return 0;
    void *handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *why = dlerror();
        /* By bare name, not found is not an error, but found and unloadable is. */
        if (!must_exist && (!why || strstr(why, "cannot open shared object file"))) return 0;
        snprintf(reason, cap, "%.400s does not load: %.300s", path, why ? why : "no reason given");
        return -1;
    }
    int abi = 0;
    *table = spec->open_table(dlsym(handle, spec->symbol), &abi);
    if (!*table) {
        snprintf(reason, cap,
                 "%.500s is not this version's %s (interface %d, expected %d): "
                 "reinstall rtcl",
                 path, spec->what, abi, spec->abi);
        dlclose(handle);
        return -1;
    }
    return 1;
}

const void *rt_module_load(const rt_module_spec *spec, char *reason, size_t cap) {
    char here[4096] = "", path[4200];
    const void *table = NULL;
    Dl_info info;
    if (dladdr((void *)&rt_module_load, &info) && info.dli_fname) {
        snprintf(here, sizeof here, "%s", info.dli_fname);
        char *slash = strrchr(here, '/');
        if (slash)
            *slash = '\0';
        else
            here[0] = '\0'; /* a bare name: the program was found through PATH */
    }
    int found = 0;
    if (here[0]) {
        snprintf(path, sizeof path, "%s/%s", here, spec->file);
        found = try_path(spec, path, 1, &table, reason, cap);
        if (!found) {
            snprintf(path, sizeof path, "%s/%s/%s", here, RT_MODULE_BIN_TO_LIB, spec->file);
            found = try_path(spec, path, 1, &table, reason, cap);
        }
    }
    if (!found) found = try_path(spec, spec->file, 0, &table, reason, cap);
#ifdef RT_MODULE_INSTALL_DIR
    if (!found) {
        snprintf(path, sizeof path, "%s/%s", RT_MODULE_INSTALL_DIR, spec->file);
        found = try_path(spec, path, 1, &table, reason, cap);
    }
#endif
    if (found > 0) return table;
    if (found == 0)
        snprintf(reason, cap,
                 "the %s %s (%s) was not found beside %.300s"
#ifdef RT_MODULE_INSTALL_DIR
                 " nor in " RT_MODULE_INSTALL_DIR
#endif
                 " nor on the library path: install it with rtcl; %s",
                 spec->what, spec->file, spec->wraps, here[0] ? here : "the program",
                 spec->without);
    return NULL;
}

/* SPDX-License-Identifier: Apache-2.0 */
/* module_loader.h - finding and loading an optional module of the library
 * (the image module over OpenImageIO, the glTF module over tinygltf): one
 * search, one set of messages, whatever the module.
 *
 * Where a module is looked for, in order:
 *  1. beside the binary that holds this code (dladdr): the shared library
 *     librtcl.so, or the program itself when it links the static library
 *     (rtcl in the build folder, where the modules are built beside it);
 *  2. from there, the relative path from the install's bin to its lib folder
 *     (an installed rtcl, linked statically, in PREFIX/bin);
 *  3. by bare name, as the dynamic loader finds it (the program's RUNPATH,
 *     which the build gives every program of the build tree, then
 *     LD_LIBRARY_PATH and the loader's cache);
 *  4. the install's lib folder as configured (a user program linked with the
 *     installed static library, anywhere).
 * A module that exists but does not load (a library it needs is missing) or
 * is another version's is reported with the reason, never skipped silently. */
#ifndef RT_FORMATS_MODULE_LOADER_H
#define RT_FORMATS_MODULE_LOADER_H

#include <stddef.h>

/* What the search needs to know of one module. */
typedef struct rt_module_spec {
    const char *file;    /* the file name, e.g. "librtcl_image.so" */
    const char *symbol;  /* its one exported entry point */
    const char *what;    /* its name in messages, e.g. "image module" */
    const char *wraps;   /* the library inside it, e.g. "OpenImageIO" */
    const char *without; /* what works without it, e.g. ".ppm and .pfm need no module" */
    int abi;             /* the interface this build expects */
    /* Calls the entry point (dlsym's result, NULL when the symbol is
     * missing) and returns the module's table when it is this build's
     * interface, else NULL with *abi the interface it reports (0: none). */
    const void *(*open_table)(void *entry, int *abi);
} rt_module_spec;

/* Finds and loads spec's module by the rules above. Returns its table (the
 * module stays loaded for the life of the process: tables and documents it
 * made may be in use), or NULL with the reason, one sentence, in reason. */
const void *rt_module_load(const rt_module_spec *spec, char *reason, size_t cap);

#endif

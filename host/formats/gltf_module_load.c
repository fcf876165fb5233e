/* SPDX-License-Identifier: Apache-2.0 */
/* gltf_module_load.c - finding and loading the glTF module (gltf_module.h)
 * by module_loader.h's rules. */
#include "formats/gltf_module.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "formats/module_loader.h"

static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const rt_gltf_module *module_table;
static char module_reason[768];

#ifdef RT_HAVE_GLTF_MODULE
static const void *open_table(void *symbol, int *abi) {
    rt_gltf_module_entry entry = NULL;
    memcpy(&entry, &symbol, sizeof entry); /* object to function pointer, as POSIX allows */
    const rt_gltf_module *table = entry ? entry() : NULL;
    *abi = table ? table->abi : 0;
    if (!table || table->abi != RT_GLTF_MODULE_ABI || table->doc_size != sizeof(rt_gltf_doc) ||
        table->error_size != sizeof(rt_error) || !table->read || !table->free_doc)
        return NULL;
    return table;
}

static void load_module(void) {
    static const rt_module_spec spec = {RT_GLTF_MODULE_FILE,
                                        RT_GLTF_MODULE_SYMBOL,
                                        "glTF module",
                                        "tinygltf",
                                        ".obj and .json scenes need no module",
                                        RT_GLTF_MODULE_ABI,
                                        open_table};
    /* never closed: documents it made may still be freed */
    module_table = rt_module_load(&spec, module_reason, sizeof module_reason);
}
#else
static void load_module(void) {
    snprintf(module_reason, sizeof module_reason,
             "this build has no glTF support: tinygltf was not found when it was configured "
             "(install libtinygltf-dev nlohmann-json3-dev libstb-dev and configure again); .obj "
             "and .json scenes load without it");
}
#endif

const rt_gltf_module *rt_gltf_module_get(rt_error *err) {
    pthread_once(&module_once, load_module);
    if (!module_table) rt_fail(err, RT_ERROR_UNSUPPORTED, "%s", module_reason);
    return module_table;
}

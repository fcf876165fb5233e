/* SPDX-License-Identifier: Apache-2.0 */
/* image_load.c - finding and loading the image module (image_module.h) by
 * module_loader.h's rules. */
#include "formats/image_module.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "formats/module_loader.h"

static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const rt_image_module *module_table;
static char module_reason[768];

#ifdef RT_HAVE_IMAGE_MODULE
static const void *open_table(void *symbol, int *abi) {
    rt_image_module_entry entry = NULL;
    memcpy(&entry, &symbol, sizeof entry); /* object to function pointer, as POSIX allows */
    const rt_image_module *table = entry ? entry() : NULL;
    *abi = table ? table->abi : 0;
    if (!table || table->abi != RT_IMAGE_MODULE_ABI || table->image_size != sizeof(rt_image) ||
        table->error_size != sizeof(rt_error) || !table->read || !table->encode)
        return NULL;
    return table;
}

static void load_module(void) {
    static const rt_module_spec spec = {
        RT_IMAGE_MODULE_FILE,           RT_IMAGE_MODULE_SYMBOL, "image module", "OpenImageIO",
        ".ppm and .pfm need no module", RT_IMAGE_MODULE_ABI,    open_table};
    /* never closed: OpenImageIO keeps global state */
    module_table = rt_module_load(&spec, module_reason, sizeof module_reason);
}
#else
static void load_module(void) {
    snprintf(module_reason, sizeof module_reason,
             "this build has no PNG or EXR support: OpenImageIO was not found when it was "
             "configured (install libopenimageio-dev and configure again); .ppm and .pfm work "
             "without it");
}
#endif

const rt_image_module *rt_image_module_get(rt_error *err) {
    pthread_once(&module_once, load_module);
    if (!module_table) rt_fail(err, RT_ERROR_UNSUPPORTED, "%s", module_reason);
    return module_table;
}

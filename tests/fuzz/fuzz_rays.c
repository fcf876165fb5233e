/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_rays.c - libFuzzer harness of the ray-file reader of `rtcl trace`
 * (formats/ray_file.c). The first byte's low bit selects the 11-number form
 * (--offset-origins); the rest is the file's text. A parse must end (no
 * hang), give at most one ray per line, and name the file and line when it
 * fails. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "formats/ray_file.h"
#include "fuzz_util.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size == 0) return 0;
    const int with_normals = data[0] & 1;
    const size_t len = size - 1;
    /* The reader's contract: text[len] is '\0', as rt_read_file leaves it. */
    char *text = malloc(len + 1);
    if (!text) abort();
    memcpy(text, data + 1, len);
    text[len] = '\0';
    size_t lines = 1;
    for (size_t i = 0; i < len; i++) lines += text[i] == '\n';

    rt_ray *rays = NULL;
    size_t count = 0;
    rt_error err;
    rt_error_clear(&err);
    rt_status st = rt_rays_parse(text, len, "fuzz.rays", with_normals, &rays, &count, &err);
    if (st == RT_OK) {
        fuzz_check(count <= lines, "more rays than lines");
        fuzz_check((count == 0) == (rays == NULL), "rays and count disagree");
        volatile float sink = 0.0f; /* every ray is read (ASan checks the array) */
        for (size_t i = 0; i < count; i++) sink += rays[i].tmax;
        (void)sink;
    } else {
        fuzz_check(rays == NULL && count == 0, "a failed parse returned rays");
        fuzz_check(strncmp(err.message, "fuzz.rays:", 10) == 0, "an error that names no file");
        fuzz_check(st == RT_ERROR_PARSE || st == RT_ERROR_OUT_OF_MEMORY, "an unexpected status");
        fuzz_check(st != RT_ERROR_PARSE || err.line >= 1, "a parse error without a line");
    }
    free(rays);
    free(text);
    return 0;
}

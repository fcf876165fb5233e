/* SPDX-License-Identifier: Apache-2.0 */
/* name_table.c - see name_table.h. */
#include "formats/name_table.h"

#include <stdlib.h>
#include <string.h>

/* FNV-1a over bytes. */
static uint64_t hash_bytes(const char *p, size_t len) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) h = (h ^ (unsigned char)p[i]) * 1099511628211ull;
    return h;
}

/* The slot where name is, or the empty one where it would go. */
static size_t slot_of(const rt_name_table *t, const char *name, size_t len) {
    const size_t mask = t->slot_count - 1;
    for (size_t i = (size_t)hash_bytes(name, len) & mask;; i = (i + 1) & mask) {
        const uint32_t id = t->slots[i];
        if (id == RT_NO_NAME || (t->sizes[id] == len && memcmp(t->names[id], name, len) == 0))
            return i;
    }
}

uint32_t rt_name_find(const rt_name_table *t, const char *name, size_t len) {
    if (!t->slot_count) return RT_NO_NAME;
    return t->slots[slot_of(t, name, len)];
}

/* Room for one more id: the arrays and a table kept at most half full. */
static int make_room(rt_name_table *t) {
    if (t->count == t->capacity) {
        uint32_t cap = t->capacity ? 2 * t->capacity : 16;
        if (cap < t->capacity) return 0;
        char **names = realloc(t->names, (size_t)cap * sizeof *names);
        if (!names) return 0;
        t->names = names;
        size_t *sizes = realloc(t->sizes, (size_t)cap * sizeof *sizes);
        if (!sizes) return 0;
        t->sizes = sizes;
        t->capacity = cap;
    }
    if (2 * ((size_t)t->count + 1) <= t->slot_count) return 1;
    size_t n = t->slot_count ? 2 * t->slot_count : 32;
    uint32_t *slots = malloc(n * sizeof *slots);
    if (!slots) return 0;
    for (size_t i = 0; i < n; i++) slots[i] = RT_NO_NAME;
    free(t->slots);
    t->slots = slots;
    t->slot_count = n;
    for (uint32_t id = 0; id < t->count; id++)
        t->slots[slot_of(t, t->names[id], t->sizes[id])] = id;
    return 1;
}

uint32_t rt_name_add(rt_name_table *t, const char *name, size_t len, int *added) {
    *added = 0;
    uint32_t id = rt_name_find(t, name, len);
    if (id != RT_NO_NAME) return id;
    if (t->count == RT_NO_NAME - 1 || !make_room(t)) return RT_NO_NAME;
    char *copy = malloc(len + 1);
    if (!copy) return RT_NO_NAME;
    memcpy(copy, name, len);
    copy[len] = '\0';
    id = t->count++;
    t->names[id] = copy;
    t->sizes[id] = len;
    t->slots[slot_of(t, name, len)] = id;
    *added = 1;
    return id;
}

void rt_name_table_free(rt_name_table *t) {
    for (uint32_t i = 0; i < t->count; i++) free(t->names[i]);
    free(t->names);
    free(t->sizes);
    free(t->slots);
    memset(t, 0, sizeof *t);
}

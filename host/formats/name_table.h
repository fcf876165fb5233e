/* SPDX-License-Identifier: Apache-2.0 */
/* name_table.h - names (byte strings of any length) to dense ids 0, 1, 2...
 * in order of first sight, with O(1) lookups: the material names of MTL
 * files and the usemtl names of an OBJ file. Names are kept whole: two
 * names that differ anywhere are two ids. */
#ifndef RT_NAME_TABLE_H
#define RT_NAME_TABLE_H

#include <stddef.h>
#include <stdint.h>

#define RT_NO_NAME UINT32_MAX

typedef struct rt_name_table {
    char **names;  /* by id, NUL-terminated copies */
    size_t *sizes; /* by id, their lengths */
    uint32_t count, capacity;
    uint32_t *slots; /* open addressing: ids or RT_NO_NAME, at most half full */
    size_t slot_count;
} rt_name_table;

/* The id of the len bytes at name, or RT_NO_NAME. A zeroed table is empty. */
uint32_t rt_name_find(const rt_name_table *table, const char *name, size_t len);

/* The id of name, added as the next id when new (*added set to 1, else 0);
 * RT_NO_NAME when out of memory (the table is unchanged). */
uint32_t rt_name_add(rt_name_table *table, const char *name, size_t len, int *added);

void rt_name_table_free(rt_name_table *table);

#endif /* RT_NAME_TABLE_H */

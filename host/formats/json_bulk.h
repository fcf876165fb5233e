/* SPDX-License-Identifier: Apache-2.0 */
/* json_bulk.h - the big number arrays of a JSON scene (inline meshes'
 * "positions", "normals" and "triangles") read straight from the text,
 * without a JSON value per number.
 *
 * jansson builds a value of about 50 bytes per number, so a 61 MB inline
 * mesh took 770 MB. Before jansson parses the scene, rt_json_bulk_scan finds
 * every value of those keys that is an array of valid JSON numbers (by
 * jansson's own grammar, none beyond its ranges) of at least
 * RT_JSON_BULK_MIN_BYTES of text; jansson then reads the text through
 * rt_json_bulk_read, which hands it each such array as the placeholder
 * [{"":OFFSET}] (OFFSET: the array's place in the text), padded with blanks
 * to the array's length, so that every other position in the text is
 * unchanged. The loader, finding a placeholder, takes the entry of that
 * offset (each once) and parses the numbers from the text itself. A
 * placeholder written in a scene file by hand names no entry, or one taken
 * already, and is an error like any other wrong value. */
#ifndef RT_JSON_BULK_H
#define RT_JSON_BULK_H

#include <stddef.h>
#include <stdint.h>

/* Arrays shorter than this stay with jansson (the placeholder must fit). */
#define RT_JSON_BULK_MIN_BYTES 64

typedef struct rt_json_bulk {
    size_t start, end; /* the array's '[' and one past its ']' */
    size_t count;      /* numbers in it */
    int taken;         /* handed to the loader already */
} rt_json_bulk;

typedef struct rt_json_bulk_table {
    rt_json_bulk *arrays; /* in text order */
    size_t count, capacity;
} rt_json_bulk_table;

/* Finds the bulk arrays of text (len bytes). 0 when out of memory (then the
 * table is empty and the text goes to jansson as it is). */
int rt_json_bulk_scan(const char *text, size_t len, rt_json_bulk_table *table);

/* The entry whose array starts at offset, or NULL. */
rt_json_bulk *rt_json_bulk_at(rt_json_bulk_table *table, size_t offset);

void rt_json_bulk_free(rt_json_bulk_table *table);

/* A reader of the text for json_load_callback: the text with each bulk
 * array replaced by its placeholder. */
typedef struct rt_json_bulk_reader {
    const char *text;
    size_t len, pos;
    const rt_json_bulk_table *table;
    size_t next; /* the first array not wholly before pos */
} rt_json_bulk_reader;

/* json_load_callback_t: up to size bytes of the text from reader->pos into
 * buffer; 0 at the end. */
size_t rt_json_bulk_read(void *buffer, size_t size, void *reader);

/* One number of a bulk array at text[*pos] (after blanks), the array's
 * next element: 1 and its kind (integer: no '.', 'e' or 'E') and value, the
 * integer's exactly, as jansson reads them; *pos moves past it and the
 * comma after it. 0 at the array's end. */
int rt_json_bulk_next(const char *text, size_t end, size_t *pos, size_t *at, int *integer,
                      long long *ivalue, double *rvalue);

#endif /* RT_JSON_BULK_H */

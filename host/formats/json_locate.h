/* SPDX-License-Identifier: Apache-2.0 */
/* json_locate.h - where a value sits in JSON text, for error messages.
 *
 * JSON libraries such as jansson keep no source positions in the values they
 * build, yet an error about a value (a wrong type, a name that does not
 * exist) should point at that value. Errors are rare and stop a load, so
 * rather than indexing every value up front these functions scan the text
 * once, on demand, following a path of keys and array indices.
 *
 * Lines and columns are 1-based; a column counts characters (UTF-8 code
 * points), as jansson does. The text is expected to be valid JSON (it has
 * been parsed already); on anything else the scan stops safely and reports
 * that the path was not found. Dependency-free: part of the core.
 */
#ifndef RT_JSON_LOCATE_H
#define RT_JSON_LOCATE_H

#include <stddef.h>

/* One step of a path: a member of an object (key != NULL) or an element of
 * an array (key == NULL, index). */
typedef struct rt_json_step {
    const char *key; /* UTF-8, as decoded (escapes resolved) */
    size_t index;
} rt_json_step;

/* Line and column of byte offset in text (an offset past the end counts as
 * the end). */
void rt_json_offset_position(const char *text, size_t len, size_t offset, int *line, int *column);

/* Finds the value at path (depth steps; depth 0 is the whole document).
 * With want_key, and a last step that is an object member, gives the
 * position of the member's key instead of its value. Returns 1 and sets
 * line/column, or 0 when the path is not in the text. */
int rt_json_locate(const char *text, size_t len, const rt_json_step *path, size_t depth,
                   int want_key, int *line, int *column);

/* The same with the path written as text, e.g. "objects[2].material" or ""
 * for the root. Keys in such a path cannot contain '.' or '['. */
int rt_json_locate_path(const char *text, size_t len, const char *path, int want_key, int *line,
                        int *column);

#endif /* RT_JSON_LOCATE_H */

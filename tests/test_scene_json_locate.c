/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_json_locate.c - positions of JSON values by path (json_locate.h),
 * which the JSON scene loader uses for its error messages. */
#include <string.h>

#include "check.h"
#include "formats/json_locate.h"

static const char *doc = "{\n"
                         "  \"a\": {\"b\": [10, [20, 21], {\"c\": true}]},\n"
                         "  \"caf\\u00e9\": \"x\", \"s\": \"q\\\"{[,\",\n"
                         "  \"\\ud83d\\ude00\": null,\r\n"
                         "  \"\xc3\xa9t\xc3\xa9\": 5, \"last\": [ ]\n"
                         "}";

/* Checks that path is found at line:column. */
static void at(const char *path, int want_key, int line, int column) {
    int l = -1, c = -1;
    int found = rt_json_locate_path(doc, strlen(doc), path, want_key, &l, &c);
    CHECK_MSG(found && l == line && c == column, "%s%s: found %d at %d:%d, expected %d:%d", path,
              want_key ? " (key)" : "", found, l, c, line, column);
}

static void absent(const char *path) {
    int l, c;
    CHECK_MSG(!rt_json_locate_path(doc, strlen(doc), path, 0, &l, &c), "%s was found", path);
}

int main(void) {
    at("", 0, 1, 1);
    at("a", 0, 2, 8);
    at("a", 1, 2, 3);
    at("a.b", 0, 2, 14);
    at("a.b[0]", 0, 2, 15);
    at("a.b[1]", 0, 2, 19);
    at("a.b[1][1]", 0, 2, 24);
    at("a.b[2].c", 0, 2, 35);
    at("a.b[2].c", 1, 2, 30);
    at("caf\xc3\xa9", 1, 3, 3);        /* an escaped key matches its decoded text */
    at("s", 0, 3, 26);                 /* after a string with escapes and brackets */
    at("\xf0\x9f\x98\x80", 0, 4, 19);  /* a surrogate pair */
    at("\xc3\xa9t\xc3\xa9", 0, 5, 10); /* columns count characters, not bytes */
    at("last", 0, 5, 21);
    absent("missing");
    absent("a.b[3]");
    absent("a[0]");     /* an object is not an array */
    absent("a.b.c");    /* nor the other way round */
    absent("last[0]");  /* an empty array */
    absent("a.b[0].x"); /* a number has no members */

    /* Broken text is scanned safely and reports nothing. */
    const char *broken[] = {"{\"a\": [1, 2", "{\"a\" 1}", "{\"a\": \"unterminated", "[", "",
                            "{\"x\\"};
    for (size_t i = 0; i < sizeof broken / sizeof broken[0]; i++) {
        int l, c;
        CHECK(!rt_json_locate_path(broken[i], strlen(broken[i]), "a[5]", 0, &l, &c));
    }

    int l, c;
    rt_json_offset_position("ab\ncd", 5, 4, &l, &c);
    CHECK(l == 2 && c == 2);
    rt_json_offset_position("ab", 2, 99, &l, &c); /* past the end: the end */
    CHECK(l == 1 && c == 3);
    return TEST_END();
}

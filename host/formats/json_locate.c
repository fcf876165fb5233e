/* SPDX-License-Identifier: Apache-2.0 */
/* json_locate.c - positions of JSON values by path, found by scanning the text. */
#include "formats/json_locate.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A read position in the text; every access checks against len. */
typedef struct scanner {
    const char *text;
    size_t len;
    size_t pos;
} scanner;

static int at_end(const scanner *s) {
    return s->pos >= s->len;
}

static char peek(const scanner *s) {
    return at_end(s) ? '\0' : s->text[s->pos];
}

static void skip_space(scanner *s) {
    while (!at_end(s)) {
        char c = s->text[s->pos];
        if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
        s->pos++;
    }
}

void rt_json_offset_position(const char *text, size_t len, size_t offset, int *line, int *column) {
    int l = 1, c = 1;
    if (offset > len) offset = len;
    for (size_t i = 0; i < offset; i++) {
        unsigned char b = (unsigned char)text[i];
        if (b == '\n') {
            l++;
            c = 1;
        } else if ((b & 0xC0) != 0x80) {
            c++; /* continuation bytes belong to the character before */
        }
    }
    *line = l;
    *column = c;
}

static int hex4(scanner *s, uint32_t *out) {
    if (s->len - s->pos < 4) return 0;
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) {
        char c = s->text[s->pos++];
        v <<= 4;
        if (c >= '0' && c <= '9')
            v |= (uint32_t)(c - '0');
        else if (c >= 'a' && c <= 'f')
            v |= (uint32_t)(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F')
            v |= (uint32_t)(c - 'A' + 10);
        else
            return 0;
    }
    *out = v;
    return 1;
}

static size_t utf8_encode(uint32_t cp, char out[4]) {
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6));
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12));
        out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18));
    out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* Reads the string at the scanner (which is on its opening quote) and
 * compares its decoded text with key (NULL: just skip it). Returns 1 when
 * equal, 0 when not, -1 when the text is malformed. */
static int read_string(scanner *s, const char *key) {
    if (peek(s) != '"') return -1;
    s->pos++;
    size_t k = 0;
    int same = key != NULL;
    while (!at_end(s)) {
        char c = s->text[s->pos++];
        char bytes[4];
        size_t n = 1;
        bytes[0] = c;
        if (c == '"') return same && key[k] == '\0';
        if (c == '\\') {
            if (at_end(s)) return -1;
            char e = s->text[s->pos++];
            /* The one-letter escapes and what they stand for. */
            static const char letters[] = "bfnrt", meant[] = "\b\f\n\r\t";
            const char *letter = e ? strchr(letters, e) : NULL;
            if (letter) {
                bytes[0] = meant[letter - letters];
            } else if (e == 'u') {
                uint32_t cp, low;
                if (!hex4(s, &cp)) return -1;
                /* A surrogate pair spells one character beyond U+FFFF. */
                if (cp >= 0xD800 && cp <= 0xDBFF && s->len - s->pos >= 6 &&
                    s->text[s->pos] == '\\' && s->text[s->pos + 1] == 'u') {
                    size_t save = s->pos;
                    s->pos += 2;
                    if (hex4(s, &low) && low >= 0xDC00 && low <= 0xDFFF)
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
                    else
                        s->pos = save;
                }
                n = utf8_encode(cp, bytes);
            } else {
                bytes[0] = e; /* \" \\ \/ */
            }
        }
        if (same) {
            for (size_t i = 0; i < n && same; i++) {
                if (key[k] == '\0' || key[k] != bytes[i])
                    same = 0;
                else
                    k++;
            }
        }
    }
    return -1;
}

/* Moves past one value of any kind. Nesting is counted, not recursed, so a
 * deep document cannot exhaust the stack. Returns 0 on malformed text. */
static int skip_value(scanner *s) {
    size_t depth = 0;
    do {
        skip_space(s);
        char c = peek(s);
        if (c == '"') {
            if (read_string(s, NULL) < 0) return 0;
        } else if (c == '{' || c == '[') {
            depth++;
            s->pos++;
        } else if (c == '}' || c == ']') {
            if (depth == 0) return 0;
            depth--;
            s->pos++;
        } else if (c == ',' || c == ':') {
            if (depth == 0) return 0;
            s->pos++;
        } else if (c == '\0' && at_end(s)) {
            return 0;
        } else {
            /* A number, true, false or null: up to the next delimiter. */
            size_t start = s->pos;
            while (!at_end(s) && !strchr(",:]} \t\r\n", s->text[s->pos])) s->pos++;
            if (s->pos == start) return 0;
        }
    } while (depth > 0);
    return 1;
}

/* Moves from the opening '{' to the value of member key; with key_pos, also
 * the offset of the key. Returns 0 when the object has no such member. */
static int find_member(scanner *s, const char *key, size_t *key_pos) {
    s->pos++; /* '{' */
    for (;;) {
        skip_space(s);
        if (peek(s) != '"') return 0; /* '}' or malformed */
        size_t start = s->pos;
        int same = read_string(s, key);
        if (same < 0) return 0;
        skip_space(s);
        if (peek(s) != ':') return 0;
        s->pos++;
        skip_space(s);
        if (same) {
            *key_pos = start;
            return 1;
        }
        if (!skip_value(s)) return 0;
        skip_space(s);
        if (peek(s) != ',') return 0;
        s->pos++;
    }
}

/* Moves from the opening '[' to element index. */
static int find_element(scanner *s, size_t index) {
    s->pos++; /* '[' */
    for (size_t i = 0;; i++) {
        skip_space(s);
        if (peek(s) == ']' || at_end(s)) return 0;
        if (i == index) return 1;
        if (!skip_value(s)) return 0;
        skip_space(s);
        if (peek(s) != ',') return 0;
        s->pos++;
    }
}

int rt_json_locate(const char *text, size_t len, const rt_json_step *path, size_t depth,
                   int want_key, int *line, int *column) {
    if (!text) return 0;
    scanner s = {text, len, 0};
    skip_space(&s);
    size_t target = s.pos;
    for (size_t i = 0; i < depth; i++) {
        char c = peek(&s);
        size_t key_pos = 0;
        if (path[i].key) {
            if (c != '{' || !find_member(&s, path[i].key, &key_pos)) return 0;
        } else {
            if (c != '[' || !find_element(&s, path[i].index)) return 0;
        }
        target = (want_key && path[i].key && i + 1 == depth) ? key_pos : s.pos;
    }
    rt_json_offset_position(text, len, target, line, column);
    return 1;
}

int rt_json_locate_path(const char *text, size_t len, const char *path, int want_key, int *line,
                        int *column) {
    /* Split the path into steps, keys copied into one buffer. */
    size_t plen = strlen(path);
    char *keys = malloc(plen + 1);
    rt_json_step *steps = malloc((plen + 1) * sizeof *steps);
    size_t depth = 0, k = 0;
    int ok = keys && steps;
    const char *p = path;
    while (ok && *p) {
        if (*p == '[') {
            char *end;
            unsigned long long index = strtoull(p + 1, &end, 10);
            if (end == p + 1 || *end != ']') ok = 0;
            steps[depth].key = NULL;
            steps[depth++].index = (size_t)index;
            p = ok ? end + 1 : p;
        } else {
            if (*p == '.') p++;
            steps[depth].key = keys + k;
            steps[depth++].index = 0;
            while (*p && *p != '.' && *p != '[') keys[k++] = *p++;
            keys[k++] = '\0';
        }
    }
    if (ok) ok = rt_json_locate(text, len, steps, depth, want_key, line, column);
    free(keys);
    free(steps);
    return ok;
}

// SPDX-License-Identifier: Apache-2.0
/* kernel_cache.c - see kernel_cache.h. */
#define _POSIX_C_SOURCE 200809L
#include "base/kernel_cache.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/atomic_file.h"

#define FNV_PRIME 0x100000001b3ull
#define FNV_BASIS 0xcbf29ce484222325ull
/* The second lane's basis: FNV-1a's basis of another string, so the lanes
 * start apart. */
#define FNV_BASIS_B  0x84222325cbf29ce4ull
#define HEADER_BYTES 48
static const char magic[8] = {'r', 't', 'c', 'l', 'k', 'c', '1', '\n'};

void rt_kc_key_init(rt_kc_key *k) {
    k->a = FNV_BASIS;
    k->b = FNV_BASIS_B;
    k->len = 0;
}

static void add_bytes(rt_kc_key *k, const unsigned char *p, size_t n) {
    uint64_t a = k->a, b = k->b;
    for (size_t i = 0; i < n; i++) {
        a = (a ^ p[i]) * FNV_PRIME;
        b = (b ^ (unsigned char)~p[i]) * FNV_PRIME;
    }
    k->a = a;
    k->b = b;
    k->len += n;
}

void rt_kc_key_add(rt_kc_key *k, const void *data, size_t n) {
    unsigned char len[8];
    for (int i = 0; i < 8; i++) len[i] = (unsigned char)((uint64_t)n >> (8 * i));
    add_bytes(k, len, 8);
    add_bytes(k, data, n);
}

void rt_kc_key_add_str(rt_kc_key *k, const char *s) {
    if (!s) s = "";
    rt_kc_key_add(k, s, strlen(s));
}

/* FNV-1a 64 of a payload (its checksum in the header). */
static uint64_t checksum(const void *data, size_t n) {
    rt_kc_key k;
    rt_kc_key_init(&k);
    add_bytes(&k, data, n);
    return k.a;
}

/* Creates path and its missing parents (mode 0700). 1 when it is a
 * writable folder afterwards. */
static int make_folder(char *path) {
    struct stat st;
    if (stat(path, &st) == 0) return S_ISDIR(st.st_mode) && access(path, W_OK | X_OK) == 0;
    for (char *p = path + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        int bad = mkdir(path, 0700) != 0 && errno != EEXIST;
        *p = '/';
        if (bad) return 0;
    }
    if (mkdir(path, 0700) != 0 && errno != EEXIST) return 0;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode) && access(path, W_OK | X_OK) == 0;
}

static int is_off(const char *v) {
    return !v[0] || !strcasecmp(v, "off") || !strcmp(v, "0") || !strcasecmp(v, "none");
}

int rt_kc_folder(char *dir, size_t cap) {
    const char *own = getenv("RTCL_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    int n;
    dir[0] = '\0';
    if (own) {
        if (is_off(own)) return 0;
        n = snprintf(dir, cap, "%s", own);
    } else if (xdg && xdg[0] == '/') {
        n = snprintf(dir, cap, "%s/rtcl", xdg);
    } else if (home && home[0]) {
        n = snprintf(dir, cap, "%s/.cache/rtcl", home);
    } else {
        return 0;
    }
    /* A name too long for entries to fit beside it is unusable. */
    if (n < 0 || (size_t)n + 40 >= cap) {
        dir[0] = '\0';
        return 0;
    }
    while (n > 1 && dir[n - 1] == '/') dir[--n] = '\0';
    if (!make_folder(dir)) {
        dir[0] = '\0';
        return 0;
    }
    return 1;
}

static void entry_path(char *path, size_t cap, const char *dir, const char *kind,
                       const rt_kc_key *key) {
    snprintf(path, cap, "%s/%s-%016llx.bin", dir, kind, (unsigned long long)key->a);
}

static void put64(unsigned char *p, uint64_t v) {
    for (int i = 0; i < 8; i++) p[i] = (unsigned char)(v >> (8 * i));
}

static void header(unsigned char h[HEADER_BYTES], const rt_kc_key *key, const void *data,
                   size_t size) {
    memcpy(h, magic, 8);
    put64(h + 8, key->a);
    put64(h + 16, key->b);
    put64(h + 24, key->len);
    put64(h + 32, size);
    put64(h + 40, checksum(data, size));
}

/* The whole file at path, new (NULL: unreadable or over 1 GiB). */
static unsigned char *read_all(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *buf = NULL;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    if (n >= 0 && n <= (1l << 30) && fseek(f, 0, SEEK_SET) == 0) buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *size = buf ? (size_t)n : 0;
    return buf;
}

void *rt_kc_load(const char *dir, const char *kind, const rt_kc_key *key, size_t *size) {
    *size = 0;
    if (!dir || !dir[0]) return NULL;
    char path[4096 + 64];
    entry_path(path, sizeof path, dir, kind, key);
    size_t n;
    unsigned char *file = read_all(path, &n);
    if (!file) return NULL; /* none (or unreadable: nothing to repair) */
    size_t body = n >= HEADER_BYTES ? n - HEADER_BYTES : 0;
    unsigned char want[HEADER_BYTES];
    if (n >= HEADER_BYTES) header(want, key, file + HEADER_BYTES, body);
    if (n < HEADER_BYTES || memcmp(file, want, HEADER_BYTES) != 0) {
        free(file);
        remove(path); /* damaged, or another key with the same first hash */
        return NULL;
    }
    memmove(file, file + HEADER_BYTES, body);
    *size = body;
    return file;
}

void rt_kc_save(const char *dir, const char *kind, const rt_kc_key *key, const void *data,
                size_t size) {
    if (!dir || !dir[0] || !data || !size) return;
    char path[4096 + 64];
    entry_path(path, sizeof path, dir, kind, key);
    unsigned char h[HEADER_BYTES];
    header(h, key, data, size);
    rt_atomic_file f;
    rt_error err;
    if (rt_atomic_file_open(&f, path, "kernel cache entry", &err) != RT_OK) return;
    if (fwrite(h, 1, sizeof h, f.stream) != sizeof h || fwrite(data, 1, size, f.stream) != size) {
        rt_atomic_file_discard(&f);
        return;
    }
    rt_atomic_file_commit(&f, &err);
}

void rt_kc_remove(const char *dir, const char *kind, const rt_kc_key *key) {
    if (!dir || !dir[0]) return;
    char path[4096 + 64];
    entry_path(path, sizeof path, dir, kind, key);
    remove(path);
}

// SPDX-License-Identifier: Apache-2.0
/* test_core_kernel_cache.c - base/kernel_cache.h: keys delimit their fields
 * and differ in each; the folder rules (RTCL_CACHE_DIR, the off words,
 * XDG_CACHE_HOME/rtcl only when absolute, HOME/.cache/rtcl, a folder that
 * cannot be made); an entry saved is loaded back whole, under its key only;
 * a truncated, a flipped-byte and a foreign-key entry are misses and are
 * deleted; the save leaves no temporary behind. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/kernel_cache.h"
#include "check.h"

static char base[256];

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static int files_in(const char *dir) {
    DIR *d = opendir(dir);
    int n = 0;
    if (!d) return -1;
    for (struct dirent *e; (e = readdir(d));) n += e->d_name[0] != '.' || strlen(e->d_name) > 2;
    closedir(d);
    return n;
}

static rt_kc_key key_of(const char *x, const char *y) {
    rt_kc_key k;
    rt_kc_key_init(&k);
    rt_kc_key_add_str(&k, x);
    rt_kc_key_add_str(&k, y);
    return k;
}

static void test_keys(void) {
    rt_kc_key ab_c = key_of("ab", "c"), a_bc = key_of("a", "bc"), ab_c2 = key_of("ab", "c");
    CHECK(ab_c.a != a_bc.a && ab_c.b != a_bc.b); /* fields are delimited */
    CHECK(ab_c.a == ab_c2.a && ab_c.b == ab_c2.b && ab_c.len == ab_c2.len);
    rt_kc_key other = key_of("ab", "d");
    CHECK(other.a != ab_c.a && other.b != ab_c.b);
    CHECK(ab_c.a != ab_c.b); /* the lanes start apart */
}

static void test_folder(void) {
    char dir[4096], want[1024];
    snprintf(want, sizeof want, "%s/own/deeper", base);
    setenv("RTCL_CACHE_DIR", want, 1);
    CHECK(rt_kc_folder(dir, sizeof dir) == 1 && !strcmp(dir, want) && exists(want));
    const char *off[] = {"off", "OFF", "0", "none", ""};
    for (int i = 0; i < 5; i++) {
        setenv("RTCL_CACHE_DIR", off[i], 1);
        CHECK(rt_kc_folder(dir, sizeof dir) == 0 && dir[0] == '\0');
    }
    snprintf(want, sizeof want, "%s/a_file", base);
    FILE *f = fopen(want, "w");
    if (f) fclose(f);
    snprintf(want, sizeof want, "%s/a_file/sub", base);
    setenv("RTCL_CACHE_DIR", want, 1);
    CHECK(rt_kc_folder(dir, sizeof dir) == 0 && dir[0] == '\0');
    unsetenv("RTCL_CACHE_DIR");
    snprintf(want, sizeof want, "%s/xdg", base);
    setenv("XDG_CACHE_HOME", want, 1);
    CHECK(rt_kc_folder(dir, sizeof dir) == 1);
    snprintf(want, sizeof want, "%s/xdg/rtcl", base);
    CHECK(!strcmp(dir, want));
    setenv("XDG_CACHE_HOME", "relative/xdg", 1); /* not absolute: ignored, as the spec says */
    snprintf(want, sizeof want, "%s/home", base);
    setenv("HOME", want, 1);
    CHECK(rt_kc_folder(dir, sizeof dir) == 1);
    snprintf(want, sizeof want, "%s/home/.cache/rtcl", base);
    CHECK(!strcmp(dir, want) && !exists("relative/xdg"));
    unsetenv("XDG_CACHE_HOME");
}

/* The path of the only entry in dir, into path. */
static int only_entry(const char *dir, char *path, size_t cap) {
    DIR *d = opendir(dir);
    int n = 0;
    if (!d) return 0;
    for (struct dirent *e; (e = readdir(d));)
        if (e->d_name[0] != '.') {
            snprintf(path, cap, "%s/%s", dir, e->d_name);
            n++;
        }
    closedir(d);
    return n == 1;
}

static void test_entries(void) {
    char dir[1024], path[2048];
    snprintf(dir, sizeof dir, "%s/entries", base);
    mkdir(dir, 0700);
    rt_kc_key k = key_of("source", "options"), other = key_of("source", "other options");
    unsigned char data[1000];
    for (int i = 0; i < 1000; i++) data[i] = (unsigned char)(i * 31 + 7);
    size_t size = 0;
    CHECK(rt_kc_load(dir, "cl", &k, &size) == NULL && size == 0); /* none yet */
    rt_kc_save(dir, "cl", &k, data, sizeof data);
    CHECK(files_in(dir) == 1 && only_entry(dir, path, sizeof path));
    unsigned char *back = rt_kc_load(dir, "cl", &k, &size);
    CHECK(back && size == sizeof data && !memcmp(back, data, size));
    free(back);
    CHECK(rt_kc_load(dir, "vk", &k, &size) == NULL);     /* another kind */
    CHECK(rt_kc_load(dir, "cl", &other, &size) == NULL); /* another key */
    CHECK(exists(path));                                 /* ... is not this entry's file */

    /* Damage: a flipped payload byte, a truncation, another key's header. */
    for (int damage = 0; damage < 3; damage++) {
        rt_kc_save(dir, "cl", &k, data, sizeof data);
        FILE *f = fopen(path, "r+b");
        CHECK(f != NULL);
        if (!f) return;
        if (damage == 0) {
            fseek(f, 48 + 500, SEEK_SET);
            fputc(data[500] ^ 1, f);
        } else if (damage == 1) {
            CHECK(ftruncate(fileno(f), 40) == 0);
        } else {
            fseek(f, 16, SEEK_SET); /* the second hash: a first-hash collision */
            fputc(0x5a, f);
        }
        fclose(f);
        CHECK(rt_kc_load(dir, "cl", &k, &size) == NULL && size == 0);
        CHECK(!exists(path)); /* deleted */
    }
    rt_kc_save(dir, "cl", &k, data, sizeof data);
    rt_kc_remove(dir, "cl", &k);
    CHECK(files_in(dir) == 0);                      /* no temporary left either */
    CHECK(rt_kc_load("", "cl", &k, &size) == NULL); /* the cache off */
    rt_kc_save("", "cl", &k, data, sizeof data);    /* a no-op */
}

int main(void) {
    snprintf(base, sizeof base, "/tmp/rt_kernel_cache_XXXXXX");
    if (!mkdtemp(base)) return 1;
    test_keys();
    test_folder();
    test_entries();
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", base);
    return TEST_END();
}

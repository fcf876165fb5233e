/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_atomic_file.c - base/atomic_file.h: a committed file replaces
 * the target whole; a discarded one leaves it; two open writers of one path
 * have their own temporaries and the last commit wins; a reserved temporary
 * carries the target's extension; long names stay within NAME_MAX; errors
 * name the fault (missing folder, a folder as the target, an unwritable
 * folder); rt_atomic_file_remove_temporaries removes the live temporaries
 * only; nothing is left behind. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "check.h"

static char dir[256];

static const char *in_dir(const char *name) {
    static char paths[4][1024];
    static int slot;
    char *p = paths[slot++ % 4];
    snprintf(p, sizeof paths[0], "%s/%s", dir, name);
    return p;
}

static void put(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* The file's first line (static buffer), "" when unreadable. */
static const char *content(const char *path) {
    static char buf[256];
    buf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f) return buf;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Files in dir (not . and ..). */
static int file_count(void) {
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    if (d) closedir(d);
    return n;
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/rt_atomic_%d", (int)getpid());
    CHECK(mkdir(dir, 0700) == 0);
    rt_error err;
    char target[1024], video[1024], longest[1024];
    snprintf(target, sizeof target, "%s", in_dir("out.txt"));

    /* A new file, then a replacement; permission bits of the old one stay. */
    CHECK_EQ_INT(rt_atomic_file_write(target, "text file", "one\n", 4, &err), RT_OK);
    CHECK(strcmp(content(target), "one\n") == 0);
    chmod(target, 0640);
    CHECK_EQ_INT(rt_atomic_file_write(target, "text file", "two\n", 4, &err), RT_OK);
    CHECK(strcmp(content(target), "two\n") == 0);
    struct stat st;
    CHECK(stat(target, &st) == 0 && (st.st_mode & 07777) == 0640);
    CHECK_EQ_INT(file_count(), 1);

    /* Discarded: the target stays, the temporary goes. */
    rt_atomic_file a, b;
    CHECK_EQ_INT(rt_atomic_file_open(&a, target, "text file", &err), RT_OK);
    fputs("half", a.stream);
    CHECK(a.temp && strstr(a.temp, "/.out.tmp-") &&
          strcmp(a.temp + strlen(a.temp) - 4, ".txt") == 0);
    CHECK_EQ_INT(file_count(), 2);
    rt_atomic_file_discard(&a);
    CHECK(strcmp(content(target), "two\n") == 0);
    CHECK_EQ_INT(file_count(), 1);

    /* Two writers at once: their own temporaries; the last commit wins. */
    CHECK_EQ_INT(rt_atomic_file_open(&a, target, "text file", &err), RT_OK);
    CHECK_EQ_INT(rt_atomic_file_open(&b, target, "text file", &err), RT_OK);
    CHECK(strcmp(a.temp, b.temp) != 0);
    fputs("from a\n", a.stream);
    fputs("from b\n", b.stream);
    CHECK_EQ_INT(rt_atomic_file_commit(&b, &err), RT_OK);
    CHECK(strcmp(content(target), "from b\n") == 0);
    CHECK_EQ_INT(rt_atomic_file_commit(&a, &err), RT_OK);
    CHECK(strcmp(content(target), "from a\n") == 0);
    CHECK_EQ_INT(file_count(), 1);

    /* A reserved temporary for another program, with the extension. */
    snprintf(video, sizeof video, "%s", in_dir("clip.mp4"));
    CHECK_EQ_INT(rt_atomic_file_reserve(&a, video, "video", &err), RT_OK);
    CHECK(a.stream == NULL && a.temp && strcmp(a.temp + strlen(a.temp) - 4, ".mp4") == 0);
    put(a.temp, "frames\n");
    CHECK(access(video, F_OK) != 0);
    CHECK_EQ_INT(rt_atomic_file_commit(&a, &err), RT_OK);
    CHECK(strcmp(content(video), "frames\n") == 0);

    /* What a signal handler calls: every live temporary (written or
     * reserved) goes, the target stays; the files are then discarded, and a
     * zeroed one too, without touching another writer's entry. Slots are
     * reused: more writes than slots, one after another, are all removed. */
    unlink(video);
    CHECK_EQ_INT(rt_atomic_file_open(&a, target, "text file", &err), RT_OK);
    CHECK_EQ_INT(rt_atomic_file_reserve(&b, video, "video", &err), RT_OK);
    fputs("half", a.stream);
    fflush(a.stream);
    CHECK_EQ_INT(file_count(), 3);
    rt_atomic_file_remove_temporaries();
    CHECK(access(a.temp, F_OK) != 0 && access(b.temp, F_OK) != 0);
    CHECK(strcmp(content(target), "from a\n") == 0 && access(video, F_OK) != 0);
    CHECK_EQ_INT(file_count(), 1);
    rt_atomic_file zeroed;
    memset(&zeroed, 0, sizeof zeroed);
    rt_atomic_file_discard(&zeroed);
    rt_atomic_file_discard(&a);
    rt_atomic_file_discard(&b);
    for (int i = 0; i < 2 * RT_ATOMIC_LIVE_SLOTS; i++) {
        CHECK_EQ_INT(rt_atomic_file_open(&a, target, "text file", &err), RT_OK);
        rt_atomic_file_discard(&a);
    }
    CHECK_EQ_INT(rt_atomic_file_open(&a, target, "text file", &err), RT_OK);
    rt_atomic_file_remove_temporaries();
    CHECK(access(a.temp, F_OK) != 0);
    rt_atomic_file_discard(&a);
    CHECK(strcmp(content(target), "from a\n") == 0);
    CHECK_EQ_INT(file_count(), 1);

    /* A name of NAME_MAX bytes still gets a temporary that fits. */
    char name[256];
    memset(name, 'n', 251);
    memcpy(name + 251, ".ppm", 5);
    snprintf(longest, sizeof longest, "%s", in_dir(name));
    CHECK_MSG(rt_atomic_file_write(longest, "image file", "P6\n", 3, &err) == RT_OK, "%s",
              err.message);
    CHECK(strcmp(content(longest), "P6\n") == 0);
    unlink(longest);
    unlink(video);

    /* Errors: each names the fault, and nothing is created. */
    CHECK_EQ_INT(rt_atomic_file_write(in_dir("no/such.txt"), "text file", "x", 1, &err),
                 RT_ERROR_IO);
    CHECK_CONTAINS(err.message, "cannot write the text file: folder ");
    CHECK_CONTAINS(err.message, "No such file or directory");
    CHECK_EQ_INT(rt_atomic_file_check(dir, "text file", &err), RT_ERROR_IO);
    CHECK_CONTAINS(err.message, "it is a folder");
    CHECK_EQ_INT(rt_atomic_file_check(in_dir("out.txt/x"), "text file", &err), RT_ERROR_IO);
    CHECK_CONTAINS(err.message, "is not a folder");
    CHECK_EQ_INT(rt_atomic_file_check("", "text file", &err), RT_ERROR_INVALID_ARGUMENT);
    if (geteuid() != 0) { /* root writes into read-only folders */
        chmod(dir, 0500);
        CHECK_EQ_INT(rt_atomic_file_write(target, "text file", "x", 1, &err), RT_ERROR_IO);
        CHECK_CONTAINS(err.message, "Permission denied");
        chmod(dir, 0700);
    }
    CHECK(strcmp(content(target), "from a\n") == 0);
    CHECK_EQ_INT(file_count(), 1);

    /* /dev/null is written in place, not replaced. */
    CHECK_EQ_INT(rt_atomic_file_write("/dev/null", "text file", "x", 1, &err), RT_OK);
    CHECK(stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode));

    unlink(target);
    rmdir(dir);
    return TEST_END();
}

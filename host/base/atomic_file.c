/* SPDX-License-Identifier: Apache-2.0 */
/* atomic_file.c - see atomic_file.h. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "base/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/error.h"

#ifndef NAME_MAX
#define NAME_MAX 255
#endif

/* Tries of a fresh name before giving up (a clash needs another process
 * with the same process id, counter and 64 random bits). */
#define MAX_NAME_TRIES 64

static atomic_uint name_counter;

/* The temporaries now open, for rt_atomic_file_remove_temporaries, which a
 * signal handler calls: a fixed table (no allocation), each path copied into
 * its slot. A slot is FREE, being FILLED by its writer, or LIVE; the handler
 * unlinks only LIVE ones. A slot is freed after its temporary was renamed
 * or removed, so the handler's unlink of a path just freed fails harmlessly
 * (ENOENT). */
enum { SLOT_FREE, SLOT_FILLED, SLOT_LIVE };
static struct live_slot {
    atomic_int state;
    char path[PATH_MAX];
} live_slots[RT_ATOMIC_LIVE_SLOTS];

/* Enters path in a free slot: 1 + its index, or 0 when the path is too long
 * or every slot is taken (the write goes on; only a signal cannot clean it). */
static int live_add(const char *path) {
    size_t n = strlen(path);
    if (n >= PATH_MAX) return 0;
    for (int i = 0; i < RT_ATOMIC_LIVE_SLOTS; i++) {
        int expected = SLOT_FREE;
        if (atomic_compare_exchange_strong(&live_slots[i].state, &expected, SLOT_FILLED)) {
            memcpy(live_slots[i].path, path, n + 1);
            atomic_store(&live_slots[i].state, SLOT_LIVE);
            return i + 1;
        }
    }
    return 0;
}

/* Frees the slot live_add gave (0: none). */
static void live_remove(int live) {
    if (live > 0) atomic_store(&live_slots[live - 1].state, SLOT_FREE);
}

void rt_atomic_file_remove_temporaries(void) {
    for (int i = 0; i < RT_ATOMIC_LIVE_SLOTS; i++)
        if (atomic_load(&live_slots[i].state) == SLOT_LIVE) unlink(live_slots[i].path);
}

/* The folder part of path ("." for a bare name, "/" for "/x"), new. */
static char *folder_of(const char *path) {
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    char *dir = malloc(n + 1);
    if (!dir) return NULL;
    memcpy(dir, path, n);
    dir[n] = '\0';
    return dir;
}

/* Why the folder of target cannot take a new file, or RT_OK. */
static rt_status check_folder(const char *target, const char *what, rt_error *err) {
    char *dir = folder_of(target);
    if (!dir) return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, target, 0, 0, "out of memory");
    struct stat st;
    rt_status status = RT_OK;
    if (stat(dir, &st) != 0)
        status = rt_error_set(err, RT_ERROR_IO, target, 0, 0, "cannot write the %s: folder %s: %s",
                              what, dir, strerror(errno));
    else if (!S_ISDIR(st.st_mode))
        status = rt_error_set(err, RT_ERROR_IO, target, 0, 0,
                              "cannot write the %s: %s is not a folder", what, dir);
    else if (access(dir, W_OK | X_OK) != 0)
        status = rt_error_set(err, RT_ERROR_IO, target, 0, 0, "cannot write the %s: folder %s: %s",
                              what, dir, strerror(errno));
    free(dir);
    return status;
}

rt_status rt_atomic_file_check(const char *target, const char *what, rt_error *err) {
    if (!target || !target[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no output file name");
    size_t len = strlen(target);
    struct stat st;
    if (target[len - 1] == '/' || (stat(target, &st) == 0 && S_ISDIR(st.st_mode)))
        return rt_error_set(err, RT_ERROR_IO, target, 0, 0,
                            "cannot write the %s: it is a folder, not a file name", what);
    if (stat(target, &st) == 0 && !S_ISREG(st.st_mode))
        return access(target, W_OK) == 0
                   ? RT_OK
                   : rt_error_set(err, RT_ERROR_IO, target, 0, 0, "cannot write the %s: %s", what,
                                  strerror(errno));
    /* A symlink to a file elsewhere: that file's folder counts. */
    char *real = stat(target, &st) == 0 ? realpath(target, NULL) : NULL;
    rt_status status = check_folder(real ? real : target, what, err);
    free(real);
    return status;
}

/* 64 bits for the temporary's name: the system's randomness, or the clock
 * where it is not to be had (O_EXCL still keeps names apart). */
static uint64_t random_bits(void) {
    uint64_t r = 0;
    if (getrandom(&r, sizeof r, GRND_NONBLOCK) == (ssize_t)sizeof r) return r;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (uint64_t)now.tv_nsec * 0x9e3779b97f4a7c15ull ^ (uint64_t)now.tv_sec;
}

/* The temporary's path for target: ".STEM.tmp-PID-N-RANDOM.EXT" in target's
 * folder, the stem shortened so that the name stays within NAME_MAX. */
static char *temp_name(const char *target) {
    const char *slash = strrchr(target, '/');
    const char *base = slash ? slash + 1 : target;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base || strlen(dot) > 32) dot = base + strlen(base);
    size_t dir_len = (size_t)(base - target), stem_len = (size_t)(dot - base);
    char unique[80];
    snprintf(unique, sizeof unique, ".tmp-%ld-%u-%016llx", (long)getpid(),
             atomic_fetch_add(&name_counter, 1u), (unsigned long long)random_bits());
    size_t fixed = 1 + strlen(unique) + strlen(dot);
    if (stem_len + fixed > NAME_MAX) stem_len = NAME_MAX > fixed ? NAME_MAX - fixed : 0;
    size_t size = dir_len + stem_len + fixed + 1;
    char *path = malloc(size);
    if (!path) return NULL;
    snprintf(path, size, "%.*s.%.*s%s%s", (int)dir_len, target, (int)stem_len, base, unique, dot);
    return path;
}

static void release(rt_atomic_file *f) {
    live_remove(f->live);
    free(f->target);
    free(f->temp);
    memset(f, 0, sizeof *f);
}

/* Opens f's temporary (or the in-place target) and gives its descriptor. */
static rt_status open_output(rt_atomic_file *f, const char *target, const char *what, int *fd_out,
                             rt_error *err) {
    memset(f, 0, sizeof *f);
    f->what = what;
    rt_status status = rt_atomic_file_check(target, what, err);
    if (status != RT_OK) return status;
    struct stat st;
    int exists = stat(target, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        /* A device or FIFO: written in place (see the header). */
        int fd = open(target, O_WRONLY | O_CLOEXEC);
        if (fd < 0)
            return rt_error_set(err, RT_ERROR_IO, target, 0, 0, "cannot write the %s: %s", what,
                                strerror(errno));
        f->target = strdup(target);
        if (!f->target) {
            close(fd);
            return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, target, 0, 0, "out of memory");
        }
        *fd_out = fd;
        return RT_OK;
    }
    f->target = exists ? realpath(target, NULL) : strdup(target);
    if (!f->target) {
        int e = errno;
        release(f);
        return rt_error_set(err, e == ENOMEM ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_IO, target, 0, 0,
                            "cannot write the %s: %s", what, strerror(e));
    }
    for (int tries = 0; tries < MAX_NAME_TRIES; tries++) {
        f->temp = temp_name(f->target);
        if (!f->temp) break;
        /* Entered in the table before it exists, so that a signal right
         * after open finds it (an unlink of a name not yet made fails
         * harmlessly); its slot is freed again if open fails. (An existing
         * name, EEXIST, is not expected: pid, counter and random bits.) */
        f->live = live_add(f->temp);
        /* 0666 less the umask, as fopen gives a new file. */
        int fd = open(f->temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            /* An existing target's bits; on failure the default ones stay,
             * which is no reason to fail the write. */
            if (exists && fchmod(fd, st.st_mode & 07777) != 0) errno = 0;
            *fd_out = fd;
            return RT_OK;
        }
        int e = errno;
        live_remove(f->live);
        f->live = 0;
        free(f->temp);
        f->temp = NULL;
        if (e != EEXIST) {
            rt_status st2 = check_folder(f->target, what, err);
            if (st2 == RT_OK)
                st2 = rt_error_set(err, RT_ERROR_IO, target, 0, 0, "cannot write the %s: %s", what,
                                   strerror(e));
            release(f);
            return st2;
        }
    }
    release(f);
    return rt_error_set(err, RT_ERROR_IO, target, 0, 0,
                        "cannot write the %s: no free temporary file name beside it", what);
}

rt_status rt_atomic_file_open(rt_atomic_file *f, const char *target, const char *what,
                              rt_error *err) {
    int fd = -1;
    rt_status status = open_output(f, target, what, &fd, err);
    if (status != RT_OK) return status;
    f->stream = fdopen(fd, "wb");
    if (!f->stream) {
        int e = errno;
        close(fd);
        rt_atomic_file_discard(f);
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, target, 0, 0, "cannot write the %s: %s",
                            what, strerror(e));
    }
    return RT_OK;
}

rt_status rt_atomic_file_reserve(rt_atomic_file *f, const char *target, const char *what,
                                 rt_error *err) {
    int fd = -1;
    rt_status status = open_output(f, target, what, &fd, err);
    if (status != RT_OK) return status;
    close(fd);
    return RT_OK;
}

/* Makes the temporary's content durable before the rename: without it a
 * power loss could leave the new name on an empty file. */
static int sync_path(const char *path) {
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return errno;
    int e = fsync(fd) == 0 || errno == EINVAL || errno == EROFS ? 0 : errno;
    close(fd);
    return e;
}

/* Makes a rename in target's folder durable (the folder's entry), so that a
 * file reported written is still there after a power loss. Best effort: the
 * target is already replaced, so a failure here (a file system that cannot
 * sync folders) is no reason to report the write as failed. */
static void sync_folder(const char *target) {
    char *dir = folder_of(target);
    if (!dir) return;
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        if (fsync(fd) != 0) errno = 0;
        close(fd);
    }
    free(dir);
}

rt_status rt_atomic_file_commit(rt_atomic_file *f, rt_error *err) {
    const char *what = f->what ? f->what : "file";
    int e = 0;
    if (f->stream) {
        if (fflush(f->stream) != 0) e = errno;
        if (!e && ferror(f->stream)) e = EIO;
        /* fsync fails with EINVAL on descriptors that cannot be synced (a
         * pipe or a device written in place): nothing to make durable. */
        if (!e && f->temp && fsync(fileno(f->stream)) != 0 && errno != EINVAL) e = errno;
        if (fclose(f->stream) != 0 && !e) e = errno;
        f->stream = NULL;
    } else if (f->temp) {
        e = sync_path(f->temp);
    }
    if (!e && f->temp && rename(f->temp, f->target) != 0) e = errno;
    if (!e && f->temp) sync_folder(f->target);
    if (e) {
        rt_error_set(err, RT_ERROR_IO, f->target, 0, 0, "cannot write the %s: %s", what,
                     strerror(e));
        rt_atomic_file_discard(f);
        return RT_ERROR_IO;
    }
    release(f);
    return RT_OK;
}

void rt_atomic_file_discard(rt_atomic_file *f) {
    if (!f) return;
    if (f->stream) fclose(f->stream);
    f->stream = NULL;
    if (f->temp) unlink(f->temp);
    release(f);
}

rt_status rt_atomic_file_write(const char *target, const char *what, const void *data, size_t size,
                               rt_error *err) {
    rt_atomic_file f;
    rt_status status = rt_atomic_file_open(&f, target, what, err);
    if (status != RT_OK) return status;
    errno = 0;
    if (size && fwrite(data, 1, size, f.stream) != size) {
        int e = errno ? errno : EIO;
        rt_error_set(err, RT_ERROR_IO, f.target, 0, 0, "cannot write the %s: %s", what,
                     strerror(e));
        rt_atomic_file_discard(&f);
        return RT_ERROR_IO;
    }
    return rt_atomic_file_commit(&f, err);
}

/* ---- rt.h's rt_output: the same for programs on the library ------------- */

struct rt_output {
    rt_atomic_file file;
};

rt_status rt_output_reserve(const char *target, const char *what, rt_output **out, rt_error *err) {
    *out = NULL;
    rt_output *o = calloc(1, sizeof *o);
    if (!o) return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, target, 0, 0, "out of memory");
    rt_status st = rt_atomic_file_reserve(&o->file, target, what ? what : "file", err);
    if (st != RT_OK) {
        free(o);
        return st;
    }
    *out = o;
    return RT_OK;
}

const char *rt_output_path(const rt_output *o) {
    return o->file.temp ? o->file.temp : o->file.target;
}

rt_status rt_output_commit(rt_output *o, rt_error *err) {
    rt_status st = rt_atomic_file_commit(&o->file, err);
    free(o);
    return st;
}

void rt_output_discard(rt_output *o) {
    if (!o) return;
    rt_atomic_file_discard(&o->file);
    free(o);
}

rt_status rt_output_check(const char *target, const char *what, rt_error *err) {
    return rt_atomic_file_check(target, what ? what : "file", err);
}

void rt_output_remove_temporaries(void) {
    rt_atomic_file_remove_temporaries();
}

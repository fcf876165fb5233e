/* SPDX-License-Identifier: Apache-2.0 */
/* file_read.c - see file_read.h. */
#include "base/file_read.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/error.h"

static const char *kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

rt_status rt_open_input(const char *path, const char *what, uint64_t max_bytes, int *fd_out,
                        uint64_t *size_out, rt_error *err) {
    *fd_out = -1;
    *size_out = 0;
    /* O_NONBLOCK: opening a FIFO for reading would wait for a writer. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot open the %s: %s", what,
                            strerror(errno));
    struct stat info;
    if (fstat(fd, &info) != 0) {
        int e = errno;
        close(fd);
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot read the %s: %s", what,
                            strerror(e));
    }
    if (!S_ISREG(info.st_mode)) {
        close(fd);
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0,
                            "cannot read the %s: it is %s, not a regular file", what,
                            kind_of(info.st_mode));
    }
    const uint64_t size = info.st_size > 0 ? (uint64_t)info.st_size : 0;
    if (size > max_bytes || size >= SIZE_MAX) {
        close(fd);
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "the %s is %llu bytes, more than the limit of %llu bytes", what,
                            (unsigned long long)size, (unsigned long long)max_bytes);
    }
    *fd_out = fd;
    *size_out = size;
    return RT_OK;
}

rt_status rt_read_file(const char *path, const char *what, uint64_t max_bytes, char **text,
                       size_t *len, rt_error *err) {
    *text = NULL;
    *len = 0;
    int fd;
    uint64_t size;
    rt_status st = rt_open_input(path, what, max_bytes, &fd, &size, err);
    if (st != RT_OK) return st;
    char *buf = malloc((size_t)size + 1);
    if (!buf) {
        close(fd);
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0,
                            "out of memory reading the %s (%llu bytes)", what,
                            (unsigned long long)size);
    }
    /* A regular file never blocks; read until its size, then make sure it
     * ended there. */
    size_t n = 0;
    int e = 0;
    for (;;) {
        char extra;
        const size_t want = n < size ? (size_t)size - n : 1;
        ssize_t got = read(fd, n < size ? buf + n : &extra, want);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            e = errno;
            break;
        }
        if (got == 0) break;
        if (n >= size) {
            e = -1; /* it grew */
            break;
        }
        n += (size_t)got;
    }
    close(fd);
    if (e != 0 || n != size) {
        free(buf);
        if (e > 0)
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot read the %s: %s", what,
                                strerror(e));
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "the %s changed size while read", what);
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return RT_OK;
}

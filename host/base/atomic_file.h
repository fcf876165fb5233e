/* SPDX-License-Identifier: Apache-2.0 */
/* atomic_file.h - output files written in full or not at all.
 *
 * Every file the library or rtcl writes (images, animation frames, videos,
 * hit files, generated and saved scenes) goes through these calls: the bytes
 * go into a new temporary file in the target's own folder, which is flushed
 * to the disk (fsync) and then renamed over the target. So
 *  - a failed write (a full disk, an i/o error) removes the temporary and
 *    leaves an existing target as it was;
 *  - a process killed while writing leaves the old target intact (and a
 *    stray temporary, see below, unless its signal handler calls
 *    rt_atomic_file_remove_temporaries, as rtcl's does);
 *  - concurrent writers of one path each write their own temporary, and each
 *    rename replaces the whole file: the last rename wins, no file is mixed.
 *
 * The temporary is ".STEM.tmp-UNIQUE.EXT" beside the target "STEM.EXT"
 * (hidden, with the target's extension, so a program that picks a format by
 * the name, such as ffmpeg, picks the right one). UNIQUE joins the process
 * id, a per-process counter and random bits, and the file is created with
 * O_EXCL, so two processes never share one. A writer killed by SIGKILL (or a
 * power loss before the rename) leaves its temporary behind: nothing here
 * removes such files, because a live writer's temporary (another host on a
 * network file system, another PID namespace) cannot be told from a dead
 * one's; they are safe to delete when no rtcl writes to that folder.
 *
 * Rules for the target:
 *  - a symbolic link is followed: the file it names is replaced, the link
 *    stays;
 *  - an existing regular file keeps its permission bits (the new file gets
 *    them; its owner is the writer);
 *  - an existing target that is not a regular file (a character device such
 *    as /dev/null, a FIFO) is written in place, as fopen would, since
 *    renaming over it would replace the device node: such writes are not
 *    atomic;
 *  - a folder is refused. */
#ifndef RT_ATOMIC_FILE_H
#define RT_ATOMIC_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "rt.h"

typedef struct rt_atomic_file {
    FILE *stream;     /* where to write; NULL after rt_atomic_file_reserve */
    char *target;     /* the final path (a followed symlink's file) */
    char *temp;       /* the temporary path; NULL when written in place */
    const char *what; /* the kind of file, for messages ("image file") */
    int live;         /* 1 + its slot in the table of live temporaries; 0: none */
} rt_atomic_file;

/* Opens a temporary for target (see above) and sets f->stream to it. what
 * names the file's kind in messages. On failure nothing is created and err
 * says why, naming target (a missing or read-only folder is named as such).
 * The caller writes to f->stream and then calls rt_atomic_file_commit or
 * rt_atomic_file_discard exactly once. */
rt_status rt_atomic_file_open(rt_atomic_file *f, const char *target, const char *what,
                              rt_error *err);

/* Like rt_atomic_file_open, but for a file another program writes (ffmpeg):
 * the temporary is created empty and closed, f->stream is NULL and f->temp
 * (or, for a target written in place, f->target) is the path to give that
 * program. Commit or discard it the same way. */
rt_status rt_atomic_file_reserve(rt_atomic_file *f, const char *target, const char *what,
                                 rt_error *err);

/* Flushes, fsyncs and closes the stream (any error there, ENOSPC included,
 * is reported), renames the temporary over the target and fsyncs its folder
 * (best effort, so the rename survives a power loss). On failure the
 * temporary is removed, the target is untouched and err says why. f is
 * released either way. */
rt_status rt_atomic_file_commit(rt_atomic_file *f, rt_error *err);

/* Closes and removes the temporary; the target is untouched. f is released.
 * Safe on a zeroed f. */
void rt_atomic_file_discard(rt_atomic_file *f);

/* rt_atomic_file_open, one write of size bytes, rt_atomic_file_commit. */
rt_status rt_atomic_file_write(const char *target, const char *what, const void *data, size_t size,
                               rt_error *err);

/* Whether target can be written, checked before any work is done: its
 * folder exists, is a folder and is writable, and target is not a folder.
 * RT_OK, or RT_ERROR_IO naming the fault (and the folder). Nothing is
 * created. */
rt_status rt_atomic_file_check(const char *target, const char *what, rt_error *err);

/* Removes the temporary of every rt_atomic_file of this process that is
 * open or reserved and not yet committed or discarded; the targets are
 * untouched. Async-signal-safe (it only reads a fixed table and calls
 * unlink), for a program's SIGINT/SIGTERM handler, which then ends the
 * process (rt.h: rt_output_remove_temporaries). At most
 * RT_ATOMIC_LIVE_SLOTS temporaries at once are known (more are written,
 * but such a handler cannot remove them). */
#define RT_ATOMIC_LIVE_SLOTS 64
void rt_atomic_file_remove_temporaries(void);

#endif /* RT_ATOMIC_FILE_H */

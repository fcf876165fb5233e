/* SPDX-License-Identifier: Apache-2.0 */
/* video_out.c - frames into an ffmpeg child process (video_out.h).
 *
 * ffmpeg is started with posix_spawnp and an argument vector (no shell, so
 * no path can inject a command), reads raw rgb24 frames on its stdin and
 * writes its messages into an anonymous temporary file, which is shown only
 * when it fails: a user sees nothing of it on success. */
#include "video_out.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_signals.h"
#include "rt.h"

extern char **environ;

struct cli_video {
    pid_t pid; /* 0 once waited for */
    int in;    /* the write end of ffmpeg's stdin, -1 once closed */
    FILE *log; /* ffmpeg's stderr */
    int width, height;
    unsigned char *frame; /* one frame in rgb24 */
    struct sigaction old_pipe;
    /* ffmpeg writes a temporary beside the target (with its extension, so
     * the container is the same), renamed over it once ffmpeg has succeeded:
     * a failed or killed encode leaves an existing video as it was. */
    rt_output *out;
};

static const char no_ffmpeg[] =
    "writing a video needs ffmpeg, which is not on PATH (Debian: apt-get install ffmpeg); "
    "or write the frames as images with -o DIR/frame_%04d.png";

int cli_is_video_path(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return 0;
    return !strcasecmp(dot, ".mp4") || !strcasecmp(dot, ".mkv") || !strcasecmp(dot, ".webm");
}

int cli_have_ffmpeg(void) {
    /* posix_spawnp's own search: PATH, or the system's default path when it
     * is unset; an empty entry is the current folder. */
    const char *path = getenv("PATH");
    char dflt[256];
    if (!path) {
        size_t n = confstr(_CS_PATH, dflt, sizeof dflt);
        path = n && n <= sizeof dflt ? dflt : "/bin:/usr/bin";
    }
    for (const char *p = path;;) {
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char file[4096];
        if (len + 8 < sizeof file) {
            snprintf(file, sizeof file, "%.*s%sffmpeg", (int)len, len ? p : ".", "/");
            struct stat st;
            if (stat(file, &st) == 0 && S_ISREG(st.st_mode) && access(file, X_OK) == 0) return 1;
        }
        if (!end) return 0;
        p = end + 1;
    }
}

int cli_video_check(const char *path, char *why, size_t cap) {
    rt_error err;
    if (rt_output_check(path, "video", &err) == RT_OK) return 1;
    snprintf(why, cap, "%s", err.message);
    return 0;
}

static void close_on_exec(int fd) {
    int flags = fcntl(fd, F_GETFD);
    if (flags >= 0) fcntl(fd, F_SETFD, flags | FD_CLOEXEC);
}

/* Starts ffmpeg with argv: stdin from in_fd, stdout to out_fd (-1:
 * /dev/null for both), stderr to err_fd; SIGPIPE back to its default in the
 * child (this process ignores it while it writes). 0 or an errno value. */
static int spawn(char *const argv[], int in_fd, int out_fd, int err_fd, pid_t *pid) {
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t attr;
    posix_spawn_file_actions_init(&fa);
    posix_spawnattr_init(&attr);
    sigset_t dflt;
    sigemptyset(&dflt);
    sigaddset(&dflt, SIGPIPE);
    posix_spawnattr_setsigdefault(&attr, &dflt);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
    if (in_fd >= 0)
        posix_spawn_file_actions_adddup2(&fa, in_fd, 0);
    else
        posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    if (out_fd >= 0)
        posix_spawn_file_actions_adddup2(&fa, out_fd, 1);
    else
        posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, err_fd, 2);
    int rc = posix_spawnp(pid, "ffmpeg", &fa, &attr, argv, environ);
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    return rc;
}

/* The encoders this ffmpeg has, from 'ffmpeg -encoders' (one per line: flags,
 * name, description). */
typedef struct encoders {
    int x264, vp9, vp8;
} encoders;

static encoders probe_encoders(void) {
    encoders e = {0, 0, 0};
    FILE *out = tmpfile(), *err = tmpfile();
    if (!out || !err) {
        if (out) fclose(out);
        if (err) fclose(err);
        return e;
    }
    close_on_exec(fileno(out));
    close_on_exec(fileno(err));
    char *argv[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-encoders", NULL};
    pid_t pid;
    if (spawn(argv, -1, fileno(out), fileno(err), &pid) == 0) {
        int status;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        rewind(out);
        char line[512], flags[32], name[64];
        while (fgets(line, sizeof line, out))
            if (sscanf(line, " %31s %63s", flags, name) == 2 && flags[0] == 'V') {
                e.x264 |= !strcmp(name, "libx264");
                e.vp9 |= !strcmp(name, "libvpx-vp9");
                e.vp8 |= !strcmp(name, "libvpx");
            }
    }
    fclose(out);
    fclose(err);
    return e;
}

/* why = what, then how ffmpeg ended, then its messages on one line. */
static void describe(cli_video *v, int status, const char *what, char *why, size_t cap) {
    int n;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        n = snprintf(why, cap, "%s: ffmpeg reported errors", what);
    else if (WIFEXITED(status))
        n = snprintf(why, cap, "%s: ffmpeg failed (exit status %d)", what, WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        n = snprintf(why, cap, "%s: ffmpeg was killed by signal %d", what, WTERMSIG(status));
    else
        n = snprintf(why, cap, "%s: ffmpeg failed", what);
    if (n < 0 || (size_t)n >= cap || !v->log) return;
    fflush(v->log);
    rewind(v->log);
    char text[2048];
    size_t got = fread(text, 1, sizeof text - 1, v->log);
    text[got] = '\0';
    /* Its lines joined with "; ", trailing space dropped. */
    size_t at = (size_t)n, k = 0;
    while (k < got && (text[k] == '\n' || text[k] == ' ')) k++;
    if (k < got && at + 3 < cap) {
        memcpy(why + at, ": ", 2);
        at += 2;
    }
    for (; k < got && at + 3 < cap; k++) {
        if (text[k] == '\n' || text[k] == '\r') {
            size_t j = k;
            while (j < got && (text[j] == '\n' || text[j] == '\r' || text[j] == ' ')) j++;
            if (j >= got) break;
            why[at++] = ';';
            why[at++] = ' ';
            k = j - 1;
        } else {
            why[at++] = text[k];
        }
    }
    why[at] = '\0';
}

/* Frees v; its temporary video, unless committed, is removed. */
static void release(cli_video *v) {
    rt_output_discard(v->out); /* NULL once committed */
    if (v->in >= 0) close(v->in);
    if (v->log) fclose(v->log);
    sigaction(SIGPIPE, &v->old_pipe, NULL);
    free(v->frame);
    free(v);
}

static int wait_child(cli_video *v) {
    int status = 0;
    if (v->pid > 0) {
        /* Waited for without reaping first: until it is reaped its id
         * cannot be reused, so the signal handler (cli_signals.h), which
         * kills it, can never kill another process. */
        siginfo_t info;
        while (waitid(P_PID, (id_t)v->pid, &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
        }
        cli_signals_child(0);
        while (waitpid(v->pid, &status, 0) < 0 && errno == EINTR) {
        }
    }
    v->pid = 0;
    return status;
}

cli_video *cli_video_open(const char *path, int width, int height, double fps, int metadata,
                          char *why, size_t cap) {
    if (!cli_have_ffmpeg()) {
        snprintf(why, cap, "%s", no_ffmpeg);
        return NULL;
    }
    const char *ext = strrchr(path, '.');
    int webm = ext && !strcasecmp(ext, ".webm"), mkv = ext && !strcasecmp(ext, ".mkv");
    encoders enc = probe_encoders();
    if (webm && !enc.vp9 && !enc.vp8) {
        snprintf(why, cap, "this ffmpeg has no VP9 or VP8 encoder (libvpx) for .webm; use .mp4");
        return NULL;
    }
    char size[32], rate[40];
    snprintf(size, sizeof size, "%dx%d", width, height);
    snprintf(rate, sizeof rate, "%.17g", fps);
    cli_video *v = calloc(1, sizeof *v);
    if (v) v->frame = malloc((size_t)width * (size_t)height * 3);
    if (!v || !v->frame) {
        if (v) free(v->frame);
        free(v);
        snprintf(why, cap, "out of memory");
        return NULL;
    }
    rt_error err;
    if (rt_output_reserve(path, "video", &v->out, &err) != RT_OK) {
        snprintf(why, cap, "%s", err.message);
        free(v->frame);
        free(v);
        return NULL;
    }
    const char *file = rt_output_path(v->out);
    size_t url_len = strlen(file) + 6;
    char *url = malloc(url_len);
    if (!url) {
        rt_output_discard(v->out);
        free(v->frame);
        free(v);
        snprintf(why, cap, "out of memory");
        return NULL;
    }
    /* A file: URL: a path starting with '-' is no option, one with a colon
     * no protocol. */
    snprintf(url, url_len, "file:%s", file);
    char *argv[48];
    int n = 0;
    char *head[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostats", "-y",
                    "-f",     "rawvideo",     "-pix_fmt",  "rgb24", "-s",       size,
                    "-r",     rate,           "-i",        "-"};
    for (size_t i = 0; i < sizeof head / sizeof head[0]; i++) argv[n++] = head[i];
    if ((width | height) & 1) {
        /* 4:2:0 chroma needs even sides: one black column or row more. */
        argv[n++] = "-vf";
        argv[n++] = "pad=ceil(iw/2)*2:ceil(ih/2)*2";
    }
    argv[n++] = "-c:v";
    if (webm) {
        argv[n++] = enc.vp9 ? "libvpx-vp9" : "libvpx";
        char *vpx[] = {"-crf", "30", "-b:v", "0", "-cpu-used", "4", "-f", "webm"};
        for (size_t i = 0; i < sizeof vpx / sizeof vpx[0]; i++) argv[n++] = vpx[i];
    } else if (enc.x264) {
        char *x264[] = {"libx264", "-preset", "medium", "-crf", "18"};
        for (size_t i = 0; i < sizeof x264 / sizeof x264[0]; i++) argv[n++] = x264[i];
    } else {
        argv[n++] = "mpeg4";
        argv[n++] = "-q:v";
        argv[n++] = "2";
    }
    argv[n++] = "-pix_fmt";
    argv[n++] = "yuv420p";
    if (!webm) {
        argv[n++] = "-f";
        argv[n++] = mkv ? "matroska" : "mp4";
    }
    if (!metadata) {
        /* Matroska and WebM otherwise hold the date and a random segment
         * id: two equal clips were two different files. */
        argv[n++] = "-fflags";
        argv[n++] = "+bitexact";
    }
    argv[n++] = url;
    argv[n] = NULL;

    v->in = -1;
    v->width = width;
    v->height = height;
    int fds[2] = {-1, -1};
    v->log = tmpfile();
    if (!v->log || pipe(fds) != 0) {
        snprintf(why, cap, "cannot start ffmpeg: %s", strerror(errno));
        if (v->log) fclose(v->log);
        rt_output_discard(v->out);
        free(v->frame);
        free(v);
        free(url);
        return NULL;
    }
    close_on_exec(fds[0]);
    close_on_exec(fds[1]);
    close_on_exec(fileno(v->log));
    /* A write to an ffmpeg that has exited fails with EPIPE (and is reported)
     * instead of killing rtcl. */
    struct sigaction ign;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    sigaction(SIGPIPE, &ign, &v->old_pipe);
    int rc = spawn(argv, fds[0], -1, fileno(v->log), &v->pid);
    free(url);
    close(fds[0]);
    v->in = fds[1];
    if (rc != 0) {
        v->pid = 0;
        snprintf(why, cap, "cannot start ffmpeg: %s", strerror(rc));
        release(v);
        return NULL;
    }
    cli_signals_child(v->pid);
    return v;
}

/* Clamps to [0,1] and rounds to the nearest of 256 levels, NaN to 0: the
 * PPM writer's rule (formats/image_pnm.c). */
static unsigned char to_8bit(float x) {
    if (!(x > 0.0f)) return 0;
    if (x >= 1.0f) return 255;
    return (unsigned char)((double)x * 255.0 + 0.5);
}

int cli_video_write(cli_video *v, const float *rgb, char *why, size_t cap) {
    size_t n = (size_t)v->width * (size_t)v->height * 3;
    for (size_t i = 0; i < n; i++) v->frame[i] = to_8bit(rgb[i]);
    const unsigned char *p = v->frame;
    while (n) {
        ssize_t k = write(v->in, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) {
            int e = errno;
            close(v->in);
            v->in = -1;
            int status = wait_child(v);
            if (e == EPIPE)
                describe(v, status, "the video could not be written", why, cap);
            else
                snprintf(why, cap, "sending a frame to ffmpeg: %s", strerror(e));
            return 0;
        }
        p += k;
        n -= (size_t)k;
    }
    return 1;
}

int cli_video_close(cli_video *v, char *why, size_t cap) {
    close(v->in);
    v->in = -1;
    int status = wait_child(v);
    /* ffmpeg 5 exits with 0 when writing the file's end fails (a full
     * disk): any message at level "error" is a failure too. */
    long logged = 0;
    if (v->log && fflush(v->log) == 0 && fseek(v->log, 0, SEEK_END) == 0) logged = ftell(v->log);
    int ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && logged == 0;
    if (!ok) describe(v, status, "the video could not be written", why, cap);
    rt_error err;
    if (ok) {
        rt_output *out = v->out;
        v->out = NULL;
        if (rt_output_commit(out, &err) != RT_OK) {
            snprintf(why, cap, "%s", err.message);
            ok = 0;
        }
    }
    release(v);
    return ok;
}

void cli_video_abort(cli_video *v) {
    if (!v) return;
    if (v->in >= 0) close(v->in);
    v->in = -1;
    if (v->pid > 0) kill(v->pid, SIGTERM);
    wait_child(v);
    release(v);
}

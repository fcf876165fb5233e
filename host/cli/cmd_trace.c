/* cmd_trace.c - 'rtcl trace': rays from a text file through a scene, one hit
 * line per ray (rt_trace_rays). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/file_read.h"
#include "cli_util.h"
#include "commands.h"
#include "rt_shared.h"
#include "scene/scene.h"

static const char usage_head[] =
    "usage: rtcl trace SCENE --rays RAYS.txt --out HITS.txt [--backend B] [--device D]\n"
    "                  [--tri-test T] [--any-hit] [--offset-origins] [--threads N]\n"
    "                  [--accel A] [--cl-options OPTS] [--packet-isa I] [--help]\n"
    "\n"
    "Traces the rays of RAYS.txt through SCENE (a .json scene, a bare .obj, or\n"
    "builtin:NAME) and writes one line per ray to HITS.txt.\n"
    "\n"
    "RAYS.txt   one ray per line: ox oy oz dx dy dz tmin tmax (the ray o + t d for\n"
    "           t in [tmin, tmax], inclusive; d need not be normalised, t is in its\n"
    "           units). Blank lines and lines starting with '#' are skipped. A ray\n"
    "           with a NaN or infinite component or a zero direction is a miss.\n"
    "HITS.txt   per ray: 'hit t u v prim', plus ' inst' when the scene has more\n"
    "           than one object. hit is 1 or 0; p = (1-u-v) v0 + u v1 + v v2; prim is\n"
    "           the 0-based triangle index in its mesh's file order; inst the object\n"
    "           index. Floats as %.9g. A miss is '0 inf 0 0 -1' (plus ' -1').\n"
    "\n"
    "  --tri-test T the ray/triangle test: watertight (Woop, Benthin, Wald 2013),\n"
    "               mt (Moller-Trumbore), pluecker or badouel [watertight]\n"
    "  --any-hit    stop at any hit in range (shadow-ray queries): hit is then\n"
    "               exact, t u v prim inst belong to some hit, not the closest\n"
    "  --offset-origins  each ray line has 3 more numbers, nx ny nz: the origin\n"
    "               is a point on a surface with that normal, and is moved off it\n"
    "               with the engine's offset (as for shadow and secondary rays),\n"
    "               to the side the direction points to\n";

static void print_usage(FILE *f) {
    fputs(usage_head, f);
    fputs(cli_renderer_usage, f);
}

static const char *const tri_test_names[] = {"watertight", "mt", "pluecker", "badouel"};

/* Reads the rays; on a bad line prints file:line and returns 0. */
static int read_rays(const char *path, int offset, rt_ray **out, size_t *count) {
    const int want = offset ? 11 : 8;
    /* The whole file, a regular one of at most RT_MAX_RAY_FILE_BYTES. */
    char *text;
    size_t text_len;
    rt_error rerr;
    if (rt_read_file(path, "ray file", RT_MAX_RAY_FILE_BYTES, &text, &text_len, &rerr) != RT_OK) {
        cli_error("trace", "%s", rerr.message);
        return 0;
    }
    size_t n = 0, cap = 1024;
    rt_ray *rays = malloc(cap * sizeof *rays);
    int lineno = 0, ok = rays != NULL;
    /* Line by line through the text, of any length; a line ends at '\n' or
     * at the end of the file. The text is NUL-terminated, so strtof stops
     * at the line's end once no NUL byte is inside the line. */
    for (size_t at = 0; ok && at < text_len;) {
        char *p = text + at, *eol = memchr(p, '\n', text_len - at);
        const size_t line_len = eol ? (size_t)(eol - p) : text_len - at;
        at += line_len + 1;
        lineno++;
        if (memchr(p, '\0', line_len)) {
            cli_error("trace", "%s:%d: a NUL byte in the line (a binary file?)", path, lineno);
            ok = 0;
            break;
        }
        char *const end_of_line = p + line_len;
        while (*p == ' ' || *p == '\t') p++;
        if (p == end_of_line || *p == '#' || *p == '\r') continue;
        float v[11];
        int got = 0;
        while (got < want + 1) {
            char *end;
            errno = 0;
            float x = strtof(p, &end);
            if (end == p || end > end_of_line) break;
            if (got < want) v[got] = x;
            got++;
            p = end;
        }
        while (p < end_of_line && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
        if (got != want || p < end_of_line) {
            const int rest = p < end_of_line ? (int)(end_of_line - p) : 0;
            cli_error("trace", "%s:%d: expected %d numbers 'ox oy oz dx dy dz tmin tmax%s'%s%.*s%s",
                      path, lineno, want, offset ? " nx ny nz" : "", rest ? ", found: " : "",
                      rest > 40 ? 40 : rest, p, rest > 40 ? "..." : "");
            ok = 0;
            break;
        }
        if (n == cap) {
            rt_ray *r = realloc(rays, 2 * cap * sizeof *rays);
            if (!r) {
                ok = 0;
                break;
            }
            rays = r;
            cap *= 2;
        }
        rt_ray *r = &rays[n++];
        memcpy(r->org, v, sizeof r->org);
        memcpy(r->dir, v + 3, sizeof r->dir);
        r->tmin = v[6];
        r->tmax = v[7];
        if (offset) { /* off the surface, on the side the ray leaves to */
            float d = rt_dot3(v + 8, r->dir);
            rt_offset_point(v, v + 8, d >= 0.0f ? 1.0f : -1.0f, r->org);
        }
    }
    free(text);
    if (!ok) {
        free(rays);
        return 0;
    }
    *out = rays;
    *count = n;
    return 1;
}

int cmd_trace(int argc, char **argv) {
    const char *scene_path = NULL, *rays_path = NULL, *out_path = NULL;
    int offset = 0;
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    cli_renderer_args ra;
    cli_renderer_args_init(&ra);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int taken = cli_renderer_arg(argc, argv, &i, "trace", &ra);
        if (taken < 0) return 2;
        if (taken) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--rays")) {
            if (!(rays_path = cli_value(argc, argv, &i, "trace"))) return 2;
        } else if (!strcmp(a, "--out") || !strcmp(a, "-o")) {
            if (!(out_path = cli_value(argc, argv, &i, "trace"))) return 2;
        } else if (!strcmp(a, "--tri-test")) {
            const char *name = cli_value(argc, argv, &i, "trace");
            if (!name) return 2;
            int found = -1;
            for (int k = 0; k < 4; k++)
                if (!strcmp(name, tri_test_names[k])) found = k;
            if (found < 0) {
                cli_error("trace", "unknown triangle test '%s' (watertight, mt, pluecker, badouel)",
                          name);
                return 2;
            }
            opt.tri_test = (rt_triangle_test)found;
        } else if (!strcmp(a, "--offset-origins")) {
            offset = 1;
        } else if (!strcmp(a, "--any-hit")) {
            opt.any_hit = 1;
        } else if (a[0] == '-' && a[1]) {
            cli_error("trace", "unknown option '%s'", a);
            print_usage(stderr);
            return 2;
        } else if (scene_path) {
            cli_error("trace", "more than one scene given ('%s' and '%s')", scene_path, a);
            return 2;
        } else {
            scene_path = a;
        }
    }
    if (!scene_path || !rays_path || !out_path) {
        cli_error("trace", "need SCENE, --rays and --out");
        print_usage(stderr);
        return 2;
    }
    rt_renderer *renderer = cli_renderer_create("trace", &ra);
    if (!renderer) return 2;
    rt_ray *rays = NULL;
    size_t n = 0;
    if (!read_rays(rays_path, offset, &rays, &n)) {
        rt_renderer_destroy(renderer);
        return 2;
    }
    rt_scene *scene;
    rt_error err;
    if (cli_load_scene(scene_path, &scene, &err) != RT_OK) {
        cli_error("trace", "%s", err.message);
        free(rays);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (!cli_apply_accel("trace", &ra, scene)) {
        rt_scene_destroy(scene);
        free(rays);
        rt_renderer_destroy(renderer);
        return 2;
    }
    rt_hit *hits = malloc((n ? n : 1) * sizeof *hits);
    rt_status st =
        hits ? rt_trace_rays(renderer, scene, rays, n, hits, &opt) : RT_ERROR_OUT_OF_MEMORY;
    if (st != RT_OK) {
        cli_error("trace", "%s", hits ? rt_renderer_error(renderer) : "out of memory");
        free(rays);
        free(hits);
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    rt_renderer_destroy(renderer);
    int with_inst = scene->object_count > 1;
    FILE *f = fopen(out_path, "w");
    if (!f) {
        cli_error("trace", "%s: cannot write: %s", out_path, strerror(errno));
        free(rays);
        free(hits);
        rt_scene_destroy(scene);
        return 2;
    }
    for (size_t i = 0; i < n; i++) {
        const rt_hit *h = &hits[i];
        if (h->hit)
            fprintf(f, "1 %.9g %.9g %.9g %u", h->t, h->u, h->v, h->prim);
        else
            fputs("0 inf 0 0 -1", f);
        if (with_inst) {
            if (h->hit)
                fprintf(f, " %u", h->inst);
            else
                fputs(" -1", f);
        }
        fputc('\n', f);
    }
    int bad = fclose(f) != 0;
    if (bad) cli_error("trace", "%s: write failed", out_path);
    free(rays);
    free(hits);
    rt_scene_destroy(scene);
    return bad ? 2 : 0;
}

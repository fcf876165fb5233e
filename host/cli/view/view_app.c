/* SPDX-License-Identifier: Apache-2.0 */
/* view_app.c - the viewer's window (SDL2): input, the camera, the job loop
 * with the render thread (view_worker.c), presenting, the title's numbers,
 * screenshots. Only this file includes SDL. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>

#include "frame_image.h"
#include "view.h"
#include "view_keys.h"
#include "view_script.h"
#include "view_timeline.h"
#include "view_worker.h"

int view_available(const char **why) {
    *why = "";
    return 1;
}

#define MAX_SHOTS  16
#define FPS_WINDOW 64

typedef struct shot {
    char *path;
    long min_seq; /* the first full-resolution frame numbered at least this */
} shot;

typedef struct app {
    view_options *o;
    SDL_Window *window;
    SDL_Renderer *sdl;
    SDL_Texture *texture;
    int tex_w, tex_h;
    unsigned char *bytes; /* the frame as 8-bit RGB for the texture */
    size_t bytes_size;
    Uint32 done_event;

    rt_scene *rig; /* holds only the camera: rt_camera_move/rotate do the maths */
    rt_camera cam; /* full resolution */
    double speed;  /* scene units per second */
    double time;   /* scene time, seconds */
    int playing, animated;
    char backend[288];
    rt_aov aov;
    int direct_only;

    int held[VIEW_KEY_COUNT];
    float drag_dx, drag_dy; /* since the last job */
    double wheel;           /* notches since the last job */

    view_script script;
    int scripted;
    long next_seq; /* the next job's number */
    long presented;
    int quit, status;

    shot shots[MAX_SHOTS];
    int shot_count;
    int shot_counter; /* for F12's file names */

    view_job last_job;
    int have_last_job;
    double last_compose_ms;
    double est_full_ms; /* a full-resolution frame's update + render, measured */

    const view_result *last; /* the last presented result (valid until the next post) */

    /* the numbers */
    double present_times[FPS_WINDOW];
    long present_count;
    double last_title_ms, last_update_ms, last_render_ms, last_present_ms;
    double *parts; /* per presented frame: update, render, present */
    size_t parts_cap;
    double first_present_ms, final_present_ms;
    uint64_t triangles;
    char device[192];
    int exact;
    double mrays;
    int last_divisor;
    char last_backend[32];
} app;

static void on_done(void *user) {
    SDL_Event e;
    memset(&e, 0, sizeof e);
    e.type = (Uint32)(uintptr_t)user;
    SDL_PushEvent(&e);
}

static view_key key_of(SDL_Keycode k) {
    switch (k) {
    case SDLK_w:
        return VIEW_KEY_W;
    case SDLK_a:
        return VIEW_KEY_A;
    case SDLK_s:
        return VIEW_KEY_S;
    case SDLK_d:
        return VIEW_KEY_D;
    case SDLK_r:
        return VIEW_KEY_R;
    case SDLK_f:
        return VIEW_KEY_F;
    case SDLK_q:
        return VIEW_KEY_Q;
    case SDLK_e:
        return VIEW_KEY_E;
    case SDLK_UP:
        return VIEW_KEY_UP;
    case SDLK_DOWN:
        return VIEW_KEY_DOWN;
    case SDLK_LEFT:
        return VIEW_KEY_LEFT;
    case SDLK_RIGHT:
        return VIEW_KEY_RIGHT;
    case SDLK_PAGEUP:
        return VIEW_KEY_PAGEUP;
    case SDLK_PAGEDOWN:
        return VIEW_KEY_PAGEDOWN;
    case SDLK_SPACE:
        return VIEW_KEY_SPACE;
    case SDLK_1:
    case SDLK_KP_1:
        return VIEW_KEY_1;
    case SDLK_2:
    case SDLK_KP_2:
        return VIEW_KEY_2;
    case SDLK_3:
    case SDLK_KP_3:
        return VIEW_KEY_3;
    case SDLK_4:
    case SDLK_KP_4:
        return VIEW_KEY_4;
    case SDLK_l:
        return VIEW_KEY_L;
    case SDLK_v:
        return VIEW_KEY_V;
    case SDLK_F12:
        return VIEW_KEY_F12;
    case SDLK_c:
        return VIEW_KEY_C;
    case SDLK_h:
        return VIEW_KEY_H;
    case SDLK_ESCAPE:
        return VIEW_KEY_ESCAPE;
    default:
        return VIEW_KEY_NONE;
    }
}

static void add_shot(app *a, const char *path, long min_seq) {
    if (a->shot_count == MAX_SHOTS) {
        cli_error("view", "screenshot %s dropped: %d are already waiting for a full frame", path,
                  MAX_SHOTS);
        return;
    }
    char *copy = malloc(strlen(path) + 1);
    if (!copy) {
        cli_error("view", "screenshot %s dropped: out of memory", path);
        return;
    }
    strcpy(copy, path);
    a->shots[a->shot_count].path = copy;
    a->shots[a->shot_count].min_seq = min_seq;
    a->shot_count++;
}

/* F12: the next free rtcl-view-NNNN.png in the current directory. */
static void add_numbered_shot(app *a) {
    char path[64];
    for (int tries = 0; tries < 10000; tries++) {
        snprintf(path, sizeof path, "rtcl-view-%04d.png", a->shot_counter++ % 10000);
        FILE *f = fopen(path, "rb");
        if (!f) break;
        fclose(f);
    }
    add_shot(a, path, a->next_seq);
}

static void print_camera(const app *a) {
    const rt_camera *c = &a->cam;
    printf("\"camera\": {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [%.9g, %.9g, %.9g], "
           "\"up\": [%.9g, %.9g, %.9g], \"fov\": %.9g, \"width\": %d, \"height\": %d}\n",
           (double)c->position[0], (double)c->position[1], (double)c->position[2],
           (double)c->look_at[0], (double)c->look_at[1], (double)c->look_at[2], (double)c->up[0],
           (double)c->up[1], (double)c->up[2], (double)c->hfov_degrees, c->width, c->height);
    fflush(stdout);
}

static void select_backend(app *a, const char *name) {
    const char *device = a->o->renderer.device;
    if (device && cli_backend_takes_device(name))
        snprintf(a->backend, sizeof a->backend, "%s:%s", name, device);
    else
        snprintf(a->backend, sizeof a->backend, "%s", name);
}

/* A key pressed (down) or released. One-shot keys act on the press. */
static void key_event(app *a, view_key k, int down) {
    if (k == VIEW_KEY_NONE) return;
    int was = a->held[k];
    a->held[k] = down;
    if (!down || was) return;
    static const rt_aov cycle[] = {RT_AOV_NONE,   RT_AOV_DEPTH,     RT_AOV_NORMAL,   RT_AOV_PRIMID,
                                   RT_AOV_INSTID, RT_AOV_BOX_TESTS, RT_AOV_TRI_TESTS};
    const char *backend = view_key_backend(k);
    if (backend) {
        select_backend(a, backend);
        return;
    }
    switch (k) {
    case VIEW_KEY_SPACE:
        a->playing = !a->playing;
        break;
    case VIEW_KEY_PAGEUP:
        a->speed *= 1.5;
        break;
    case VIEW_KEY_PAGEDOWN:
        a->speed /= 1.5;
        break;
    case VIEW_KEY_L:
        a->direct_only = !a->direct_only;
        break;
    case VIEW_KEY_V: {
        size_t n = sizeof cycle / sizeof cycle[0], i = 0;
        while (i < n && cycle[i] != a->aov) i++;
        a->aov = cycle[(i + 1) % n];
        break;
    }
    case VIEW_KEY_F12:
        add_numbered_shot(a);
        break;
    case VIEW_KEY_C:
        print_camera(a);
        break;
    case VIEW_KEY_H:
        printf("rtcl view keys:\n");
        view_keys_print(stdout, "  ");
        fflush(stdout);
        break;
    case VIEW_KEY_ESCAPE:
        a->quit = 1;
        break;
    default:
        break;
    }
}

static void script_event(app *a, const view_event *ev) {
    switch (ev->kind) {
    case VIEW_EVENT_DOWN:
        key_event(a, ev->key, 1);
        break;
    case VIEW_EVENT_UP:
        key_event(a, ev->key, 0);
        break;
    case VIEW_EVENT_TAP:
        key_event(a, ev->key, 1);
        key_event(a, ev->key, 0);
        break;
    case VIEW_EVENT_DRAG:
        a->drag_dx += ev->dx;
        a->drag_dy += ev->dy;
        break;
    case VIEW_EVENT_WHEEL:
        a->wheel += ev->dx;
        break;
    case VIEW_EVENT_SCREENSHOT:
        add_shot(a, ev->path, ev->frame);
        break;
    case VIEW_EVENT_QUIT:
        a->quit = 1;
        break;
    }
}

static void sdl_event(app *a, const SDL_Event *e) {
    switch (e->type) {
    case SDL_QUIT:
        a->quit = 1;
        break;
    case SDL_KEYDOWN:
    case SDL_KEYUP:
        key_event(a, key_of(e->key.keysym.sym), e->type == SDL_KEYDOWN);
        break;
    case SDL_MOUSEMOTION:
        if (e->motion.state & SDL_BUTTON_LMASK) {
            a->drag_dx += (float)e->motion.xrel;
            a->drag_dy += (float)e->motion.yrel;
        }
        break;
    case SDL_MOUSEWHEEL:
        a->wheel += e->wheel.y;
        break;
    case SDL_WINDOWEVENT:
        if (e->window.event == SDL_WINDOWEVENT_FOCUS_LOST) memset(a->held, 0, sizeof a->held);
        break;
    default:
        break;
    }
}

static int same_camera(const rt_camera *x, const rt_camera *y) {
    return memcmp(x->position, y->position, sizeof x->position) == 0 &&
           memcmp(x->look_at, y->look_at, sizeof x->look_at) == 0 &&
           memcmp(x->up, y->up, sizeof x->up) == 0 && x->hfov_degrees == y->hfov_degrees;
}

/* Advances the camera and the timeline by dt seconds of held keys, drags
 * and wheel notches. */
static void integrate(app *a, double dt) {
    const int *h = a->held;
    if (a->wheel != 0.0) a->speed *= pow(1.5, a->wheel);
    a->wheel = 0.0;
    double dist = a->speed * dt;
    double fwd = h[VIEW_KEY_W] - h[VIEW_KEY_S], right = h[VIEW_KEY_D] - h[VIEW_KEY_A];
    double up = h[VIEW_KEY_R] + h[VIEW_KEY_E] - h[VIEW_KEY_F] - h[VIEW_KEY_Q];
    if (fwd != 0.0 || right != 0.0 || up != 0.0)
        rt_camera_move(a->rig, (float)(right * dist), (float)(up * dist), (float)(fwd * dist));
    const double turn_rate = 60.0, drag_degrees = 0.2; /* degrees per second, per pixel */
    double yaw =
        (h[VIEW_KEY_LEFT] - h[VIEW_KEY_RIGHT]) * turn_rate * dt - a->drag_dx * drag_degrees;
    double pitch = (h[VIEW_KEY_UP] - h[VIEW_KEY_DOWN]) * turn_rate * dt - a->drag_dy * drag_degrees;
    a->drag_dx = a->drag_dy = 0.0f;
    if (yaw != 0.0 || pitch != 0.0) {
        /* Pitching onto the up vector is refused (rt_camera_set): then turn
         * by the yaw alone. */
        if (rt_camera_rotate(a->rig, (float)yaw, (float)pitch) != RT_OK && yaw != 0.0)
            rt_camera_rotate(a->rig, (float)yaw, 0.0f);
    }
    rt_camera_get(a->rig, &a->cam);
    if (a->playing) a->time += dt;
}

/* The resolution divisor for a job: 1 when still; while moving, the fixed
 * --move-scale or the smallest that brings the measured full frame time
 * within the budget. */
static int choose_divisor(const app *a, int moving) {
    if (!moving) return 1;
    if (a->o->move_divisor > 0) return a->o->move_divisor;
    static const int divisors[] = {1, 2, 3, 4, 6, 8};
    for (size_t i = 0; i < sizeof divisors / sizeof divisors[0]; i++) {
        int d = divisors[i];
        if (a->est_full_ms / (d * d) <= a->o->budget_ms) return d;
    }
    return 8;
}

/* Composes and posts the next job. final: no input, full resolution (the
 * frame a screenshot at the end needs). */
static void post_job(app *a, view_worker *w, int final) {
    double now = cli_now_ms();
    if (!final) {
        const view_event *ev;
        if (a->scripted)
            while ((ev = view_script_next(&a->script, a->next_seq))) script_event(a, ev);
        double dt;
        if (a->o->step_ms > 0)
            dt = a->next_seq ? a->o->step_ms / 1000.0 : 0.0;
        else
            dt = a->have_last_job ? (now - a->last_compose_ms) / 1000.0 : 0.0;
        if (dt > 1.0) dt = 1.0; /* after a stall, do not jump across the scene */
        integrate(a, dt);
    }
    a->last_compose_ms = now;
    view_job job;
    memset(&job, 0, sizeof job);
    job.seq = a->next_seq++;
    job.camera = a->cam;
    job.time = a->time;
    snprintf(job.backend, sizeof job.backend, "%s", a->backend);
    job.aov = a->aov;
    job.direct_only = a->direct_only;
    int moving = a->have_last_job && (!same_camera(&job.camera, &a->last_job.camera) ||
                                      (a->animated && job.time != a->last_job.time));
    job.divisor = final ? 1 : choose_divisor(a, moving);
    a->last_job = job;
    a->have_last_job = 1;
    view_worker_post(w, &job);
}

/* The frame as 8-bit RGB: clamped to [0, 1], rounded to nearest, NaN as 0. */
static int to_bytes(app *a, const view_result *r) {
    const rt_framebuffer *fb = &r->fb;
    size_t n = (size_t)fb->width * fb->height;
    float *display = NULL;
    const float *src = fb->pixels;
    if (r->job.aov != RT_AOV_NONE) {
        if (!(display = cli_aov_to_display(fb, r->job.aov))) return 0;
        src = display;
    }
    if (a->bytes_size < 3 * n) {
        unsigned char *b = realloc(a->bytes, 3 * n);
        if (!b) {
            free(display);
            return 0;
        }
        a->bytes = b;
        a->bytes_size = 3 * n;
    }
    for (size_t i = 0; i < 3 * n; i++) {
        float v = src[i];
        v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN fails v > 0: 0 */
        a->bytes[i] = (unsigned char)(v * 255.0f + 0.5f);
    }
    free(display);
    return 1;
}

static int present(app *a, const view_result *r) {
    const rt_framebuffer *fb = &r->fb;
    if (!to_bytes(a, r)) {
        cli_error("view", "out of memory");
        return 0;
    }
    if (!a->texture || a->tex_w != fb->width || a->tex_h != fb->height) {
        if (a->texture) SDL_DestroyTexture(a->texture);
        a->texture = SDL_CreateTexture(a->sdl, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING,
                                       fb->width, fb->height);
        if (!a->texture) {
            cli_error("view", "cannot make a %dx%d texture: %s", fb->width, fb->height,
                      SDL_GetError());
            return 0;
        }
        a->tex_w = fb->width;
        a->tex_h = fb->height;
    }
    SDL_UpdateTexture(a->texture, NULL, a->bytes, fb->width * 3);
    SDL_RenderClear(a->sdl);
    SDL_RenderCopy(a->sdl, a->texture, NULL, NULL); /* stretched: reduced frames fill it */
    SDL_RenderPresent(a->sdl);
    return 1;
}

static void describe_device(app *a, const view_result *r) {
    const rt_render_stats *s = &r->stats;
    if (s->device[0])
        snprintf(a->device, sizeof a->device, "%s on %s (%s maths)", s->backend ? s->backend : "?",
                 s->device, s->math_profile ? s->math_profile : "?");
    else if (s->packet_isa && s->backend && !strcmp(s->backend, "packet"))
        snprintf(a->device, sizeof a->device, "packet (%s x%d, %d threads)", s->packet_isa,
                 s->packet_vector, s->threads);
    else
        snprintf(a->device, sizeof a->device, "%s (%d threads)", s->backend ? s->backend : "?",
                 s->threads);
    a->exact = s->exact; /* the library's promise (the CPU backends always make it) */
}

static void update_title(app *a) {
    double now = cli_now_ms();
    if (now - a->last_title_ms < 250.0 && a->present_count > 1) return;
    a->last_title_ms = now;
    long n = a->present_count < FPS_WINDOW ? a->present_count : FPS_WINDOW;
    double fps = 0.0;
    if (n >= 2) {
        double newest = a->present_times[(a->present_count - 1) % FPS_WINDOW];
        double oldest = a->present_times[(a->present_count - n) % FPS_WINDOW];
        if (newest > oldest) fps = (double)(n - 1) * 1000.0 / (newest - oldest);
    }
    char res[32] = "full res";
    if (a->last_divisor > 1) snprintf(res, sizeof res, "1/%d res", a->last_divisor);
    char title[512];
    snprintf(title, sizeof title,
             "rtcl view | %.1f fps | ms: update %.1f, render %.1f, present %.1f | "
             "%.1f Mrays/s | %s | oracle bits %s | %llu triangles | %s | %s | %s | t %.2f s%s",
             fps, a->last_update_ms, a->last_render_ms, a->last_present_ms, a->mrays, a->device,
             a->exact ? "promised" : "NOT promised", (unsigned long long)a->triangles, res,
             cli_aov_name(a->aov), a->direct_only ? "direct" : "Whitted", a->time,
             a->playing ? " playing" : "");
    SDL_SetWindowTitle(a->window, title);
}

static void record_times(app *a, double update, double render, double present_ms) {
    if ((size_t)a->presented >= a->parts_cap) {
        size_t cap = a->parts_cap ? 2 * a->parts_cap : 256;
        double *p = realloc(a->parts, 3 * cap * sizeof(double));
        if (!p) return;
        a->parts = p;
        a->parts_cap = cap;
    }
    a->parts[3 * a->presented + 0] = update;
    a->parts[3 * a->presented + 1] = render;
    a->parts[3 * a->presented + 2] = present_ms;
}

/* Writes the screenshots the full-resolution result r fulfils. */
static void take_shots(app *a, const view_result *r) {
    if (r->job.divisor != 1) return;
    for (int i = 0; i < a->shot_count;) {
        if (a->shots[i].min_seq > r->job.seq) {
            i++;
            continue;
        }
        rt_error err;
        if (cli_frame_write(a->shots[i].path, &r->fb, r->job.aov, 0, &err) != RT_OK) {
            cli_error("view", "%s", err.message);
            a->status = 2;
        } else {
            printf("screenshot: %s (%dx%d, frame %ld, backend %s, %s, %s)\n", a->shots[i].path,
                   r->fb.width, r->fb.height, r->job.seq, r->stats.backend,
                   cli_aov_name(r->job.aov), r->job.direct_only ? "direct" : "Whitted");
            fflush(stdout);
        }
        free(a->shots[i].path);
        a->shots[i] = a->shots[--a->shot_count];
    }
}

/* Takes in a finished result before the next job is posted: a failed
 * backend switch (the next job keeps the backend that works), a failed
 * frame, the frame time that the next divisor is chosen by. Returns 0 when
 * the session must end. */
static int accept_result(app *a, const view_result *r) {
    if (r->backend_failed) {
        cli_error("view", "cannot switch to backend '%s': %s", r->job.backend, r->backend_error);
        snprintf(a->backend, sizeof a->backend, "%s", r->backend_spec);
    }
    if (!r->ok) {
        cli_error("view", "frame %ld: %s", r->job.seq, r->error);
        a->status = 2;
        return 0;
    }
    a->est_full_ms = (r->update_ms + r->render_ms) * r->job.divisor * r->job.divisor;
    return 1;
}

/* Presents a result, fulfils screenshots, updates the numbers (while the
 * next job renders). Returns 0 when the session must end. */
static int show_result(app *a, const view_result *r) {
    if (r->stats.notice && a->presented == 0) cli_error("view", "notice: %s", r->stats.notice);
    if (r->stats.backend && strcmp(r->stats.backend, a->last_backend) != 0) {
        if (a->last_backend[0]) {
            printf("backend: %s (frame %ld)\n", r->stats.backend, r->job.seq);
            fflush(stdout);
        }
        snprintf(a->last_backend, sizeof a->last_backend, "%s", r->stats.backend);
    }
    double t0 = cli_now_ms();
    if (!present(a, r)) {
        a->status = 2;
        return 0;
    }
    double t1 = cli_now_ms();
    a->last = r;
    a->last_update_ms = r->update_ms;
    a->last_render_ms = r->render_ms;
    a->last_present_ms = t1 - t0;
    a->last_divisor = r->job.divisor;
    a->triangles = r->triangles;
    a->mrays = r->render_ms > 0 ? (double)r->stats.rays / (r->render_ms * 1000.0) : 0.0;
    describe_device(a, r);
    record_times(a, r->update_ms, r->render_ms, t1 - t0);
    a->present_times[a->present_count % FPS_WINDOW] = t1;
    a->present_count++;
    if (a->presented == 0) a->first_present_ms = t1;
    a->final_present_ms = t1;
    a->presented++;
    take_shots(a, r);
    update_title(a);
    return 1;
}

static int compare_double(const void *x, const void *y) {
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static double median_of(double *v, size_t n, size_t stride, size_t offset) {
    if (!n) return 0.0;
    double *tmp = malloc(n * sizeof(double));
    if (!tmp) return 0.0;
    for (size_t i = 0; i < n; i++) tmp[i] = v[i * stride + offset];
    qsort(tmp, n, sizeof(double), compare_double);
    double m = n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
    free(tmp);
    return m;
}

/* The line printed at the end: frames after the first (which builds the
 * BVHs and, on a device, compiles and uploads) are the steady state. */
static void print_summary(app *a) {
    long steady = a->presented - 1;
    if (steady < 1 || (size_t)a->presented > a->parts_cap) {
        printf("view: %ld frames\n", a->presented);
        return;
    }
    double span = a->final_present_ms - a->first_present_ms;
    double fps = span > 0 ? (double)steady * 1000.0 / span : 0.0;
    printf("view: %ld frames; after the first: %.2f fps; median ms: update %.2f, render %.2f, "
           "present %.2f (presenting overlaps the next frame's render); %s, %llu triangles\n",
           a->presented, fps, median_of(a->parts + 3, (size_t)steady, 3, 0),
           median_of(a->parts + 3, (size_t)steady, 3, 1),
           median_of(a->parts + 3, (size_t)steady, 3, 2), a->device,
           (unsigned long long)a->triangles);
}

static int open_window(app *a) {
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        cli_error("view",
                  "cannot open a window: %s (without a display, run it under Xvfb: "
                  "xvfb-run rtcl view ...)",
                  SDL_GetError());
        return 0;
    }
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "0"); /* reduced frames: whole pixels */
    a->window = SDL_CreateWindow("rtcl view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                                 a->cam.width, a->cam.height, SDL_WINDOW_RESIZABLE);
    if (!a->window) {
        cli_error("view", "cannot open a %dx%d window: %s", a->cam.width, a->cam.height,
                  SDL_GetError());
        return 0;
    }
    a->sdl = SDL_CreateRenderer(a->window, -1, 0);
    if (!a->sdl) a->sdl = SDL_CreateRenderer(a->window, -1, SDL_RENDERER_SOFTWARE);
    if (!a->sdl) {
        cli_error("view", "cannot draw into the window: %s", SDL_GetError());
        return 0;
    }
    a->done_event = SDL_RegisterEvents(1);
    if (a->done_event == (Uint32)-1) {
        cli_error("view", "SDL has no user events left");
        return 0;
    }
    return 1;
}

/* Loads the scene, makes the renderer and the camera rig. */
static int load(app *a, rt_scene **scene, rt_renderer **renderer) {
    view_options *o = a->o;
    rt_error err;
    if (o->script) {
        if (view_script_load(o->script, &a->script, &err) != RT_OK) {
            cli_error("view", "%s", err.message);
            return 0;
        }
        a->scripted = 1;
    }
    if (!(*scene = cli_scene_open("view", o->scene_path, &o->scene, o->renderer.threads))) return 0;
    rt_camera_get(*scene, &a->cam);
    if (o->frame.width) a->cam.width = o->frame.width;
    if (o->frame.height) a->cam.height = o->frame.height;
    if (rt_scene_create(&a->rig) != RT_OK || rt_camera_set(a->rig, &a->cam) != RT_OK) {
        cli_error("view", "%s", a->rig ? rt_scene_error(a->rig) : "out of memory");
        return 0;
    }
    float lo[3], hi[3];
    double diagonal = 1.0;
    if (rt_scene_bounds(*scene, lo, hi)) {
        double d2 = 0.0;
        for (int i = 0; i < 3; i++) d2 += (double)(hi[i] - lo[i]) * (hi[i] - lo[i]);
        if (d2 > 0.0 && isfinite(d2)) diagonal = sqrt(d2);
    }
    a->speed = 0.25 * diagonal; /* crosses the scene in four seconds */
    if (!(*renderer = cli_renderer_create("view", &o->renderer))) return 0;
    snprintf(a->backend, sizeof a->backend, "%s", o->renderer.spec);
    a->time = isnan(o->scene.time) ? 0.0 : o->scene.time;
    a->playing = o->play;
    a->aov = (rt_aov)o->frame.aov;
    a->direct_only = o->frame.direct;
    return 1;
}

int view_run(view_options *o) {
    app a;
    memset(&a, 0, sizeof a);
    a.o = o;
    a.status = 2;
    rt_scene *scene = NULL;
    rt_renderer *renderer = NULL;
    view_timeline timeline;
    memset(&timeline, 0, sizeof timeline);
    view_worker *worker = NULL;
    if (!load(&a, &scene, &renderer)) goto done;
    if (view_timeline_init(&timeline, scene, o->keyframe_rate) != RT_OK) {
        cli_error("view", "out of memory");
        goto done;
    }
    a.animated = timeline.animated;
    if (!open_window(&a)) goto done;
    if (view_worker_start(&worker, renderer, scene, &timeline, a.backend, on_done,
                          (void *)(uintptr_t)a.done_event) != RT_OK) {
        cli_error("view", "cannot start the render thread");
        goto done;
    }
    a.status = 0;
    int finishing = 0;
    post_job(&a, worker, 0);
    for (;;) {
        SDL_Event e;
        if (SDL_WaitEventTimeout(&e, 10)) {
            do {
                if (e.type != a.done_event) sdl_event(&a, &e);
            } while (SDL_PollEvent(&e));
        }
        const view_result *r = view_worker_take(worker);
        if (!r) continue;
        if (!accept_result(&a, r)) break;
        /* The next job goes out before this frame is presented, so that the
         * worker renders while this thread presents. */
        int end = a.quit || (o->frames && a.presented + 1 >= o->frames);
        if (!end) post_job(&a, worker, 0);
        if (!show_result(&a, r)) break;
        if (end) {
            /* One more full frame when a screenshot still needs one. */
            int want_final = (o->screenshot && r->job.divisor != 1) || a.shot_count;
            if (finishing || !want_final) break;
            finishing = 1;
            post_job(&a, worker, 1);
        }
    }
    if (a.status == 0 && o->screenshot && a.last) {
        rt_error err;
        if (cli_frame_write(o->screenshot, &a.last->fb, a.last->job.aov, 0, &err) != RT_OK) {
            cli_error("view", "%s", err.message);
            a.status = 2;
        } else {
            printf("screenshot: %s (%dx%d, frame %ld, backend %s, %s, %s)\n", o->screenshot,
                   a.last->fb.width, a.last->fb.height, a.last->job.seq, a.last->stats.backend,
                   cli_aov_name(a.last->job.aov), a.last->job.direct_only ? "direct" : "Whitted");
        }
    }
    for (int i = 0; i < a.shot_count; i++) {
        cli_error("view", "screenshot %s not taken: the session ended first", a.shots[i].path);
        free(a.shots[i].path);
    }
    if (a.status == 0) print_summary(&a);
done:
    view_worker_stop(worker);
    if (a.texture) SDL_DestroyTexture(a.texture);
    if (a.sdl) SDL_DestroyRenderer(a.sdl);
    if (a.window) SDL_DestroyWindow(a.window);
    SDL_Quit();
    view_timeline_free(&timeline);
    view_script_free(&a.script);
    free(a.bytes);
    free(a.parts);
    rt_scene_destroy(a.rig);
    rt_scene_destroy(scene);
    rt_renderer_destroy(renderer);
    return a.status;
}

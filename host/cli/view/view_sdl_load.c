/* SPDX-License-Identifier: Apache-2.0 */
/* view_sdl_load.c - SDL2 loaded when the viewer first calls it, not when
 * rtcl starts. Linked normally, SDL2 brings about 50 libraries (X11,
 * Wayland, PulseAudio, ...) into every rtcl command: about 6 ms of CPU at
 * each start, and more inside PoCL's start-up, whose symbol lookups then
 * search them all ('rtcl devices'; docs/BENCHMARKS.md, start-up).
 *
 * This file defines the SDL functions the viewer (view_app.c) calls, each
 * forwarding to the same function of libSDL2-2.0.so.0, opened on the first
 * call (dlopen, local scope). Where the library cannot be opened, SDL_Init
 * fails and SDL_GetError says why; the viewer reports it as any failure to
 * open a window. view_app.c is unchanged: it is compiled against SDL.h as
 * before. A function the viewer starts to use must be added here (the
 * link fails until it is). */
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>

#include <SDL.h>

#define SDL_SONAME "libSDL2-2.0.so.0"

/* Every function, once: X(return type, name, (parameters), (arguments)). */
#define SDL_FUNCTIONS(X, V)                                                                        \
    V(SDL_Quit, (void), ())                                                                        \
    X(SDL_bool, SDL_SetHint, (const char *name, const char *value), (name, value))                 \
    X(SDL_Window *, SDL_CreateWindow, (const char *t, int x, int y, int w, int h, Uint32 f),       \
      (t, x, y, w, h, f))                                                                          \
    V(SDL_DestroyWindow, (SDL_Window * w), (w))                                                    \
    V(SDL_SetWindowTitle, (SDL_Window * w, const char *t), (w, t))                                 \
    X(SDL_Renderer *, SDL_CreateRenderer, (SDL_Window * w, int i, Uint32 f), (w, i, f))            \
    V(SDL_DestroyRenderer, (SDL_Renderer * r), (r))                                                \
    X(SDL_Texture *, SDL_CreateTexture, (SDL_Renderer * r, Uint32 f, int a, int w, int h),         \
      (r, f, a, w, h))                                                                             \
    V(SDL_DestroyTexture, (SDL_Texture * t), (t))                                                  \
    X(int, SDL_UpdateTexture, (SDL_Texture * t, const SDL_Rect *r, const void *p, int pitch),      \
      (t, r, p, pitch))                                                                            \
    X(int, SDL_RenderClear, (SDL_Renderer * r), (r))                                               \
    X(int, SDL_RenderCopy,                                                                         \
      (SDL_Renderer * r, SDL_Texture * t, const SDL_Rect *s, const SDL_Rect *d), (r, t, s, d))     \
    V(SDL_RenderPresent, (SDL_Renderer * r), (r))                                                  \
    X(Uint32, SDL_RegisterEvents, (int n), (n))                                                    \
    X(int, SDL_PushEvent, (SDL_Event * e), (e))                                                    \
    X(int, SDL_PollEvent, (SDL_Event * e), (e))                                                    \
    X(int, SDL_WaitEventTimeout, (SDL_Event * e, int ms), (e, ms))

#define POINTER(ret, name, params, args) static ret(SDLCALL *p_##name) params;
#define VPOINTER(name, params, args)     static void(SDLCALL * p_##name) params;
SDL_FUNCTIONS(POINTER, VPOINTER)
static int(SDLCALL *p_SDL_Init)(Uint32 flags);
static const char *(SDLCALL *p_SDL_GetError)(void);

static pthread_once_t once = PTHREAD_ONCE_INIT;
static int loaded;
static char why[300];

static void load(void) {
    void *h = dlopen(SDL_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        snprintf(why, sizeof why,
                 "%s (the viewer loads SDL2 when it starts: install libsdl2-2.0-0)", dlerror());
        return;
    }
    const char *missing = NULL;
#define FIND(name)                                                                                 \
    if (!(*(void **)&p_##name = dlsym(h, #name)) && !missing) missing = #name;
#define XFIND(ret, name, params, args) FIND(name)
#define VFIND(name, params, args)      FIND(name)
    SDL_FUNCTIONS(XFIND, VFIND)
    FIND(SDL_Init)
    FIND(SDL_GetError)
    if (missing) {
        snprintf(why, sizeof why, "%s has no %s", SDL_SONAME, missing);
        dlclose(h);
        return;
    }
    loaded = 1;
}

static int ready(void) {
    pthread_once(&once, load);
    return loaded;
}

/* SDL_Init fails (-1) when the library cannot be loaded; the viewer then
 * stops, so the others are not reached before a successful load (they
 * would return 0 or do nothing). */
int SDLCALL SDL_Init(Uint32 flags) {
    return ready() ? p_SDL_Init(flags) : -1;
}

#define FORWARD(ret, name, params, args)                                                           \
    ret SDLCALL name params {                                                                      \
        if (!ready()) return (ret)0;                                                               \
        return p_##name args;                                                                      \
    }
#define VFORWARD(name, params, args)                                                               \
    void SDLCALL name params {                                                                     \
        if (ready()) p_##name args;                                                                \
    }
SDL_FUNCTIONS(FORWARD, VFORWARD)

const char *SDLCALL SDL_GetError(void) {
    return ready() ? p_SDL_GetError() : why;
}

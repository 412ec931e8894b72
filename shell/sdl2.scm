;;; (downstroke sdl2): the part of SDL2 and SDL2_image the library uses,
;;; bound through CHICKEN's FFI (Debian's libsdl2-dev, libsdl2-image-dev).
;;;
;;; Naming follows the sdl2 egg: SDL names in kebab-case, `!` on every call
;;; with an effect, symbols for enums, multiple values for pairs.
;;;
;;; Resources. Windows, renderers, textures and surfaces are Scheme records
;;; around a native pointer. Each is freed exactly once: by its destroy
;;; procedure (destroy-window!, destroy-renderer!, destroy-texture!,
;;; free-surface!), which may be called any number of times, or else by a
;;; finalizer when the record becomes garbage (the finalizer does nothing
;;; if the resource was already destroyed). Ownership follows SDL's:
;;;   - destroying a renderer frees its textures (SDL does that), so their
;;;     records become dead and destroying them afterwards does nothing;
;;;   - destroying a window or the surface a software renderer draws on
;;;     destroys that renderer first;
;;;   - quit! invalidates every window, renderer and texture made before it
;;;     (SDL_Quit tears down the video subsystem): their records become dead
;;;     and are never passed to SDL again. Surfaces are plain memory and are
;;;     still freed.
;;; Using a dead resource is an error naming the call.
;;;
;;; Errors. A failing SDL call raises a CHICKEN error (kinds exn and sdl2)
;;; whose location is the Scheme procedure and whose message names the SDL
;;; call and carries SDL_GetError's text; image loading and saving also
;;; name the file: "IMG_LoadTexture: cannot load \"x.png\": <SDL's text>".
;;;
;;; Events. poll-event! returns #f when the queue is empty, else a list:
;;;   (quit)
;;;   (key-down KEY REPEAT?)   (key-up KEY REPEAT?)
;;;   (controller-button-down BUTTON) (controller-button-up BUTTON)
;;;   (controller-axis AXIS VALUE) (controller-added INDEX)
;;;   (controller-removed INSTANCE-ID)
;;;   (mouse-motion X Y)       (mouse-button-down BUTTON X Y)
;;;   (mouse-button-up BUTTON X Y)
;;;                            X, Y in the renderer's logical pixels (SDL
;;;                            maps a window's pointer through its logical
;;;                            size); mouse BUTTON left middle right x1 x2
;;;                            BUTTON and AXIS symbols of controller-buttons
;;;                            and controller-axes (SDL's enum order), or
;;;                            unknown
;;;   (other TYPE)             any other event, TYPE its SDL type number
;;; This is the library's one reader of SDL's event queue: (downstroke
;;; input) builds on it.
;;; KEY is a symbol: a..z, n-0..n-9, left right up down, return escape
;;; space tab backspace delete insert home end page-up page-down, lshift
;;; rshift lctrl rctrl lalt ralt lgui rgui, f1..f12, minus equals comma
;;; period slash semicolon, or unknown. push-key-event! queues a synthetic
;;; key event (tests, scripted input), push-quit-event! a quit event.

(module (downstroke sdl2)
  (;; subsystem
   init! quit! sdl-initialized? get-error get-ticks delay!
   current-video-driver
   ;; rects
   make-rect rect? rect-x rect-y rect-w rect-h
   ;; windows
   create-window! destroy-window! window? window-alive? window-size
   window-title-set! window-size-set! window-fullscreen-set! window-fullscreen?
   pref-path
   ;; renderers
   create-renderer! create-software-renderer! destroy-renderer! renderer?
   renderer-alive? renderer-software? renderer-output-size renderer-name
   ;; for sibling FFI modules (text, ...): the native SDL_Renderer*
   renderer-pointer
   render-set-logical-size! render-letterbox! render-logical-size render-scale render-scale-set!
   render-draw-color-set! render-draw-blend-mode-set!
   render-clear! render-fill-rect! render-draw-rect! render-copy!
   render-present! render-read-pixels
   ;; for (downstroke mapdraw): a tile layer's cells in one call
   render-tile-cells! render-batched render-batching? render-gl-batching? render-gl-quads
   ;; for (downstroke renderer): a run of entities drawn in one call
   render-sprite-walk!
   ;; textures
   img-load-texture! destroy-texture! texture? texture-alive? texture-size max-image-pixels
   texture-alpha-mod-set! texture-alpha-mod texture-blend-mode-set!
   texture-color-mod-set! texture-color-mod
   ;; surfaces
   create-rgba-surface! free-surface! surface? surface-alive? surface-size
   img-save-png! img-load-surface! rgba-pixels->surface! surface-pixels
   ;; bookkeeping
   live-resource-counts
   ;; events
   poll-event! poll-events! push-key-event! push-quit-event!
   key-symbols keycode->key key->keycode controller-buttons controller-axes)

  (import (downstroke keywords) (downstroke media-header))
  (import scheme (chicken base) (chicken foreign) (chicken condition)
          (chicken gc) (chicken format) (chicken bitwise) (chicken fixnum) srfi-4
          )

  (foreign-declare #<<EOF
#include <math.h>
#include <SDL.h>
#include <SDL_image.h>

static SDL_Event downstroke_event;

/* SDL's renderers never use a depth buffer, but SDL asks for one by
   default; in the browser a WebGL canvas with one has it cleared every
   frame, for nothing (docs/performance.org, "Where the platformer's frame
   goes"). So the browser build asks for none before it makes a renderer. */
static void downstroke_no_depth_buffer(void) {
#ifdef __EMSCRIPTEN__
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
#endif
}

/* The one place the library reads SDL's event queue. */
static int downstroke_poll(void) {
  if (SDL_PollEvent(&downstroke_event)) return (int)downstroke_event.type;
  return -1;
}

/* A field of the event just polled. */
static int downstroke_ev_int(int what) {
  SDL_Event *e = &downstroke_event;
  switch (what) {
  case 0: return e->key.keysym.sym;
  case 1: return e->key.repeat != 0;
  case 2: return e->cbutton.button;
  case 3: return e->caxis.axis;
  case 4: return e->caxis.value;
  case 5: return e->cdevice.which;
  case 6: return e->motion.x;
  case 7: return e->motion.y;
  case 8: return e->button.button;
  case 9: return e->button.x;
  case 10: return e->button.y;
  }
  return 0;
}

static int downstroke_push_key(int down, int keycode, int repeat) {
  SDL_Event e;
  SDL_zero(e);
  e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
  e.key.timestamp = SDL_GetTicks();
  e.key.state = down ? SDL_PRESSED : SDL_RELEASED;
  e.key.repeat = repeat ? 1 : 0;
  e.key.keysym.sym = (SDL_Keycode)keycode;
  e.key.keysym.scancode = SDL_GetScancodeFromKey((SDL_Keycode)keycode);
  e.key.keysym.mod = KMOD_NONE;
  return SDL_PushEvent(&e);
}

static int downstroke_push_quit(void) {
  SDL_Event e;
  SDL_zero(e);
  e.type = SDL_QUIT;
  e.quit.timestamp = SDL_GetTicks();
  return SDL_PushEvent(&e);
}

static void downstroke_letterbox(SDL_Renderer *r, int lw, int lh) {
  int w, h, v, off;
  float want, real, scale;
  SDL_Rect bars[2];
  if (lw <= 0 || lh <= 0 || SDL_GetRendererOutputSize(r, &w, &h) < 0 || w <= 0 || h <= 0) return;
  want = (float)lw / lh;
  real = (float)w / h;
  if (SDL_fabs(want - real) < 0.0001) return;
  if (want > real) {
    scale = (float)w / lw;
    v = (int)SDL_floor(lh * scale);
    off = (h - v) / 2;
    bars[0].x = 0; bars[0].y = 0; bars[0].w = w; bars[0].h = off;
    bars[1].x = 0; bars[1].y = off + v; bars[1].w = w; bars[1].h = h - off - v;
  } else {
    scale = (float)h / lh;
    v = (int)SDL_floor(lw * scale);
    off = (w - v) / 2;
    bars[0].x = 0; bars[0].y = 0; bars[0].w = off; bars[0].h = h;
    bars[1].x = off + v; bars[1].y = 0; bars[1].w = w - off - v; bars[1].h = h;
  }
  SDL_RenderSetScale(r, 1.0f, 1.0f);
  SDL_RenderSetViewport(r, NULL);
  SDL_SetRenderDrawBlendMode(r, SDL_BLENDMODE_NONE);
  SDL_SetRenderDrawColor(r, 0, 0, 0, 255);
  SDL_RenderFillRects(r, bars, 2);
  SDL_RenderSetLogicalSize(r, lw, lh);
}

/* Where every rect enters SDL. Its numbers arrive as doubles (whatever
   real a game computed: huge, infinite, NaN) and leave as the ints SDL
   takes; a span with nothing in it, or a NaN, is not drawn.

   A filled or outlined rect is one colour, so cutting it changes nothing
   that can be seen: each span [p, p + size) is floored at both ends and
   cut to [-limit, limit], limit at most 2^23 (SDL turns rects into
   floats, which hold every integer below 2^24) and at most 2^29 / scale
   (SDL's software renderer multiplies by the renderer's scale in ints),
   both far outside any window. */
/* floor(v) for v well inside the int range (most rects are whole already) */
static int ds_floor(double v) {
  int i = (int)v;
  return (double)i > v ? i - 1 : i;
}

static int ds_span(double p, double size, double limit, int *lo, int *len) {
  double a = p, b = p + size;
  int ia, ib;
  if (!(a < b)) return 0;
  if (a < -limit) a = -limit;
  if (b > limit) b = limit;
  ia = ds_floor(a); ib = ds_floor(b);
  if (ia >= ib) return 0;
  *lo = ia; *len = ib - ia;
  return 1;
}

static double ds_dest_limit(SDL_Renderer *r) {
  float sx = 1.0f, sy = 1.0f;
  double s;
  SDL_RenderGetScale(r, &sx, &sy);
  s = sx > sy ? sx : sy;
  if (!(s > 1.0)) s = 1.0;
  return s > 64.0 ? 536870912.0 / s : 8388608.0;
}

static void ds_q_flush(void);
static int ds_q_copy(SDL_Renderer *r, SDL_Texture *t, SDL_Rect *src, SDL_Rect *dst, int h, int v);
static int ds_q_copy_ex(SDL_Renderer *r, SDL_Texture *t, SDL_Rect *src, SDL_Rect *dst, double angle,
                        int h, int v);

/* Fill (which 0) or outline (1) a rect, or the whole target. */
static int downstroke_rect(SDL_Renderer *r, int which, int whole,
                           double x, double y, double w, double h) {
  SDL_Rect rc;
  double limit = ds_dest_limit(r);
  ds_q_flush();
  if (!whole && !(ds_span(x, w, limit, &rc.x, &rc.w) && ds_span(y, h, limit, &rc.y, &rc.h)))
    return 0;
  return which ? SDL_RenderDrawRect(r, whole ? NULL : &rc)
               : SDL_RenderFillRect(r, whole ? NULL : &rc);
}

/* A copy stretches its source over its destination, so cutting the
   destination alone would squeeze the picture. A copy near the view (no
   edge more than DS_REACH px beyond it) goes to SDL as it is; for any
   other the answer is 2, and render-copy! cuts it on whole source pixels
   first. A turned copy that far is not drawn (answer 0): its picture
   cannot be cut that way. */
#define DS_REACH 16384.0

static int ds_copy_rect(SDL_Renderer *r, SDL_Texture *t, SDL_Rect *src, SDL_Rect *dst,
                        double angle, int flip) {
  ds_q_flush();
  if (flip == 0 && angle == 0.0) return SDL_RenderCopy(r, t, src, dst);
  return SDL_RenderCopyEx(r, t, src, dst, angle, NULL, (SDL_RendererFlip)flip);
}

/* A copy; use_src / use_dst false: NULL (the whole texture / target).
   A source is cut to +-2^24, beyond any texture. */
static int downstroke_copy(SDL_Renderer *r, SDL_Texture *t, int use_src,
                           double sx, double sy, double sw, double sh, int use_dst,
                           double dx, double dy, double dw, double dh,
                           double angle, int hflip, int vflip) {
  SDL_Rect src, dst, vp;
  int flip = (hflip ? SDL_FLIP_HORIZONTAL : 0) | (vflip ? SDL_FLIP_VERTICAL : 0);
  double ax = dx, bx = dx + dw, ay = dy, by = dy + dh;
  if (use_src && !(ds_span(sx, sw, 16777216.0, &src.x, &src.w)
                   && ds_span(sy, sh, 16777216.0, &src.y, &src.h)))
    return 0;
  if (!use_dst) return ds_copy_rect(r, t, use_src ? &src : NULL, NULL, angle, flip);
  if (!(ax < bx) || !(ay < by)) return 0;
  SDL_RenderGetViewport(r, &vp);
  if (!(ax >= -DS_REACH && bx <= vp.w + DS_REACH && ay >= -DS_REACH && by <= vp.h + DS_REACH))
    return angle == 0.0 ? 2 : 0;
  dst.x = ds_floor(ax); dst.y = ds_floor(ay);
  dst.w = ds_floor(bx) - dst.x; dst.h = ds_floor(by) - dst.y;
  if (dst.w <= 0 || dst.h <= 0) return 0;
  return ds_copy_rect(r, t, use_src ? &src : NULL, &dst, angle, flip);
}

/* The usual rect and copy, whose numbers render-fill-rect!, render-draw-rect!
   and render-copy! found to be small fixnums near the view: as they are. */
static int downstroke_rect_ints(SDL_Renderer *r, int which, int x, int y, int w, int h) {
  SDL_Rect rc = { x, y, w, h };
  ds_q_flush();
  return which ? SDL_RenderDrawRect(r, &rc) : SDL_RenderFillRect(r, &rc);
}

static int downstroke_copy_ints(SDL_Renderer *r, SDL_Texture *t, int use_src,
                                int sx, int sy, int sw, int sh, int dx, int dy, int dw, int dh,
                                double angle, int hflip, int vflip) {
  SDL_Rect src = { sx, sy, sw, sh }, dst = { dx, dy, dw, dh };
  int flip = (hflip ? SDL_FLIP_HORIZONTAL : 0) | (vflip ? SDL_FLIP_VERTICAL : 0);
  if (use_src && (angle == 0.0 ? ds_q_copy(r, t, &src, &dst, hflip, vflip)
                                : ds_q_copy_ex(r, t, &src, &dst, angle, hflip, vflip)))
    return 0;
  return ds_copy_rect(r, t, use_src ? &src : NULL, &dst, angle, flip);
}

/* The view in the renderer's logical pixels. */
static void downstroke_view(SDL_Renderer *r, int *w, int *h) {
  SDL_Rect vp;
  SDL_RenderGetViewport(r, &vp);
  *w = vp.w; *h = vp.h;
}

#include "shell/tiles.c"

/* The copy queue (render-batched): between ds_q_begin and ds_q_end, a
   copy of a source inside its texture (turned: on opengl only), on the
   accelerated renderer being batched, is kept as a quad whose vertices carry the
   colour and alpha the copy is drawn with (the texture's modulation when
   it was queued, as SDL's own copy takes it); a run of one texture goes
   to SDL as one SDL_RenderGeometry call (tiles.c's ds_batch_send).
   Anything else drawn on the renderer sends the run first (ds_q_flush:
   sdl2.scm calls it wherever a renderer or texture is used), so the
   order of what is drawn never changes. */
static SDL_Renderer *ds_q_r = NULL;
static SDL_Texture *ds_q_t = NULL;
static int ds_q_n = 0, ds_q_tw = 1, ds_q_th = 1, ds_q_status = 0;
static int ds_q_turns = 0;            /* turned copies join the queue (ds_q_copy_turned) */

static void ds_q_flush(void) {
  if (ds_q_n > 0) {
    int st = ds_batch_send(ds_q_r, ds_q_t, ds_q_n);
    if (st < 0) ds_q_status = st;
  }
  ds_q_n = 0;
}

/* Turned copies are queued on SDL's opengl renderer only, whose
   SDL_RenderCopyEx (SDL 2.26) is the geometry ds_q_copy_turned repeats. */
static int ds_q_turning_renderer(SDL_Renderer *r) {
#if defined(__EMSCRIPTEN__)
  (void)r;
  return 0;
#else
  SDL_RendererInfo info;
  return SDL_GetRendererInfo(r, &info) == 0 && info.name && SDL_strcmp(info.name, "opengl") == 0;
#endif
}

static void ds_q_begin(SDL_Renderer *r) {
  ds_q_flush(); ds_q_r = r; ds_q_t = NULL; ds_q_status = 0;
  ds_q_turns = ds_q_turning_renderer(r);
}

static int ds_q_end(void) {
  int st;
  ds_q_flush();
  ds_q_r = NULL; ds_q_t = NULL;
  st = ds_q_status; ds_q_status = 0;
  return st;
}

/* 1 when the queue has room for a copy of src of t (a run of t open,
   src inside it); 0 when the copy is to go to SDL (the run so far sent). */
static inline int ds_q_room(SDL_Renderer *r, SDL_Texture *t, const SDL_Rect *src, const SDL_Rect *dst) {
  if (r != ds_q_r || !src || !dst || dst->w <= 0 || dst->h <= 0) return 0;
  if (t != ds_q_t || ds_q_n == DS_BATCH_QUADS) {
    ds_q_flush();
    ds_q_t = t;
    if (SDL_QueryTexture(t, NULL, NULL, &ds_q_tw, &ds_q_th) < 0 || ds_q_tw <= 0 || ds_q_th <= 0) {
      ds_q_t = NULL;
      return 0;
    }
  }
  if (src->x < 0 || src->y < 0 || src->w <= 0 || src->h <= 0
      || src->x + src->w > ds_q_tw || src->y + src->h > ds_q_th) { ds_q_flush(); return 0; }
  return 1;
}

static inline void ds_q_color(SDL_Color c) {
  SDL_Vertex *p = &ds_batch_verts[ds_q_n * 4];
  p[0].color = c; p[1].color = c; p[2].color = c; p[3].color = c;
}

/* 1 when the copy was queued, its vertices coloured c. */
static inline int ds_q_copy_colored(SDL_Renderer *r, SDL_Texture *t, const SDL_Rect *src, const SDL_Rect *dst,
                             int h, int v, SDL_Color c) {
  if (!ds_q_room(r, t, src, dst)) return 0;
  ds_batch_quad_to(ds_q_n, ds_q_tw, ds_q_th, src->x, src->y, src->w, src->h,
                   dst->x, dst->y, dst->w, dst->h, h, v);
  ds_q_color(c);
  ds_q_n++;
  return 1;
}

/* A turned copy (SDL_RenderCopyEx about the centre of dst, h and v its
   flips), queued on the opengl renderer as the four corners SDL 2.26
   computes for it there: SDL turns a copy on the CPU, in floats, with
   SDL_sinf and SDL_cosf, and draws it as two triangles of the corners
   TL TR BL and TR BL BR. Every operation below is SDL's, in its order,
   so the corners are SDL's to the bit (shell/tests/tile-batch-test.scm
   compares crowds drawn both ways in a real window). An angle of a whole
   number of turns without a flip is SDL's plain copy. */
static int ds_q_copy_turned(SDL_Renderer *r, SDL_Texture *t, const SDL_Rect *src, const SDL_Rect *dst,
                            double angle, int h, int v, SDL_Color c) {
  float minx, miny, maxx, maxy, centerx, centery, minu, minv, maxu, maxv, rad, s, co;
  float s_minx, s_miny, s_maxx, s_maxy, c_minx, c_miny, c_maxx, c_maxy;
  SDL_Vertex *p;
  if (!ds_q_turns || !(angle > -1e9 && angle < 1e9) || !ds_q_room(r, t, src, dst)) return 0;
  if (!h && !v && (int)(angle / 360) == angle / 360) return ds_q_copy_colored(r, t, src, dst, 0, 0, c);
  minu = (float)src->x / (float)ds_q_tw;
  minv = (float)src->y / (float)ds_q_th;
  maxu = (float)(src->x + src->w) / (float)ds_q_tw;
  maxv = (float)(src->y + src->h) / (float)ds_q_th;
  centerx = (float)dst->w / 2.0f + (float)dst->x;
  centery = (float)dst->h / 2.0f + (float)dst->y;
  minx = h ? (float)dst->x + (float)dst->w : (float)dst->x;
  maxx = h ? (float)dst->x : (float)dst->x + (float)dst->w;
  miny = v ? (float)dst->y + (float)dst->h : (float)dst->y;
  maxy = v ? (float)dst->y : (float)dst->y + (float)dst->h;
  rad = (float)((M_PI * angle) / 180.0);
  s = SDL_sinf(rad);
  co = SDL_cosf(rad);
  s_minx = s * (minx - centerx); s_miny = s * (miny - centery);
  s_maxx = s * (maxx - centerx); s_maxy = s * (maxy - centery);
  c_minx = co * (minx - centerx); c_miny = co * (miny - centery);
  c_maxx = co * (maxx - centerx); c_maxy = co * (maxy - centery);
  /* the queue's corner order, TL TR BL BR (ds_batch_send's triangles) */
  p = &ds_batch_verts[ds_q_n * 4];
  p[0].position.x = (c_minx - s_miny) + centerx; p[0].position.y = (s_minx + c_miny) + centery;
  p[1].position.x = (c_maxx - s_miny) + centerx; p[1].position.y = (s_maxx + c_miny) + centery;
  p[2].position.x = (c_minx - s_maxy) + centerx; p[2].position.y = (s_minx + c_maxy) + centery;
  p[3].position.x = (c_maxx - s_maxy) + centerx; p[3].position.y = (s_maxx + c_maxy) + centery;
  p[0].tex_coord.x = minu; p[0].tex_coord.y = minv;
  p[1].tex_coord.x = maxu; p[1].tex_coord.y = minv;
  p[2].tex_coord.x = minu; p[2].tex_coord.y = maxv;
  p[3].tex_coord.x = maxu; p[3].tex_coord.y = maxv;
  ds_q_color(c);
  ds_q_n++;
  return 1;
}

/* The texture's modulation, as SDL's copy would draw it. */
static SDL_Color ds_texture_modulation(SDL_Texture *t) {
  SDL_Color c = { 255, 255, 255, 255 };
  SDL_GetTextureColorMod(t, &c.r, &c.g, &c.b);
  SDL_GetTextureAlphaMod(t, &c.a);
  return c;
}

static int ds_q_copy(SDL_Renderer *r, SDL_Texture *t, SDL_Rect *src, SDL_Rect *dst, int h, int v) {
  if (r != ds_q_r) return 0;
  return ds_q_copy_colored(r, t, src, dst, h, v, ds_texture_modulation(t));
}

static int ds_q_copy_ex(SDL_Renderer *r, SDL_Texture *t, SDL_Rect *src, SDL_Rect *dst, double angle,
                        int h, int v) {
  if (r != ds_q_r || !ds_q_turns) return 0;
  return ds_q_copy_turned(r, t, src, dst, angle, h, v, ds_texture_modulation(t));
}

#include "shell/sprites.c"
EOF
)

  ;;; ------------------------------------------------------------------
  ;;; Errors

  (define get-error (foreign-lambda c-string "SDL_GetError"))

  (define (sdl-error who call #!optional detail)
    (signal
     (make-composite-condition
      (make-property-condition
       'exn 'location who
       'message (if detail
                    (sprintf "~a: ~a: ~a" call detail (get-error))
                    (sprintf "~a: ~a" call (get-error)))
       'arguments '())
      (make-property-condition 'sdl2 'call call))))

  ;; SDL's int returns: negative is failure.
  (define (check-status who call status)
    (when (< status 0) (sdl-error who call))
    (void))

  ;;; ------------------------------------------------------------------
  ;;; Subsystem. `generation` counts init!/quit! cycles, so resources made
  ;;; before a quit! are known to be gone.

  (define initialized? #f)
  (define generation 0)

  (define (sdl-initialized?) initialized?)

  ;; (init!) or (init! '(video events timer)); video is the default.
  (define (init! #!optional (subsystems '(video)))
    (let ((flags (foldl (lambda (acc s)
                          (bitwise-ior acc
                                        (case s
                                          ((video) (foreign-value "SDL_INIT_VIDEO" unsigned-int))
                                          ((events) (foreign-value "SDL_INIT_EVENTS" unsigned-int))
                                          ((timer) (foreign-value "SDL_INIT_TIMER" unsigned-int))
                                          ((audio) (foreign-value "SDL_INIT_AUDIO" unsigned-int))
                                          ((game-controller)
                                           (foreign-value "SDL_INIT_GAMECONTROLLER" unsigned-int))
                                          (else (error 'init! "unknown SDL subsystem" s)))))
                        0 subsystems)))
      (check-status 'init! "SDL_Init"
                    ((foreign-lambda int "SDL_Init" unsigned-int) flags))
      ;; PNG support; IMG_Init answers the formats it could set up.
      (let ((png (foreign-value "IMG_INIT_PNG" int)))
        (when (zero? (bitwise-and png ((foreign-lambda int "IMG_Init" int) png)))
          (sdl-error 'init! "IMG_Init")))
      (unless initialized? (set! generation (+ generation 1)))
      (set! initialized? #t)
      (void)))

  (define (quit!)
    (when initialized?
      ((foreign-lambda void "IMG_Quit"))
      ((foreign-lambda void "SDL_Quit"))
      (set! initialized? #f))
    (void))

  (define get-ticks (foreign-lambda unsigned-integer32 "SDL_GetTicks"))

  ;; The name of the video driver SDL is using ("x11", "wayland",
  ;; "dummy", ...), or #f when video is not initialised.
  (define current-video-driver
    (foreign-lambda c-string "SDL_GetCurrentVideoDriver"))
  (define (delay! ms) ((foreign-lambda void "SDL_Delay" unsigned-integer32) ms))

  ;;; ------------------------------------------------------------------
  ;;; Rects

  (define-record-type rect
    (make-rect x y w h)
    rect?
    (x rect-x) (y rect-y) (w rect-w) (h rect-h))

  ;;; ------------------------------------------------------------------
  ;;; Resource records. `ptr` is the native pointer, #f once destroyed.

  (define-record-type window
    (%make-window ptr generation renderer)
    window?
    (ptr window-ptr window-ptr-set!)
    (generation window-generation)
    (renderer window-renderer window-renderer-set!))

  (define-record-type surface
    (%make-surface ptr renderer)
    surface?
    (ptr surface-ptr surface-ptr-set!)
    (renderer surface-renderer surface-renderer-set!))

  ;; parent: the window or surface it draws to.
  (define-record-type renderer
    (%make-renderer ptr generation parent software?)
    renderer?
    (ptr renderer-ptr renderer-ptr-set!)
    (generation renderer-generation)
    (parent renderer-parent)
    (software? renderer-software?))

  (define-record-type texture
    (%make-texture ptr renderer width height)
    texture?
    (ptr texture-ptr texture-ptr-set!)
    (renderer texture-renderer)
    (width texture-width)
    (height texture-height))

  (define (current? gen) (and initialized? (= gen generation)))

  (define (window-alive? w)
    (and (window-ptr w) (current? (window-generation w))))

  (define (renderer-alive? r)
    (and (renderer-ptr r)
         (current? (renderer-generation r))
         (let ((p (renderer-parent r)))
           (if (window? p) (window-alive? p) (surface-alive? p)))))

  (define (texture-alive? t)
    (and (texture-ptr t) (renderer-alive? (texture-renderer t))))

  (define (surface-alive? s) (and (surface-ptr s) #t))

  (define (live-window who w)
    (unless (and (window? w) (window-alive? w))
      (error who (sprintf "~a: not a live window" who) w))
    (window-ptr w))

  ;; (render-batched r thunk): calls thunk with r's copies of a source
  ;; inside its texture (turned ones on the opengl renderer only) kept in
  ;; C and sent as one SDL_RenderGeometry call per run of one texture (the
  ;; copy queue of the C above), on an accelerated renderer; as a plain call on a
  ;; software one (SDL's software renderer draws geometry otherwise than
  ;; its copies). Whatever else uses the renderer or a texture meanwhile
  ;; (live-renderer, live-texture and the C helpers flush) sends the
  ;; queued run first, so nothing changes order.
  (define batching? #f)
  (define q-flush! (foreign-lambda void "ds_q_flush"))
  (define-inline (flush-batch!) (when batching? (q-flush!)))
  (define (live-renderer who r)
    (flush-batch!)
    (live-renderer* who r))
  (define (live-renderer* who r)
    (unless (and (renderer? r) (renderer-alive? r))
      (error who (sprintf "~a: not a live renderer" who) r))
    (renderer-ptr r))

  ;; The SDL_Renderer* of a live renderer (an error naming `who` otherwise),
  ;; for other modules that call SDL libraries on it, such as SDL_ttf.
  (define (renderer-pointer who r) (live-renderer who r))

  ;; (render-batching? #f): render-batched only calls its thunk (to
  ;; compare the two, as shell/tests/tile-batch-test.scm does).
  (define render-batching? (make-parameter #t))
  ;; (render-gl-batching? #f): runs of quads go to SDL_RenderGeometry even
  ;; on the opengl renderer, where shell/gl-batch.c draws them itself;
  ;; render-gl-quads: how many quads it has drawn so (both for the
  ;; comparisons of shell/tests/gl-batch-test.scm).
  (define render-gl-batching? (make-parameter #t))
  (define (render-gl-quads) (inexact->exact (foreign-value "ds_gl_quads" double)))
  (define gl-allow! (foreign-lambda void "ds_gl_allow" bool))
  (define (render-batched r thunk)
    (if (or batching? (renderer-software? r) (not (render-batching?)))
        (thunk)
        (let ((rp (live-renderer 'render-batched r)))
          (dynamic-wind
           (lambda ()
             ((foreign-lambda void "ds_q_begin" c-pointer) rp)
             (gl-allow! (render-gl-batching?))
             (set! batching? #t))
           thunk
           (lambda ()
             (set! batching? #f)
             (check-status 'render-batched "SDL_RenderGeometry"
                           ((foreign-lambda int "ds_q_end"))))))))



  (define (live-texture who t)
    (flush-batch!)
    (live-texture* who t))
  ;; without sending the queued copies: render-copy!'s, which may queue one
  (define (live-texture* who t)
    (unless (and (texture? t) (texture-alive? t))
      (error who (sprintf "~a: not a live texture" who) t))
    (texture-ptr t))

  (define (live-surface who s)
    (unless (and (surface? s) (surface-alive? s))
      (error who (sprintf "~a: not a live surface" who) s))
    (surface-ptr s))

  ;;; ------------------------------------------------------------------
  ;;; Live resource counts. (live-resource-counts) -> an alist
  ;;;   ((windows . N) (renderers . N) (textures . N) (surfaces . N))
  ;;; of the records made by this module that still hold their native
  ;;; pointer: +1 when one is created, -1 when its destroy procedure (or its
  ;;; finalizer) first runs. A texture freed implicitly by SDL (its renderer
  ;;; destroyed, or quit!) stays counted until its record is destroyed or
  ;;; collected; the engine destroys every texture it made. For leak checks.

  (define count-windows 0)
  (define count-renderers 0)
  (define count-textures 0)
  (define count-surfaces 0)

  (define (live-resource-counts)
    (list (cons 'windows count-windows)
          (cons 'renderers count-renderers)
          (cons 'textures count-textures)
          (cons 'surfaces count-surfaces)))

  ;;; ------------------------------------------------------------------
  ;;; Explicitly destroyed records and the GC. CHICKEN cannot unregister a
  ;;; finalizer, so a record destroyed by hand stays registered until a
  ;;; major GC finds it dead; until then it (and its table entry) counts as
  ;;; live, and a game that replaces a texture every frame makes CHICKEN
  ;;; grow its heap and finalizer table again and again (measured: 18 MB ->
  ;;; 41 MB RSS over 150,000 frames). So every `collect-every` explicit
  ;;; destroys run one major GC (a few ms at most, once per thousands of
  ;;; frames), which releases those records; memory then stays flat.
  ;;; Destroys run by a finalizer do not count (no GC from a finalizer).

  (define collect-every 2048)
  (define destroyed-since-gc 0)
  (define finalizing? #f)

  ;; Called by each destroy procedure once its resource is freed.
  (define (note-destroyed!)
    (unless finalizing?
      (set! destroyed-since-gc (+ destroyed-since-gc 1))
      (when (>= destroyed-since-gc collect-every)
        (set! destroyed-since-gc 0)
        (gc #t))))

  (define (finalizer proc)
    (lambda (x)
      (dynamic-wind (lambda () (set! finalizing? #t))
                    (lambda () (proc x))
                    (lambda () (set! finalizing? #f)))))

  ;;; ------------------------------------------------------------------
  ;;; Destruction: idempotent, and the finalizers call the same procedures.

  (define (destroy-texture! t)
    (let ((p (texture-ptr t)))
      (when p
        (flush-batch!)
        (texture-ptr-set! t #f)
        (set! count-textures (- count-textures 1))
        ;; A dead renderer has already freed its textures.
        (when (renderer-alive? (texture-renderer t))
          ((foreign-lambda void "SDL_DestroyTexture" c-pointer) p))
        (note-destroyed!)))
    (void))

  (define (destroy-renderer! r)
    (let ((p (renderer-ptr r))
          (alive (renderer-alive? r)))
      (when p
        (flush-batch!)
        (renderer-ptr-set! r #f)
        (set! count-renderers (- count-renderers 1))
        (when alive
          ((foreign-lambda void "SDL_DestroyRenderer" c-pointer) p))
        (note-destroyed!)))
    (void))

  (define (destroy-window! w)
    (let ((p (window-ptr w))
          (alive (window-alive? w)))
      (when p
        (let ((r (window-renderer w)))
          (when r (destroy-renderer! r) (window-renderer-set! w #f)))
        (window-ptr-set! w #f)
        (set! count-windows (- count-windows 1))
        (when alive
          ((foreign-lambda void "SDL_DestroyWindow" c-pointer) p))
        (note-destroyed!)))
    (void))

  (define (free-surface! s)
    (let ((p (surface-ptr s)))
      (when p
        (let ((r (surface-renderer s)))
          (when r (destroy-renderer! r) (surface-renderer-set! s #f)))
        (surface-ptr-set! s #f)
        (set! count-surfaces (- count-surfaces 1))
        ((foreign-lambda void "SDL_FreeSurface" c-pointer) p)
        (note-destroyed!)))
    (void))

  ;;; ------------------------------------------------------------------
  ;;; Windows

  (define (window-flag sym)
    (case sym
      ((shown) (foreign-value "SDL_WINDOW_SHOWN" unsigned-int))
      ((hidden) (foreign-value "SDL_WINDOW_HIDDEN" unsigned-int))
      ((resizable) (foreign-value "SDL_WINDOW_RESIZABLE" unsigned-int))
      ((fullscreen) (foreign-value "SDL_WINDOW_FULLSCREEN" unsigned-int))
      ((fullscreen-desktop) (foreign-value "SDL_WINDOW_FULLSCREEN_DESKTOP" unsigned-int))
      ((borderless) (foreign-value "SDL_WINDOW_BORDERLESS" unsigned-int))
      ((allow-high-dpi) (foreign-value "SDL_WINDOW_ALLOW_HIGHDPI" unsigned-int))
      (else (error 'create-window! "unknown window flag" sym))))

  ;; (create-window! title x y w h #!optional flags): x and y are pixels or
  ;; the symbols centered / undefined; flags a list of symbols.
  (define (create-window! title x y w h #!optional (flags '(shown)))
    (let* ((pos (lambda (v)
                  (case v
                    ((centered) (foreign-value "SDL_WINDOWPOS_CENTERED" int))
                    ((undefined) (foreign-value "SDL_WINDOWPOS_UNDEFINED" int))
                    (else v))))
           (p ((foreign-lambda c-pointer "SDL_CreateWindow"
                               c-string int int int int unsigned-int)
               title (pos x) (pos y) w h
               (foldl (lambda (acc f) (bitwise-ior acc (window-flag f))) 0 flags))))
      (unless p (sdl-error 'create-window! "SDL_CreateWindow"))
      (set! count-windows (+ count-windows 1))
      (set-finalizer! (%make-window p generation #f) (finalizer destroy-window!))))

  (define (window-size w)
    (let ((p (live-window 'window-size w)))
      (let-location ((wi int 0) (hi int 0))
        ((foreign-lambda void "SDL_GetWindowSize" c-pointer (c-pointer int) (c-pointer int))
         p (location wi) (location hi))
        (values wi hi))))

  (define (window-size-set! w width height)
    (unless (and (exact-integer? width) (exact-integer? height) (< 0 width 65536) (< 0 height 65536))
      (error 'window-size-set! "the size must be two positive integers" width height))
    ((foreign-lambda void "SDL_SetWindowSize" c-pointer int int)
     (live-window 'window-size-set! w) width height))

  ;; Fullscreen at the desktop's resolution (no video mode change); the
  ;; renderer's logical size letterboxes the game inside it.
  (define (window-fullscreen-set! w on?)
    (check-status 'window-fullscreen-set! "SDL_SetWindowFullscreen"
                  ((foreign-lambda int "SDL_SetWindowFullscreen" c-pointer unsigned-int)
                   (live-window 'window-fullscreen-set! w)
                   (if on? (foreign-value "SDL_WINDOW_FULLSCREEN_DESKTOP" unsigned-int) 0))))

  (define (window-fullscreen? w)
    (not (zero? (bitwise-and ((foreign-lambda unsigned-int "SDL_GetWindowFlags" c-pointer)
                              (live-window 'window-fullscreen? w))
                             (foreign-value "SDL_WINDOW_FULLSCREEN" unsigned-int)))))

  ;; The per-user directory SDL gives an application for its files
  ;; (SDL_GetPrefPath: on Linux $XDG_DATA_HOME/ORG/APP/, else
  ;; ~/.local/share/ORG/APP/), created if missing; needs no init!.
  (define (pref-path org app)
    (unless (and (string? org) (string? app) (> (string-length app) 0))
      (error 'pref-path "org and app must be strings (app not empty)" org app))
    (let ((p ((foreign-lambda* c-string ((c-string org) (c-string app))
                "static char buf[4096];
                 char *p = SDL_GetPrefPath(org, app);
                 if (!p) C_return(NULL);
                 if (SDL_strlcpy(buf, p, sizeof buf) >= sizeof buf) {
                   SDL_free(p); SDL_SetError(\"the path is too long\"); C_return(NULL);
                 }
                 SDL_free(p);
                 C_return(buf);")
              org app)))
      (unless p (sdl-error 'pref-path "SDL_GetPrefPath" (sprintf "org ~s, app ~s" org app)))
      p))

  (define (window-title-set! w title)
    ((foreign-lambda void "SDL_SetWindowTitle" c-pointer c-string)
     (live-window 'window-title-set! w) title))

  ;;; ------------------------------------------------------------------
  ;;; Renderers

  (define sdl-create-renderer
    (foreign-lambda c-pointer "SDL_CreateRenderer" c-pointer int unsigned-int))

  ;; An accelerated renderer for the window, falling back to SDL's software
  ;; renderer when no accelerated one can be made. vsync?: asks for
  ;; presentation synchronised with the display (accelerated only).
  (define/keywords (create-renderer! w #!key (vsync? #f))
    (let ((wp (live-window 'create-renderer! w)))
      (when (window-renderer w)
        (error 'create-renderer! "the window already has a renderer" w))
      (let* ((accel (bitwise-ior
                     (foreign-value "SDL_RENDERER_ACCELERATED" unsigned-int)
                     (if vsync? (foreign-value "SDL_RENDERER_PRESENTVSYNC" unsigned-int) 0)))
             (p (begin ((foreign-lambda void "downstroke_no_depth_buffer"))
                       (sdl-create-renderer wp -1 accel)))
             (software? (not p))
             (p (or p (sdl-create-renderer
                       wp -1 (foreign-value "SDL_RENDERER_SOFTWARE" unsigned-int)))))
        (unless p (sdl-error 'create-renderer! "SDL_CreateRenderer"))
        (set! count-renderers (+ count-renderers 1))
        (let ((r (%make-renderer p generation w software?)))
          (window-renderer-set! w r)
          (set-finalizer! r (finalizer destroy-renderer!))))))

  ;; A software renderer drawing into a surface: headless drawing, tests,
  ;; screenshots. The surface must outlive it (free-surface! destroys it).
  (define (create-software-renderer! s)
    (let ((sp (live-surface 'create-software-renderer! s)))
      (unless initialized? (error 'create-software-renderer! "SDL is not initialized (init!)"))
      (when (surface-renderer s)
        (error 'create-software-renderer! "the surface already has a renderer" s))
      (let ((p ((foreign-lambda c-pointer "SDL_CreateSoftwareRenderer" c-pointer) sp)))
        (unless p (sdl-error 'create-software-renderer! "SDL_CreateSoftwareRenderer"))
        (set! count-renderers (+ count-renderers 1))
        (let ((r (%make-renderer p generation s #t)))
          (surface-renderer-set! s r)
          (set-finalizer! r (finalizer destroy-renderer!))))))

  ;; The size in pixels of what the renderer draws to, ignoring any logical size.
  (define (renderer-output-size r)
    (let ((p (live-renderer 'renderer-output-size r)))
      (let-location ((w int 0) (h int 0))
        (check-status 'renderer-output-size "SDL_GetRendererOutputSize"
                      ((foreign-lambda int "SDL_GetRendererOutputSize"
                                       c-pointer (c-pointer int) (c-pointer int))
                       p (location w) (location h)))
        (values w h))))

  ;; The name SDL gives the renderer's backend ("software", "opengl", ...).
  (define (renderer-name r)
    (let ((p (live-renderer 'renderer-name r)))
      (let ((name ((foreign-lambda* c-string ((c-pointer r))
                     "SDL_RendererInfo info;
                      if (SDL_GetRendererInfo((SDL_Renderer*)r, &info) < 0) C_return(NULL);
                      C_return(info.name);")
                   p)))
        (unless name (sdl-error 'renderer-name "SDL_GetRendererInfo"))
        name)))

  ;; Black bars around the game where the window's shape is not the
  ;; game's (a resized or fullscreen window): SDL's logical size centres
  ;; the game with its aspect kept (the same sums as SDL's letterbox), and
  ;; the scene's clear has filled the whole window; the bars are drawn over
  ;; the margins at the window's own scale, then the logical size is set
  ;; again. Nothing is drawn when the shapes agree.
  (define (render-letterbox! r lw lh)
    ((foreign-lambda void "downstroke_letterbox" c-pointer int int)
     (live-renderer 'render-letterbox! r) lw lh))

  (define (render-set-logical-size! r w h)
    (check-status 'render-set-logical-size! "SDL_RenderSetLogicalSize"
                  ((foreign-lambda int "SDL_RenderSetLogicalSize" c-pointer int int)
                   (live-renderer 'render-set-logical-size! r) w h)))

  ;; (values w h); 0 and 0 when no logical size is set.
  (define (render-logical-size r)
    (let ((p (live-renderer 'render-logical-size r)))
      (let-location ((w int 0) (h int 0))
        ((foreign-lambda void "SDL_RenderGetLogicalSize" c-pointer (c-pointer int) (c-pointer int))
         p (location w) (location h))
        (values w h))))

  ;; The renderer's drawing scale, (values sx sy); a logical size sets it.
  (define (render-scale r)
    (let ((p (live-renderer 'render-scale r)))
      (let-location ((sx float 1.0) (sy float 1.0))
        ((foreign-lambda void "SDL_RenderGetScale" c-pointer (c-pointer float) (c-pointer float))
         p (location sx) (location sy))
        (values sx sy))))

  ;; SDL's scale is a C float: from about 1e-38 to 3.4e38.
  (define (float-scale? v) (and (real? v) (finite? v) (<= 1e-38 v 3e38)))

  (define (render-scale-set! r sx sy)
    (unless (and (float-scale? sx) (float-scale? sy))
      (error 'render-scale-set! "the scale must be two positive finite numbers a float holds" sx sy))
    (check-status 'render-scale-set! "SDL_RenderSetScale"
                  ((foreign-lambda int "SDL_RenderSetScale" c-pointer float float)
                   (live-renderer 'render-scale-set! r) (exact->inexact sx) (exact->inexact sy))))

  (define (byte who v)
    (unless (and (fixnum? v) (<= 0 v 255))
      (error who "a colour component must be an integer 0..255" v))
    v)

  (define (render-draw-color-set! r red green blue #!optional (alpha 255))
    (check-status 'render-draw-color-set! "SDL_SetRenderDrawColor"
                  ((foreign-lambda int "SDL_SetRenderDrawColor"
                                   c-pointer unsigned-byte unsigned-byte unsigned-byte unsigned-byte)
                   (live-renderer 'render-draw-color-set! r)
                   (byte 'render-draw-color-set! red) (byte 'render-draw-color-set! green)
                   (byte 'render-draw-color-set! blue) (byte 'render-draw-color-set! alpha))))

  (define (blend-mode who sym)
    (case sym
      ((none) (foreign-value "SDL_BLENDMODE_NONE" int))
      ((blend) (foreign-value "SDL_BLENDMODE_BLEND" int))
      ((add) (foreign-value "SDL_BLENDMODE_ADD" int))
      ((mod) (foreign-value "SDL_BLENDMODE_MOD" int))
      (else (error who "unknown blend mode (none blend add mod)" sym))))

  ;; How fill-rect and draw-rect combine with what is drawn: a symbol,
  ;; none (the default: replace), blend, add or mod.
  (define (render-draw-blend-mode-set! r mode)
    (check-status 'render-draw-blend-mode-set! "SDL_SetRenderDrawBlendMode"
                  ((foreign-lambda int "SDL_SetRenderDrawBlendMode" c-pointer int)
                   (live-renderer 'render-draw-blend-mode-set! r)
                   (blend-mode 'render-draw-blend-mode-set! mode))))

  (define (render-clear! r)
    (check-status 'render-clear! "SDL_RenderClear"
                  ((foreign-lambda int "SDL_RenderClear" c-pointer)
                   (live-renderer 'render-clear! r))))

  ;; A rect's numbers as the C doubles downstroke_rect and downstroke_copy
  ;; turn into SDL's ints (above): any real, bignums and fractions included.
  (define-inline (c-real v) (if (or (fixnum? v) (flonum? v)) v (exact->inexact v)))

  (define rect-op
    (foreign-lambda int "downstroke_rect" c-pointer int bool double double double double))
  (define rect-op-ints
    (foreign-lambda int "downstroke_rect_ints" c-pointer int int int int int))

  ;; Fixnum edges within +-near-limit: passed on as they are (a map's
  ;; tiles, sprites and boxes near the view, hundreds a frame, cost what
  ;; they cost before any of this); the rest go through the cuts above.
  ;; The same number as DS_REACH.
  (define near-limit 16384)

  (define-inline (near-span? p size)
    (and (fixnum? p) (fixnum? size) (fx>= p (fxneg near-limit)) (fx<= p near-limit)
         (fx> size 0) (fx<= size near-limit) (fx<= (fx+ p size) near-limit)))

  (define (do-rect who call which r rect)
    (check-status who call
                  (if rect
                      (let ((x (rect-x rect)) (y (rect-y rect)) (w (rect-w rect)) (h (rect-h rect)))
                        (if (and (near-span? x w) (near-span? y h))
                            (rect-op-ints (live-renderer who r) which x y w h)
                            (rect-op (live-renderer who r) which #f (c-real x) (c-real y) (c-real w) (c-real h))))
                      (rect-op (live-renderer who r) which #t 0. 0. 0. 0.))))

  ;; rect: a rect, or #f for the whole target.
  (define (render-fill-rect! r rect) (do-rect 'render-fill-rect! "SDL_RenderFillRect" 0 r rect))
  (define (render-draw-rect! r rect) (do-rect 'render-draw-rect! "SDL_RenderDrawRect" 1 r rect))

  (define sdl-copy
    (foreign-lambda int "downstroke_copy" c-pointer c-pointer bool double double double double
                    bool double double double double double bool bool))
  (define sdl-copy-ints
    (foreign-lambda int "downstroke_copy_ints" c-pointer c-pointer bool int int int int
                    int int int int double bool bool))

  ;; (render-copy! renderer texture src dst #!key flip angle): src and dst
  ;; are rects or #f (the whole texture / target); flip is a list of the
  ;; symbols horizontal and vertical; angle in degrees, clockwise, about
  ;; the centre of dst.
  (define/keywords (render-copy! r t src dst #!key (flip '()) (angle 0))
    (let ((rp (live-renderer* 'render-copy! r))
          (tp (live-texture* 'render-copy! t))
          (h? (and (memq 'horizontal flip) #t))
          (v? (and (memq 'vertical flip) #t)))
      (unless (eq? (texture-renderer t) r)
        (error 'render-copy! "the texture belongs to another renderer" t))
      (unless (and (real? angle) (or (exact? angle) (finite? angle)))
        (error 'render-copy! "angle: must be a finite number of degrees" angle))
      (let ((call (if (and (null? flip) (zero? angle)) "SDL_RenderCopy" "SDL_RenderCopyEx"))
            (degrees (exact->inexact angle)))
        (if dst
            (let ((dx (rect-x dst)) (dy (rect-y dst)) (dw (rect-w dst)) (dh (rect-h dst)))
              (if (and (near-span? dx dw) (near-span? dy dh))
                  (if src
                      (let ((sx (rect-x src)) (sy (rect-y src)) (sw (rect-w src)) (sh (rect-h src)))
                        (if (and (near-span? sx sw) (near-span? sy sh))
                            ;; the usual copy
                            (check-status 'render-copy! call
                                          (sdl-copy-ints rp tp #t sx sy sw sh dx dy dw dh degrees h? v?))
                            (copy-beyond! r t rp tp src dst h? v? angle call degrees)))
                      (check-status 'render-copy! call
                                    (sdl-copy-ints rp tp #f 0 0 0 0 dx dy dw dh degrees h? v?)))
                  (copy-beyond! r t rp tp src dst h? v? angle call degrees)))
            (check-status 'render-copy! call
                          (if src
                              (sdl-copy rp tp #t (c-real (rect-x src)) (c-real (rect-y src))
                                        (c-real (rect-w src)) (c-real (rect-h src))
                                        #f 0 0 0 0 degrees h? v?)
                              (sdl-copy rp tp #f 0 0 0 0 #f 0 0 0 0 degrees h? v?)))))))

  ;; A copy whose numbers are not all small fixnums: downstroke_copy takes
  ;; it as doubles when they are fixnums and draws it when it is near the
  ;; view; anything else is cut by copy-far!.
  (define (copy-beyond! r t rp tp src dst h? v? angle call degrees)
    (let ((status (if (and (fixnum? (rect-x dst)) (fixnum? (rect-y dst))
                           (fixnum? (rect-w dst)) (fixnum? (rect-h dst)))
                      (sdl-copy rp tp (and src #t)
                                (if src (c-real (rect-x src)) 0) (if src (c-real (rect-y src)) 0)
                                (if src (c-real (rect-w src)) 0) (if src (c-real (rect-h src)) 0)
                                #t (rect-x dst) (rect-y dst) (rect-w dst) (rect-h dst) degrees h? v?)
                      2)))
      (if (eqv? status 2)
          (copy-far! r t rp tp src dst h? v? angle call)
          (check-status 'render-copy! call status))))

  (define (whole-texture t) (receive (w h) (texture-size t) (make-rect 0 0 w h)))

  ;;; A copy far beyond the view (downstroke_copy answered 2, or its
  ;;; numbers are not fixnums): cut on whole source pixels, in exact
  ;;; arithmetic, so that a sprite 1e308 px wide shows, exactly where they
  ;;; fall, the texels the view sees. Along an axis where a texel is at
  ;;; most `texel-reach` px, one copy of the texels seen, whose edges lie
  ;;; within a texel of the view; where a texel is larger, each texel seen
  ;;; alone, its destination cut to the view (a texel is one colour, so
  ;;; nothing is squeezed). A turned copy, a NaN or an infinity in the
  ;;; destination is not drawn. Half of DS_REACH: every piece is near the
  ;;; view for downstroke_copy.
  (define texel-reach 8192)

  (define (exact-coordinate v)
    (cond ((exact? v) v)
          ((and (flonum? v) (finite? v)) (inexact->exact v))
          (else #f)))

  ;; One axis: destination [a, b), source texels [s, s + n), mirrored when
  ;; flip?, seen through [v0, v1]: a list of (s0 s1 d0 d1), exact.
  (define (texel-pieces a b s n flip? v0 v1)
    (let ((lo (max a v0)) (hi (min b v1)))
      (if (or (>= lo hi) (<= n 0))
          '()
          (let* ((k (/ (- b a) n))                       ; px per texel
                 (at (lambda (t) (+ a (* k (if flip? (- (+ s n) t) (- t s))))))
                 (u (lambda (x) (+ s (/ (- x a) k))))
                 (t0 (max s (floor (if flip? (- (+ s s n) (u hi)) (u lo)))))
                 (t1 (min (+ s n) (ceiling (if flip? (- (+ s s n) (u lo)) (u hi)))))
                 (t1 (if (<= t1 t0) (+ t0 1) t1))
                 (piece (lambda (t0 t1)
                          (let ((d0 (at (if flip? t1 t0))) (d1 (at (if flip? t0 t1))))
                            (list t0 t1 d0 d1)))))
            (if (<= k texel-reach)
                (list (piece t0 t1))
                (let loop ((t t0) (out '()))
                  (if (>= t t1)
                      (reverse out)
                      (let ((p (piece t (+ t 1))))
                        (loop (+ t 1)
                              (cons (list (car p) (cadr p) (max (caddr p) v0) (min (cadddr p) v1))
                                    out))))))))))

  (define (copy-far! r t rp tp src dst h? v? angle call)
    (let ((x (exact-coordinate (rect-x dst))) (y (exact-coordinate (rect-y dst)))
          (w (exact-coordinate (rect-w dst))) (h (exact-coordinate (rect-h dst)))
          (s (or src (whole-texture t))))
      (when (and x y w h (zero? angle))
        (receive (vw vh) (render-view-size r)
          (let ((xs (texel-pieces x (+ x w) (rect-x s) (rect-w s) h? -1 (+ vw 1)))
                (ys (texel-pieces y (+ y h) (rect-y s) (rect-h s) v? -1 (+ vh 1))))
            (for-each
             (lambda (px)
               (for-each
                (lambda (py)
                  (let ((x0 (floor (caddr px))) (x1 (floor (cadddr px)))
                        (y0 (floor (caddr py))) (y1 (floor (cadddr py))))
                    (when (and (< x0 x1) (< y0 y1))
                      (check-status 'render-copy! call
                                    (sdl-copy rp tp #t (car px) (car py)
                                              (- (cadr px) (car px)) (- (cadr py) (car py))
                                              #t x0 y0 (- x1 x0) (- y1 y0) 0. h? v?)))))
                ys))
             xs))))))

;;; (render-tile-cells! r textures data width height col0 row0 c0 c1 r0 r1
  ;;;                     order table tw th fx fy vw vh pass used)
  ;;; The cells c0..c1 x r0..r1 of an orthogonal tile layer (data: its
  ;;; u32vector of width x height cells, the first at col0 row0) drawn as
  ;;; (downstroke mapdraw) draws them, in one call (shell/tiles.c says what
  ;;; each number is). textures: a vector of this renderer's textures, the
  ;;; table's texture numbers counting from 1; table: an s32vector. Pass 0
  ;;; only marks in the u8vector `used` the textures the visible cells
  ;;; need; pass 1 draws, in runs of one SDL_RenderGeometry call per
  ;;; texture on an accelerated renderer. Answers #f, drawing nothing, for
  ;;; what it does not take (more than 64 textures, numbers beyond C's
  ;;; ints): the caller then draws cell by cell.
  (define tile-cells
    (foreign-lambda int "ds_tile_cells" c-pointer int u32vector int int int int int
                    int int int int int s32vector int int int int int int int int bool u8vector))
  (define max-tile-textures 64)
  (define c-int-limit 536870912)
  (define (c-int? . vs)
    (let loop ((vs vs))
      (or (null? vs)
          (and (fixnum? (car vs)) (fx< (car vs) c-int-limit) (fx> (car vs) (fxneg c-int-limit))
               (loop (cdr vs))))))
  (define (render-tile-cells! r textures data width height col0 row0 c0 c1 r0 r1
                              order table tw th fx fy vw vh pass used)
    (let ((rp (live-renderer 'render-tile-cells! r))
          (n (vector-length textures)))
      (and (fx<= n max-tile-textures)
           (fx>= (u8vector-length used) n)
           (c-int? width height col0 row0 c0 c1 r0 r1 order tw th fx fy vw vh pass)
           (c-int? (* tw (+ (abs col0) width 1)) (* th (+ (abs row0) height 1)))
           (begin
             (do ((i 0 (fx+ i 1))) ((fx= i n))
               (let ((t (vector-ref textures i)))
                 (unless (eq? (texture-renderer t) r)
                   (error 'render-tile-cells! "the texture belongs to another renderer" t))
                 ((foreign-lambda void "ds_tiles_texture" int c-pointer) i (live-texture 'render-tile-cells! t))))
             (gl-allow! (render-gl-batching?))
             (check-status 'render-tile-cells! "SDL_RenderGeometry"
                           (tile-cells rp n data (u32vector-length data) width height col0 row0
                                       c0 c1 r0 r1 order table (s32vector-length table) tw th
                                       fx fy vw vh pass (not (renderer-software? r)) used))
             #t))))

;;; (render-sprite-walk! r texture entities keys sheet cx cy): draws
  ;;; entities from the first on, as (downstroke renderer) draws them, in
  ;;; one walk in C (shell/sprites.c says which it takes), and answers the
  ;;; list from the first one it left to the renderer ('() when none).
  ;;; texture: the scene's sprite sheet or #f; keys: the renderer's vector
  ;;; of the keys it draws by; sheet: an s32vector of the sheet's first gid,
  ;;; tile width and height, spacing, margin and columns (0: none); cx cy:
  ;;; the camera.
  (define sprite-walk
    (foreign-lambda scheme-object "ds_sprite_walk" c-pointer c-pointer scheme-object scheme-object
                    s32vector scheme-object scheme-object))
  (define (render-sprite-walk! r t entities keys sheet cx cy)
    (let* ((rp (live-renderer* 'render-copy! r))
           ;; a texture of another renderer, or a dead one: the sprites
           ;; go to the renderer's own path, which says so
           (tp (and t (texture? t) (eq? (texture-renderer t) r) (texture-alive? t) (texture-ptr t)))
           (rest (sprite-walk rp tp entities keys sheet cx cy))
           (status (foreign-value "ds_walk_status" int)))
      (check-status 'render-copy! "SDL_RenderCopy" status)
      rest))

  (define (render-view-size r)
    (let-location ((w int 0) (h int 0))
      ((foreign-lambda void "downstroke_view" c-pointer (c-pointer int) (c-pointer int))
       (live-renderer 'render-copy! r) (location w) (location h))
      (values w h)))

  (define (render-present! r)
    ((foreign-lambda void "SDL_RenderPresent" c-pointer) (live-renderer 'render-present! r)))

  ;; The render target's pixels, RGBA order, row by row:
  ;; (values u8vector width height), 4 bytes a pixel.
  (define (render-read-pixels r)
    (let ((p (live-renderer 'render-read-pixels r)))
      (receive (w h) (renderer-output-size r)
        (let ((buf (make-u8vector (* w h 4) 0)))
          (check-status 'render-read-pixels "SDL_RenderReadPixels"
                        ((foreign-lambda* int ((c-pointer r) (u8vector buf) (int pitch))
                           "SDL_Renderer *rr = (SDL_Renderer*)r;
                            int lw, lh, status; float sx, sy; SDL_Rect vp;
                            /* SDL reads the viewport: read the whole target,
                               letterbox bars included, then put the viewport
                               and scale back (through the logical size when
                               one is set, as SDL computes them) */
                            SDL_RenderGetLogicalSize(rr, &lw, &lh);
                            SDL_RenderGetScale(rr, &sx, &sy);
                            SDL_RenderGetViewport(rr, &vp);
                            SDL_RenderSetScale(rr, 1.0f, 1.0f);
                            SDL_RenderSetViewport(rr, NULL);
                            status = SDL_RenderReadPixels(rr, NULL, SDL_PIXELFORMAT_RGBA32, buf, pitch);
                            if (lw > 0 && lh > 0) SDL_RenderSetLogicalSize(rr, lw, lh);
                            else { SDL_RenderSetViewport(rr, &vp); SDL_RenderSetScale(rr, sx, sy); }
                            C_return(status);")
                         p buf (* w 4)))
          (values buf w h)))))

  ;;; ------------------------------------------------------------------
  ;;; Textures

  ;; The most pixels an image file may have: 8192 x 8192 (256 MB as RGBA).
  ;; PNG, JPEG, GIF, BMP, QOI and WebP are measured from their header,
  ;; before anything is decoded; another format SDL_image reads (TGA ...)
  ;; is measured once decoded, and freed again when it is too large.
  (define max-image-pixels (make-parameter (* 8192 8192)))

  (define (too-many-pixels who path w h)
    (error who (sprintf "~s is ~a x ~a pixels: more than the limit of ~a (max-image-pixels)"
                        path w h (max-image-pixels))))

  (define (check-image-header who path)
    (let ((why (file-problem path)))
      (cond ((equal? why "not found"))          ; SDL_image says so itself
            (why (error who (sprintf "~s ~a" path why)))
            ((image-file-size path)
             => (lambda (size)
                  (when (> (* (car size) (cadr size)) (max-image-pixels))
                    (too-many-pixels who path (car size) (cadr size))))))))

  ;; A texture from an image file (PNG and whatever else SDL_image reads).
  ;; key: #f, or a colour (r g b) drawn transparent (Tiled's `trans`): the
  ;; image is read into a surface, the colour keyed out, then uploaded.
  (define (img-load-texture! r path #!optional (key #f))
    (unless (string? path) (error 'img-load-texture! "the path must be a string" path))
    (check-image-header 'img-load-texture! path)
    (when key
      (unless (and (list? key) (= 3 (length key)))
        (error 'img-load-texture! "the colour key must be (r g b)" key))
      (for-each (lambda (c) (byte 'img-load-texture! c)) key))
    (let* ((rp (live-renderer 'img-load-texture! r))
           (p (if key
                  ((foreign-lambda* c-pointer ((c-pointer r) (c-string path)
                                               (unsigned-byte kr) (unsigned-byte kg) (unsigned-byte kb))
                     "SDL_Surface *s = IMG_Load(path); SDL_Texture *t = NULL;
                      if (s) {
                        if (SDL_SetColorKey(s, SDL_TRUE, SDL_MapRGB(s->format, kr, kg, kb)) == 0)
                          t = SDL_CreateTextureFromSurface((SDL_Renderer*)r, s);
                        SDL_FreeSurface(s);
                      }
                      C_return(t);")
                   rp path (car key) (cadr key) (caddr key))
                  ((foreign-lambda c-pointer "IMG_LoadTexture" c-pointer c-string) rp path))))
      (unless p (sdl-error 'img-load-texture! "IMG_LoadTexture"
                           (sprintf "cannot load ~s" path)))
      (set! count-textures (+ count-textures 1))
      (let-location ((w int 0) (h int 0))
        ((foreign-lambda int "SDL_QueryTexture" c-pointer c-pointer c-pointer
                         (c-pointer int) (c-pointer int))
         p #f #f (location w) (location h))
        (when (> (* w h) (max-image-pixels))
          ((foreign-lambda void "SDL_DestroyTexture" c-pointer) p)
          (set! count-textures (- count-textures 1))
          (too-many-pixels 'img-load-texture! path w h))
        (set-finalizer! (%make-texture p r w h) (finalizer destroy-texture!)))))

  ;; (values width height)
  (define (texture-size t)
    (live-texture 'texture-size t)
    (values (texture-width t) (texture-height t)))

  ;; alpha: 0..255, multiplied into every pixel the texture draws.
  (define (texture-alpha-mod-set! t alpha)
    (check-status 'texture-alpha-mod-set! "SDL_SetTextureAlphaMod"
                  ((foreign-lambda int "SDL_SetTextureAlphaMod" c-pointer unsigned-byte)
                   (live-texture 'texture-alpha-mod-set! t)
                   (byte 'texture-alpha-mod-set! alpha))))

  (define (texture-alpha-mod t)
    (let ((p (live-texture 'texture-alpha-mod t)))
      (let-location ((a unsigned-byte 0))
        (check-status 'texture-alpha-mod "SDL_GetTextureAlphaMod"
                      ((foreign-lambda int "SDL_GetTextureAlphaMod" c-pointer (c-pointer unsigned-byte))
                       p (location a)))
        a)))

  ;; How the texture's pixels combine with what is drawn: none, blend, add
  ;; or mod. An image without an alpha channel loads as none, which ignores
  ;; the alpha modulation; a translucent layer sets blend.
  (define (texture-blend-mode-set! t mode)
    (check-status 'texture-blend-mode-set! "SDL_SetTextureBlendMode"
                  ((foreign-lambda int "SDL_SetTextureBlendMode" c-pointer int)
                   (live-texture 'texture-blend-mode-set! t)
                   (blend-mode 'texture-blend-mode-set! mode))))

  ;; red, green, blue: 0..255, multiplied into the colour of every pixel
  ;; the texture draws (255 255 255 leaves it unchanged).
  (define (texture-color-mod-set! t red green blue)
    (check-status 'texture-color-mod-set! "SDL_SetTextureColorMod"
                  ((foreign-lambda int "SDL_SetTextureColorMod" c-pointer
                                   unsigned-byte unsigned-byte unsigned-byte)
                   (live-texture 'texture-color-mod-set! t)
                   (byte 'texture-color-mod-set! red)
                   (byte 'texture-color-mod-set! green)
                   (byte 'texture-color-mod-set! blue))))

  ;; (values red green blue)
  (define (texture-color-mod t)
    (let ((p (live-texture 'texture-color-mod t)))
      (let-location ((r unsigned-byte 0) (g unsigned-byte 0) (b unsigned-byte 0))
        (check-status 'texture-color-mod "SDL_GetTextureColorMod"
                      ((foreign-lambda int "SDL_GetTextureColorMod" c-pointer
                                       (c-pointer unsigned-byte) (c-pointer unsigned-byte)
                                       (c-pointer unsigned-byte))
                       p (location r) (location g) (location b)))
        (values r g b))))

  ;;; ------------------------------------------------------------------
  ;;; Surfaces

  ;; A w x h surface of 32-bit RGBA pixels (SDL_PIXELFORMAT_RGBA32),
  ;; initially transparent black.
  (define (create-rgba-surface! w h)
    (let ((p ((foreign-lambda* c-pointer ((int w) (int h))
                "C_return(SDL_CreateRGBSurfaceWithFormat(0, w, h, 32, SDL_PIXELFORMAT_RGBA32));")
              w h)))
      (unless p (sdl-error 'create-rgba-surface! "SDL_CreateRGBSurfaceWithFormat"))
      (wrap-surface p)))

  (define (wrap-surface p)
    (set! count-surfaces (+ count-surfaces 1))
    (set-finalizer! (%make-surface p #f) (finalizer free-surface!)))

  ;; An image file (PNG ...) as a new RGBA surface (SDL_PIXELFORMAT_RGBA32);
  ;; an error names the file.
  (define (img-load-surface! path)
    (unless (string? path) (error 'img-load-surface! "the path must be a string" path))
    (check-image-header 'img-load-surface! path)
    (let ((raw ((foreign-lambda c-pointer "IMG_Load" c-string) path)))
      (unless raw (sdl-error 'img-load-surface! "IMG_Load" (sprintf "cannot load ~s" path)))
      (let ((w ((foreign-lambda* int ((c-pointer s)) "C_return(((SDL_Surface*)s)->w);") raw))
            (h ((foreign-lambda* int ((c-pointer s)) "C_return(((SDL_Surface*)s)->h);") raw)))
        (when (> (* w h) (max-image-pixels))
          ((foreign-lambda void "SDL_FreeSurface" c-pointer) raw)
          (too-many-pixels 'img-load-surface! path w h)))
      (let ((p ((foreign-lambda* c-pointer ((c-pointer s))
                  "SDL_Surface *c = SDL_ConvertSurfaceFormat((SDL_Surface*)s, SDL_PIXELFORMAT_RGBA32, 0);
                   SDL_FreeSurface((SDL_Surface*)s);
                   C_return(c);")
                raw)))
        (unless p (sdl-error 'img-load-surface! "SDL_ConvertSurfaceFormat"
                             (sprintf "cannot convert ~s" path)))
        (wrap-surface p))))

  ;; A new w x h RGBA surface holding a copy of `pixels`, a u8vector of
  ;; w * h * 4 bytes in RGBA order, row by row (what render-read-pixels and
  ;; surface-pixels give).
  (define (rgba-pixels->surface! pixels w h)
    (unless (and (u8vector? pixels) (fixnum? w) (fixnum? h) (> w 0) (> h 0)
                 (= (u8vector-length pixels) (* w h 4)))
      (error 'rgba-pixels->surface! "pixels must be a u8vector of w * h * 4 bytes" w h))
    (let ((s (create-rgba-surface! w h)))
      ((foreign-lambda* void ((c-pointer s) (u8vector buf) (int w) (int h))
         "SDL_Surface *sf = (SDL_Surface*)s; int y;
          for (y = 0; y < h; y++)
            SDL_memcpy((Uint8*)sf->pixels + y * sf->pitch, buf + y * w * 4, w * 4);")
       (surface-ptr s) pixels w h)
      s))

  ;; An RGBA surface's pixels: (values u8vector width height), RGBA order,
  ;; row by row. Flushes the surface's software renderer first.
  (define (surface-pixels s)
    (let ((r (surface-renderer s)))
      (when (and r (renderer-alive? r))
        ((foreign-lambda int "SDL_RenderFlush" c-pointer) (renderer-ptr r))))
    (let ((p (live-surface 'surface-pixels s)))
      (unless ((foreign-lambda* bool ((c-pointer s))
                 "C_return(((SDL_Surface*)s)->format->format == SDL_PIXELFORMAT_RGBA32);") p)
        (error 'surface-pixels "not an RGBA32 surface" s))
      (receive (w h) (surface-size s)
        (let ((buf (make-u8vector (* w h 4) 0)))
          ((foreign-lambda* void ((c-pointer s) (u8vector buf) (int w) (int h))
             "SDL_Surface *sf = (SDL_Surface*)s; int y;
              for (y = 0; y < h; y++)
                SDL_memcpy(buf + y * w * 4, (Uint8*)sf->pixels + y * sf->pitch, w * 4);")
           p buf w h)
          (values buf w h)))))

  (define (surface-size s)
    (let ((p (live-surface 'surface-size s)))
      (values ((foreign-lambda* int ((c-pointer s)) "C_return(((SDL_Surface*)s)->w);") p)
              ((foreign-lambda* int ((c-pointer s)) "C_return(((SDL_Surface*)s)->h);") p))))

  (define (img-save-png! s path)
    (unless (string? path) (error 'img-save-png! "the path must be a string" path))
    (let ((r (surface-renderer s)))
      ;; a software renderer batches its drawing: flush it into the surface
      (when (and r (renderer-alive? r))
        ((foreign-lambda int "SDL_RenderFlush" c-pointer) (renderer-ptr r))))
    (let ((status ((foreign-lambda int "IMG_SavePNG" c-pointer c-string)
                   (live-surface 'img-save-png! s) path)))
      (when (< status 0)
        (sdl-error 'img-save-png! "IMG_SavePNG" (sprintf "cannot save ~s" path)))
      (void)))

  ;;; ------------------------------------------------------------------
  ;;; Keys

  (define key-table
    (append
     (let loop ((c (char->integer #\a)) (out '()))
       (if (> c (char->integer #\z))
           (reverse out)
           (loop (+ c 1) (cons (cons (string->symbol (string (integer->char c))) c) out))))
     (let loop ((d 0) (out '()))
       (if (> d 9)
           (reverse out)
           (loop (+ d 1) (cons (cons (string->symbol (sprintf "n-~a" d)) (+ 48 d)) out))))
     `((left . ,(foreign-value "SDLK_LEFT" int))
       (right . ,(foreign-value "SDLK_RIGHT" int))
       (up . ,(foreign-value "SDLK_UP" int))
       (down . ,(foreign-value "SDLK_DOWN" int))
       (return . ,(foreign-value "SDLK_RETURN" int))
       (escape . ,(foreign-value "SDLK_ESCAPE" int))
       (space . ,(foreign-value "SDLK_SPACE" int))
       (tab . ,(foreign-value "SDLK_TAB" int))
       (backspace . ,(foreign-value "SDLK_BACKSPACE" int))
       (delete . ,(foreign-value "SDLK_DELETE" int))
       (insert . ,(foreign-value "SDLK_INSERT" int))
       (home . ,(foreign-value "SDLK_HOME" int))
       (end . ,(foreign-value "SDLK_END" int))
       (page-up . ,(foreign-value "SDLK_PAGEUP" int))
       (page-down . ,(foreign-value "SDLK_PAGEDOWN" int))
       (lshift . ,(foreign-value "SDLK_LSHIFT" int))
       (rshift . ,(foreign-value "SDLK_RSHIFT" int))
       (lctrl . ,(foreign-value "SDLK_LCTRL" int))
       (rctrl . ,(foreign-value "SDLK_RCTRL" int))
       (lalt . ,(foreign-value "SDLK_LALT" int))
       (ralt . ,(foreign-value "SDLK_RALT" int))
       (lgui . ,(foreign-value "SDLK_LGUI" int))
       (rgui . ,(foreign-value "SDLK_RGUI" int))
       (minus . ,(foreign-value "SDLK_MINUS" int))
       (equals . ,(foreign-value "SDLK_EQUALS" int))
       (comma . ,(foreign-value "SDLK_COMMA" int))
       (period . ,(foreign-value "SDLK_PERIOD" int))
       (slash . ,(foreign-value "SDLK_SLASH" int))
       (semicolon . ,(foreign-value "SDLK_SEMICOLON" int))
       (f1 . ,(foreign-value "SDLK_F1" int)) (f2 . ,(foreign-value "SDLK_F2" int))
       (f3 . ,(foreign-value "SDLK_F3" int)) (f4 . ,(foreign-value "SDLK_F4" int))
       (f5 . ,(foreign-value "SDLK_F5" int)) (f6 . ,(foreign-value "SDLK_F6" int))
       (f7 . ,(foreign-value "SDLK_F7" int)) (f8 . ,(foreign-value "SDLK_F8" int))
       (f9 . ,(foreign-value "SDLK_F9" int)) (f10 . ,(foreign-value "SDLK_F10" int))
       (f11 . ,(foreign-value "SDLK_F11" int)) (f12 . ,(foreign-value "SDLK_F12" int)))))

  (define (key-symbols) (map car key-table))

  (define (keycode->key code)
    (let loop ((t key-table))
      (cond ((null? t) 'unknown)
            ((= (cdar t) code) (caar t))
            (else (loop (cdr t))))))

  (define (key->keycode key)
    (let ((p (assq key key-table)))
      (unless p (error 'key->keycode "unknown key symbol" key))
      (cdr p)))

  ;;; ------------------------------------------------------------------
  ;;; Events

  (define ev-int (foreign-lambda int "downstroke_ev_int" int))

  ;; SDL_GameControllerButton and SDL_GameControllerAxis, in enum order.
  (define controller-buttons
    '(a b x y back guide start left-stick right-stick left-shoulder right-shoulder
      dpad-up dpad-down dpad-left dpad-right))
  (define controller-axes '(left-x left-y right-x right-y trigger-left trigger-right))

  (define (nth-or-unknown xs i)
    (if (and (>= i 0) (< i (length xs))) (list-ref xs i) 'unknown))

  (define type-quit (foreign-value "SDL_QUIT" int))
  (define type-key-down (foreign-value "SDL_KEYDOWN" int))
  (define type-key-up (foreign-value "SDL_KEYUP" int))
  (define type-cbutton-down (foreign-value "SDL_CONTROLLERBUTTONDOWN" int))
  (define type-cbutton-up (foreign-value "SDL_CONTROLLERBUTTONUP" int))
  (define type-caxis (foreign-value "SDL_CONTROLLERAXISMOTION" int))
  (define type-cadded (foreign-value "SDL_CONTROLLERDEVICEADDED" int))
  (define type-cremoved (foreign-value "SDL_CONTROLLERDEVICEREMOVED" int))
  (define type-mmotion (foreign-value "SDL_MOUSEMOTION" int))
  (define type-mbutton-down (foreign-value "SDL_MOUSEBUTTONDOWN" int))
  (define type-mbutton-up (foreign-value "SDL_MOUSEBUTTONUP" int))
  (define mouse-button-names '(left middle right x1 x2))

  ;; The next event as a list (see the head of this file), or #f.
  (define (poll-event!)
    (unless initialized? (error 'poll-event! "SDL is not initialized (init!)"))
    (let ((type ((foreign-lambda int "downstroke_poll"))))
      (cond ((< type 0) #f)
            ((= type type-quit) (list 'quit))
            ((= type type-key-down) (list 'key-down (keycode->key (ev-int 0)) (= 1 (ev-int 1))))
            ((= type type-key-up) (list 'key-up (keycode->key (ev-int 0)) (= 1 (ev-int 1))))
            ((= type type-cbutton-down)
             (list 'controller-button-down (nth-or-unknown controller-buttons (ev-int 2))))
            ((= type type-cbutton-up)
             (list 'controller-button-up (nth-or-unknown controller-buttons (ev-int 2))))
            ((= type type-caxis)
             (list 'controller-axis (nth-or-unknown controller-axes (ev-int 3)) (ev-int 4)))
            ((= type type-cadded) (list 'controller-added (ev-int 5)))
            ((= type type-cremoved) (list 'controller-removed (ev-int 5)))
            ((= type type-mmotion) (list 'mouse-motion (ev-int 6) (ev-int 7)))
            ((= type type-mbutton-down)
             (list 'mouse-button-down (nth-or-unknown mouse-button-names (- (ev-int 8) 1))
                   (ev-int 9) (ev-int 10)))
            ((= type type-mbutton-up)
             (list 'mouse-button-up (nth-or-unknown mouse-button-names (- (ev-int 8) 1))
                   (ev-int 9) (ev-int 10)))
            (else (list 'other type)))))

  ;; Every pending event, oldest first.
  (define (poll-events!)
    (let loop ((out '()))
      (let ((e (poll-event!)))
        (if e (loop (cons e out)) (reverse out)))))

  ;; (push-key-event! 'key-down 'left #!key repeat?)
  (define/keywords (push-key-event! type key #!key (repeat? #f))
    (unless initialized? (error 'push-key-event! "SDL is not initialized (init!)"))
    (let ((down (case type
                  ((key-down) 1)
                  ((key-up) 0)
                  (else (error 'push-key-event! "type must be key-down or key-up" type)))))
      (when (< ((foreign-lambda int "downstroke_push_key" int int int)
                down (key->keycode key) (if repeat? 1 0))
               1)
        (sdl-error 'push-key-event! "SDL_PushEvent"))
      (void)))

  (define (push-quit-event!)
    (unless initialized? (error 'push-quit-event! "SDL is not initialized (init!)"))
    (when (< ((foreign-lambda int "downstroke_push_quit")) 1)
      (sdl-error 'push-quit-event! "SDL_PushEvent"))
    (void)))

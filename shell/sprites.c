/* (downstroke renderer)'s entities drawn by one walk in C (sdl2.scm's
   render-sprite-walk!, included by sdl2.scm after the copy queue): for
   each entity it can draw, the same copy, at the same pixels and with the
   same modulation, that renderer.scm's draw-entity! would make, without a
   trip through Scheme. It stops at the first entity it leaves to Scheme
   and answers the list from there (renderer.scm draws that one and calls
   again with the rest), so the draw order never changes.

   Left to Scheme: boxes (#:color without a drawable tile), animations not
   stepped yet, particles (#:emitter), other sheets (#:tileset), anything
   renderer.scm would report as an error, copies beyond the reach of
   render-copy!'s usual path (far from the view, huge), and numbers this
   walk does not take (below). The numbers taken are the ones whose
   arithmetic in doubles gives exactly what renderer.scm's gives: finite
   flonums (the same double operations, in the same order), fixnums within
   +-2^20, and fractions of such numerators over a power of two up to 2^8
   (exact in a double, and so are the few sums and products of them a
   sprite's box takes, with tiles below 2^16 px: fewer than 53 significant
   bits, since a turn by a whole multiple of 90 degrees, the one exact
   turn, adds one product and not two). Floating-point contraction (FMA)
   would change the sums; neither the x86-64 baseline nor wasm32 has it. */
#include "shell/keys.c"

/* renderer.scm's define-drawn-keys, in its order. */
enum { DS_K_TILE_ID, DS_K_COLOR, DS_K_X, DS_K_Y, DS_K_FACING, DS_K_ANIMATIONS,
       DS_K_OFFSET_X, DS_K_OFFSET_Y, DS_K_ORIGIN_X, DS_K_ORIGIN_Y, DS_K_FLIP_X, DS_K_FLIP_Y,
       DS_K_ANGLE, DS_K_SCALE, DS_K_SCALE_X, DS_K_SCALE_Y, DS_K_ALPHA, DS_K_TINT,
       DS_K_TILESET, DS_K_EMITTER, DS_K_COUNT };
#define DS_K(k) ((C_word)1 << DS_K_##k)
#define DS_SPRITE_KEYS (~(DS_K(OFFSET_X) - 1))   /* every bit from #:sprite-offset-x up */

#define DS_EXACT_LIMIT 1048576                    /* 2^20 */
#define DS_NEAR 16384                             /* sdl2.scm's near-limit, DS_REACH */
#define DS_TO_SCHEME 1                            /* ds_sprite_one: Scheme draws it */

static int ds_walk_status = 0;

/* The texture's modulation as the walk last read or set it (t NULL: not
   read yet in this walk). Only the walk's own calls change a texture's
   modulation while it runs, so one read serves every sprite of the
   walk, and resetting a component that is full already is skipped. */
static struct { SDL_Texture *t; SDL_Color c; } ds_walk_mod = { NULL, { 255, 255, 255, 255 } };

static inline SDL_Color ds_walk_modulation(SDL_Texture *t) {
  if (ds_walk_mod.t != t) { ds_walk_mod.c = ds_texture_modulation(t); ds_walk_mod.t = t; }
  return ds_walk_mod.c;
}

/* A number this walk takes, as a double; 0 when it takes none. */
static inline int ds_number(C_word v, double *out) {
  if (v & C_FIXNUM_BIT) {
    C_word n = C_unfix(v);
    if (n < -DS_EXACT_LIMIT || n > DS_EXACT_LIMIT) return 0;
    *out = (double)n;
    return 1;
  }
  if (C_immediatep(v)) return 0;
  if (C_block_header(v) == C_FLONUM_TAG) {
    double d = C_flonum_magnitude(v);
    if (!isfinite(d)) return 0;
    *out = d;
    return 1;
  }
  if (C_block_header(v) == C_RATNUM_TAG) {
    C_word n = C_u_i_ratnum_num(v), d = C_u_i_ratnum_denom(v);
    if (!(n & C_FIXNUM_BIT) || !(d & C_FIXNUM_BIT)) return 0;
    n = C_unfix(n); d = C_unfix(d);
    if (n < -DS_EXACT_LIMIT || n > DS_EXACT_LIMIT || d <= 0 || d > 256 || (d & (d - 1))) return 0;
    *out = (double)n / (double)d;
    return 1;
  }
  return 0;
}

/* renderer.scm's byte-of: a fixnum or a flonum (an infinity only when
   inf_ok) held to 0-255, rounded half to even as Scheme's round. */
static int ds_byte(C_word v, int inf_ok, int *out) {
  double d;
  if (v & C_FIXNUM_BIT) {
    C_word n = C_unfix(v);
    *out = n >= 255 ? 255 : n <= 0 ? 0 : (int)n;
    return 1;
  }
  if (C_immediatep(v) || C_block_header(v) != C_FLONUM_TAG) return 0;
  d = C_flonum_magnitude(v);
  if (isnan(d) || (!inf_ok && isinf(d))) return 0;
  *out = d >= 255.0 ? 255 : d <= 0.0 ? 0 : (int)nearbyint(d);
  return 1;
}

/* A #:tint of 3 or 4 components (the first three are the colour). */
static int ds_tint(C_word t, SDL_Color *c) {
  int k[4], n = 0;
  for (; !C_immediatep(t) && C_truep(C_i_pairp(t)); t = C_block_item(t, 1)) {
    if (n == 4 || !ds_byte(C_block_item(t, 0), 1, &k[n])) return 0;
    n++;
  }
  if (t != C_SCHEME_END_OF_LIST || n < 3) return 0;
  c->r = (Uint8)k[0]; c->g = (Uint8)k[1]; c->b = (Uint8)k[2];
  return 1;
}

/* mapdraw.scm's sine: whole multiples of 90 degrees exactly. */
static double ds_sine(double degrees) {
  if (degrees == floor(degrees)) {
    double m = fmod(degrees, 360.0);
    if (m < 0) m += 360.0;
    if (m == 0.0 || m == 180.0) return 0.0;
    if (m == 90.0) return 1.0;
    if (m == 270.0) return -1.0;
  }
  return sin(degrees * (4.0 * atan(1.0)) / 180.0);
}

/* The span [p, p + size) as render-copy! passes it on unchanged. */
static inline int ds_near(double p, double size) {
  return p >= -DS_NEAR && p <= DS_NEAR && size > 0 && size <= DS_NEAR && p + size <= DS_NEAR;
}

/* One copy as renderer.scm makes it: the texture's modulation, or the
   tint and alpha given (tinted, alpha < 255), which are reset to full
   after the copy as renderer.scm resets them. Copies join the queue when
   one is open (turned ones on the opengl renderer only, sdl2.scm's
   ds_q_copy_turned); the rest go to SDL at once. */
static int ds_sprite_copy(SDL_Renderer *r, SDL_Texture *t, const SDL_Rect *src, const SDL_Rect *dst,
                          double angle, int h, int v, int tinted, SDL_Color tint, int alpha) {
  SDL_Color m = ds_walk_modulation(t), c = m;
  int st = 0;
  if (tinted) { c.r = tint.r; c.g = tint.g; c.b = tint.b; }
  if (alpha < 255) c.a = (Uint8)alpha;
  if (!(angle == 0.0 ? ds_q_copy_colored(r, t, src, dst, h, v, c)
                     : ds_q_copy_turned(r, t, src, dst, angle, h, v, c))) {
    ds_q_flush();
    ds_walk_mod.t = NULL;               /* read again after SDL's copy */
    if (tinted) st = SDL_SetTextureColorMod(t, c.r, c.g, c.b);
    if (st >= 0 && alpha < 255) st = SDL_SetTextureAlphaMod(t, c.a);
    if (st >= 0) st = ds_copy_rect(r, t, (SDL_Rect *)src, (SDL_Rect *)dst, angle,
                                   (h ? SDL_FLIP_HORIZONTAL : 0) | (v ? SDL_FLIP_VERTICAL : 0));
    m.r = m.g = m.b = m.a = 0;          /* so both resets below are made */
  }
  if (tinted && (m.r != 255 || m.g != 255 || m.b != 255)) SDL_SetTextureColorMod(t, 255, 255, 255);
  if (alpha < 255 && m.a != 255) SDL_SetTextureAlphaMod(t, 255);
  if (ds_walk_mod.t == t) {             /* what the resets left */
    if (tinted) ds_walk_mod.c.r = ds_walk_mod.c.g = ds_walk_mod.c.b = 255;
    if (alpha < 255) ds_walk_mod.c.a = 255;
  }
  return st;
}

/* One entity: 0 drawn (or nothing to draw), DS_TO_SCHEME, or SDL's
   negative status. sheet: first gid, tile width and height, spacing,
   margin, columns (0: no sheet). */
static int ds_sprite_one(SDL_Renderer *r, SDL_Texture *t, C_word mask, const C_word *v,
                         const int *sheet, double cx, double cy) {
  double x = 0, y = 0;
  long long local, sx, sy;
  int sw = sheet[1], sh = sheet[2], facing_left;
  SDL_Rect src, dst;
  if (mask < 0 || (mask & (DS_K(ANIMATIONS) | DS_K(TILESET) | DS_K(EMITTER)))) return DS_TO_SCHEME;
  if ((mask & DS_K(X)) && !ds_number(v[DS_K_X], &x)) return DS_TO_SCHEME;
  if ((mask & DS_K(Y)) && !ds_number(v[DS_K_Y], &y)) return DS_TO_SCHEME;
  if (!(mask & DS_K(TILE_ID)))          /* no tile and no box: nothing to draw */
    return (mask & (DS_K(COLOR) | DS_SPRITE_KEYS)) ? DS_TO_SCHEME : 0;
  if (!t || sheet[5] <= 0 || !(v[DS_K_TILE_ID] & C_FIXNUM_BIT)) return DS_TO_SCHEME;
  local = (long long)C_unfix(v[DS_K_TILE_ID]) - sheet[0];
  if (local < 0) return DS_TO_SCHEME;
  sx = sheet[4] + (local % sheet[5]) * (long long)(sw + sheet[3]);
  sy = sheet[4] + (local / sheet[5]) * (long long)(sh + sheet[3]);
  if (!ds_near((double)sx, sw) || !ds_near((double)sy, sh)) return DS_TO_SCHEME;
  src.x = (int)sx; src.y = (int)sy; src.w = sw; src.h = sh;
  facing_left = (mask & DS_K(FACING)) && v[DS_K_FACING] == C_fix(-1);
  if (!(mask & DS_SPRITE_KEYS)) {       /* a plain sprite: at its place, its size */
    double dx = floor(x - cx), dy = floor(y - cy);
    SDL_Color none = { 255, 255, 255, 255 };
    if (!ds_near(dx, sw) || !ds_near(dy, sh)) return DS_TO_SCHEME;
    dst.x = (int)dx; dst.y = (int)dy; dst.w = sw; dst.h = sh;
    return ds_sprite_copy(r, t, &src, &dst, 0.0, facing_left, 0, 0, none, 255);
  }
  {
    /* renderer.scm's draw-tile! and sprite-box, operation for operation */
    double scale = 1, kx, ky, ox = sw / 2.0, oy = sh / 2.0, angle = 0, offx = 0, offy = 0;
    double px, py, e[4], x0, y0, x1, y1;
    int alpha = 255, tinted = 0, i;
    SDL_Color tint = { 255, 255, 255, 255 };
    if ((mask & DS_K(ALPHA)) && !ds_byte(v[DS_K_ALPHA], 0, &alpha)) return DS_TO_SCHEME;
    if (alpha == 0) return 0;
    if ((mask & DS_K(SCALE)) && !ds_number(v[DS_K_SCALE], &scale)) return DS_TO_SCHEME;
    kx = scale; ky = scale;
    if ((mask & DS_K(SCALE_X)) && !ds_number(v[DS_K_SCALE_X], &kx)) return DS_TO_SCHEME;
    if ((mask & DS_K(SCALE_Y)) && !ds_number(v[DS_K_SCALE_Y], &ky)) return DS_TO_SCHEME;
    if ((mask & DS_K(ORIGIN_X)) && !ds_number(v[DS_K_ORIGIN_X], &ox)) return DS_TO_SCHEME;
    if ((mask & DS_K(ORIGIN_Y)) && !ds_number(v[DS_K_ORIGIN_Y], &oy)) return DS_TO_SCHEME;
    if ((mask & DS_K(ANGLE)) && !ds_number(v[DS_K_ANGLE], &angle)) return DS_TO_SCHEME;
    if ((mask & DS_K(OFFSET_X)) && !ds_number(v[DS_K_OFFSET_X], &offx)) return DS_TO_SCHEME;
    if ((mask & DS_K(OFFSET_Y)) && !ds_number(v[DS_K_OFFSET_Y], &offy)) return DS_TO_SCHEME;
    if (kx < 0 || ky < 0) return DS_TO_SCHEME;          /* an error, said by Scheme */
    px = x + offx + ox;
    py = y + offy + oy;
    if (angle == 0) {
      e[0] = px - kx * ox; e[1] = py - ky * oy;
      e[2] = px + kx * (sw - ox); e[3] = py + ky * (sh - oy);
    } else {
      double dx = kx * (sw / 2.0 - ox), dy = ky * (sh / 2.0 - oy);
      double mx = px, my = py, hw = kx * sw / 2.0, hh = ky * sh / 2.0;
      /* turned about its centre (the default origin), the centre stays:
         the terms below are zeros then (of either sign, which changes no
         pixel: a box edge is mx -+ hw, and hw is 0 only for no box) */
      if (dx != 0 || dy != 0) {
        double s = ds_sine(angle), c = ds_sine(angle + 90);
        mx = px + (dx * c - dy * s); my = py + dx * s + dy * c;
      }
      e[0] = mx - hw; e[1] = my - hh; e[2] = mx + hw; e[3] = my + hh;
    }
    for (i = 0; i < 4; i++) if (!isfinite(e[i])) return DS_TO_SCHEME;
    x0 = floor(e[0] - cx); y0 = floor(e[1] - cy); x1 = floor(e[2] - cx); y1 = floor(e[3] - cy);
    if (!(x1 > x0 && y1 > y0)) return isfinite(x1 - x0) && isfinite(y1 - y0) ? 0 : DS_TO_SCHEME;
    if ((mask & DS_K(TINT)) && !(tinted = ds_tint(v[DS_K_TINT], &tint))) return DS_TO_SCHEME;
    if (!ds_near(x0, x1 - x0) || !ds_near(y0, y1 - y0)) return DS_TO_SCHEME;
    dst.x = (int)x0; dst.y = (int)y0; dst.w = (int)(x1 - x0); dst.h = (int)(y1 - y0);
    return ds_sprite_copy(r, t, &src, &dst, angle, ((mask & DS_K(FLIP_X)) != 0) != facing_left,
                          (mask & DS_K(FLIP_Y)) != 0, tinted, tint, alpha);
  }
}

/* The walk: answers the entities from the first one left to Scheme (or
   whose copy failed: ds_walk_status then holds SDL's status), else '(). */
static C_word ds_sprite_walk(SDL_Renderer *r, SDL_Texture *t, C_word entities, C_word keys,
                             const int *sheet, C_word camera_x, C_word camera_y) {
  C_word es, v[DS_K_COUNT];
  double cx, cy;
  ds_key_table table;
  ds_walk_status = 0;
  ds_walk_mod.t = NULL;
  if (C_header_size(keys) != DS_K_COUNT || !ds_number(camera_x, &cx) || !ds_number(camera_y, &cy))
    return entities;
  ds_key_table_init(&table, keys, DS_K_COUNT);
  for (es = entities; !C_immediatep(es) && C_truep(C_i_pairp(es)); es = C_block_item(es, 1)) {
    int st = ds_sprite_one(r, t, ds_read_keys_with(&table, C_block_item(es, 0), keys, DS_K_COUNT, v),
                           v, sheet, cx, cy);
    if (st == DS_TO_SCHEME) return es;
    if (st < 0) { ds_walk_status = st; return es; }
  }
  return es;
}

/* (downstroke motion)'s C: the motion kernels, steps 2-7 of
   docs/physics.org's pipeline (and tile ground detection): the fixnum
   kernel for entities of small fixnums and exact rationals, the flonum
   kernel for entities of finite flonums. Included by motion.scm, one
   compilation unit with it; the Scheme comments there say why it is C. */

#include "physics/motion.h"
#include "physics/arith.h"
#include "physics/escape.c"
#include <math.h>

static long ds_min(long a, long b) { return a < b ? a : b; }
static long ds_max(long a, long b) { return a > b ? a : b; }

/* A position is n/d: a small fixnum (d = 1) or an exact rational of small
   fixnums in lowest terms. The cells of a span [n/d, n/d + size) on tiles
   of `tile` px: floor(n / (d tile)) to ceil((n + size d) / (d tile)) - 1,
   which is floor((n + size d - 1) / (d tile)): tile-stop's span-first and
   span-last for integers and rationals alike. */
static long ds_first(long n, long d, long tile) { return ds_floor_div(n, d * tile); }
static long ds_last(long n, long d, long size, long tile) {
  return ds_floor_div(n + size * d - 1, d * tile);
}

/* tile-stop: where a body that moved by v (not 0) to pos = pn/pd stops on
   one axis, or 0 when no solid line is in its way; its span on the other
   axis is an/ad .. an/ad + across_size. Cell (line, cell) of the grid is
   byte line*ls + cell*cs, both counted from the map's origin. A stop is
   always a whole pixel. */
static int ds_tile_stop(long v, long pn, long pd, long size, long an, long ad, long across_size,
                        int swept, int one_way, long tile, long tile_across, const unsigned char *bytes,
                        long ls, long cs, long line_origin, long cell_origin,
                        long line_count, long cell_count, long *stop)
{
  /* one_way: one-way cells (byte 2) count where their line's top is at or
     below the body's bottom at the start of the motion, (pn - v pd)/pd +
     size, here in units of 1/pd */
  long start_bottom = one_way ? pn - v * pd + size * pd : 0;
  int forward = v > 0;
  long l0 = ds_first(pn, pd, tile), l1 = ds_last(pn, pd, size, tile);
  long lo = ds_max(ds_first(an, ad, tile_across) - cell_origin, 0);
  long hi = ds_min(ds_last(an, ad, across_size, tile_across) - cell_origin, cell_count - 1);
  long from = forward ? l0 : l1, to = forward ? l1 : l0, line, cell;
  if (swept) {      /* from the cell the leading edge was in before the move,
                       on the side it moves to: floor((s + size) / T) forward,
                       ceil(s / T) - 1 = floor((s - 1/pd) / T) backward */
    long sn = pn - v * pd;
    from = forward ? ds_min(ds_floor_div(sn + size * pd, pd * tile), l0)
                   : ds_max(ds_floor_div(sn - 1, pd * tile), l1);
  }
  from -= line_origin;
  to -= line_origin;
  from = forward ? ds_max(from, 0) : ds_min(from, line_count - 1);
  to = forward ? ds_min(to, line_count - 1) : ds_max(to, 0);
  if (lo > hi || (forward ? from > to : from < to)) return 0;
  for (line = from; ; line += forward ? 1 : -1) {
    const unsigned char *base = bytes + line * ls;
    for (cell = lo; cell <= hi; cell++)
      if (base[cell * cs] &&      /* most cells are empty: one test */
          (base[cell * cs] == 1 ||
           (one_way && DS_ONE_WAY(base[cell * cs]) && (line + line_origin) * tile * pd >= start_bottom))) {
        long at = line + line_origin;
        *stop = forward ? at * tile - size : (at + 1) * tile;
        return 1;
      }
    if (line == to) return 0;
  }
}

/* The grid byte of a cell: 0 outside the map. */
static int ds_cell(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                   long col, long row)
{
  long c = col - col0, r = row - row0;
  return c >= 0 && c < cols && r >= 0 && r < rows ? bytes[r * cols + c] : 0;
}

/* Whether the box [xn/xd, +w) x [yn/yd, +h) covers a solid cell (byte 1).
   Swept mode takes a moving body that starts a frame so out of the tiles
   first (tile-collisions.scm's leave-solids); the kernel leaves such a body to it. */
static int ds_box_solid(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                        long tw, long th, long xn, long xd, long w, long yn, long yd, long h)
{
  long c0 = ds_max(ds_first(xn, xd, tw) - col0, 0), c1 = ds_min(ds_last(xn, xd, w, tw) - col0, cols - 1);
  long r0 = ds_max(ds_first(yn, yd, th) - row0, 0), r1 = ds_min(ds_last(yn, yd, h, th) - row0, rows - 1);
  long r, c;
  for (r = r0; r <= r1; r++)
    for (c = c0; c <= c1; c++)
      if (bytes[r * cols + c] == 1) return 1;
  return 0;
}

/* Whether a slope cell (byte 3) lies where the slope rules could look at
   this body this frame (docs/physics.org, "Slopes"): the columns of
   x .. x + vx widened by a tile and twice the width, the rows of y .. y + vy
   widened by a tile and twice the height, more than any tile pass, escape
   aside (the kernel takes no body inside solid tiles), can move it or its
   foot's cut reach. Such a body takes the readable steps. */
static int ds_near_slope(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                         long tw, long th, long xn, long xd, long w, long vx,
                         long yn, long yd, long h, long vy)
{
  long xa = ds_floor_div(ds_min(xn, xn + vx * xd), xd) - tw - 2 * w - 1;
  long xb = ds_floor_div(ds_max(xn, xn + vx * xd), xd) + tw + 2 * w + 1;
  long ya = ds_floor_div(ds_min(yn, yn + vy * yd), yd) - th - 2 * h - 1;
  long yb = ds_floor_div(ds_max(yn, yn + vy * yd), yd) + th + 2 * h + 1;
  long c0 = ds_max(ds_floor_div(xa, tw) - col0, 0), c1 = ds_min(ds_floor_div(xb, tw) - col0, cols - 1);
  long r0 = ds_max(ds_floor_div(ya, th) - row0, 0), r1 = ds_min(ds_floor_div(yb, th) - row0, rows - 1);
  long r, c;
  for (r = r0; r <= r1; r++)
    for (c = c0; c <= c1; c++)
      if (bytes[r * cols + c] >= 3) return 1;   /* a floor (3) or ceiling (4) slope */
  return 0;
}

/* map is #(cols rows col0 row0 tile-width tile-height). */
/* Fixnums below this stay fixnums, and fit a long, through the sums below:
   2^40 on 64-bit CHICKEN (62-bit fixnums), 2^27 on 32-bit (30-bit). */
#ifdef C_SIXTY_FOUR
# define DS_LIMIT (1L << 40)
# define DS_RATIONALS 1
#else
# define DS_LIMIT (1L << 27)
# define DS_RATIONALS 0
#endif
#define DS_SMALL(o) (C_truep(C_fixnump(o)) && C_unfix(o) < DS_LIMIT && C_unfix(o) > -DS_LIMIT)
#define DS_SIZE(o) (C_truep(C_fixnump(o)) && C_unfix(o) >= 0 && C_unfix(o) < DS_LIMIT)

/* A position the kernel may take, as *n / *d: a small fixnum, or (on
   64-bit) an exact rational of fixnums (bodies pushed apart by halves,
   quarter-pixel starts); ds_room then says whether its digits leave room
   for the sums below. */
static int ds_position(C_word o, long *n, long *d) {
  if (DS_SMALL(o)) { *n = C_unfix(o); *d = 1; return 1; }
  if (DS_RATIONALS && !C_immediatep(o) && C_block_header(o) == C_RATNUM_TAG) {
    C_word num = C_block_item(o, 0), den = C_block_item(o, 1);
    if (C_truep(C_fixnump(num)) && C_truep(C_fixnump(den))) {
      *n = C_unfix(num);
      *d = C_unfix(den);
      return 1;
    }
  }
  return 0;
}

/* The flonum kernel, for a scene without a map: an entity the fixnum
   kernel leaves whose position, velocities, acceleration and gravity are
   finite flonums or small fixnums. Each number is a fixnum or a double,
   and a sum is taken as CHICKEN's + takes it: two fixnums exactly, else
   both as doubles, in the readable steps' order, so every double is the
   one the readable steps make. A sum that is not finite is their error to
   raise: the entity goes to them (-1). Not inlined: its frame lasts
   only as long as the call, and is no part of the C frame of the pass's
   walk (motion.scm's motion-pass), which every body spends of the nursery. */
typedef struct { int flo; long n; double d; } ds_num;

/* the helpers below are inlined into ds_flonum_motion, their one caller */
#define DS_INLINE static inline __attribute__((always_inline))

DS_INLINE int ds_num_of(C_word o, ds_num *v) {
  if (DS_SMALL(o)) { v->flo = 0; v->n = C_unfix(o); return 1; }
  if (!C_immediatep(o) && C_block_header(o) == C_FLONUM_TAG) {
    double d = C_flonum_magnitude(o);
    if (d - d != 0.0) return 0;          /* an infinity or a NaN */
    v->flo = 1; v->d = d; return 1;
  }
  return 0;
}

DS_INLINE ds_num ds_num_add(ds_num a, ds_num b) {
  ds_num r;
  if (!a.flo && !b.flo) { r.flo = 0; r.n = a.n + b.n; }
  else { r.flo = 1; r.d = (a.flo ? a.d : (double)a.n) + (b.flo ? b.d : (double)b.n); }
  return r;
}

/* whether the Scheme value o is the number v already: the same fixnum, or
   a flonum of the same bits (so -0.0 is not 0.0) */
DS_INLINE int ds_num_is(C_word o, ds_num v) {
  if (!v.flo) return o == C_fix(v.n);
  return !C_immediatep(o) && C_block_header(o) == C_FLONUM_TAG &&
         memcmp(&C_flonum_magnitude(o), &v.d, sizeof(double)) == 0;
}

/* Where the flonum kernel's doubles wait, read right after the call by
   motion.scm's kernel-number as ds_flonum_out_ref (a new flonum): a C
   array, not a Scheme vector, so reading one needs no type or bounds
   check and no lookup of a global. */
static double ds_flonum_out[4];
#define ds_flonum_out_ref(ptr, c, slot) C_flonum(ptr, ds_flonum_out[C_unfix(slot)])

/* Puts v in out[slot], or, a double, in ds_flonum_out[slot] with the flonum bit. */
DS_INLINE int ds_num_put(C_word out, int slot, ds_num v, int flonum_bit) {
  if (!v.flo) { C_set_block_item(out, slot, C_fix(v.n)); return 0; }
  ds_flonum_out[slot] = v.d;
  return flonum_bit;
}

DS_INLINE ds_num ds_num_sub(ds_num a, ds_num b) {
  ds_num r;
  if (!a.flo && !b.flo) { r.flo = 0; r.n = a.n - b.n; }
  else { r.flo = 1; r.d = (a.flo ? a.d : (double)a.n) - (b.flo ? b.d : (double)b.n); }
  return r;
}

DS_INLINE ds_num ds_num_int(long n) { ds_num r; r.flo = 0; r.n = n; return r; }
DS_INLINE int ds_num_zero(ds_num v) { return v.flo ? v.d == 0.0 : v.n == 0; }
DS_INLINE int ds_num_positive(ds_num v) { return v.flo ? v.d > 0.0 : v.n > 0; }

/* The flonums the map kernel takes: below 2^40 in magnitude, so that
   every tile index below is a whole double well inside 2^53 and every
   sum of two of them is exact. A body beyond is left to the readable
   steps (whose indices there may be bignums). */
#define DS_FLO_LIMIT 1099511627776.0
DS_INLINE int ds_num_near(ds_num v) { return !v.flo || (v.d < DS_FLO_LIMIT && v.d > -DS_FLO_LIMIT); }

/* tile-grid.scm's cell arithmetic on a fixnum or a double, as Scheme
   computes it: floor-div for an integer; for a flonum one IEEE division
   by the tile size, then floor or ceiling. The answer is a whole double. */
DS_INLINE double ds_span_first(ds_num p, long tile) {     /* also cell-of */
  return p.flo ? floor(p.d / (double)tile) : (double)ds_floor_div(p.n, tile);
}
DS_INLINE double ds_span_last(ds_num p, long size, long tile) {
  return p.flo ? ceil((p.d + (double)size) / (double)tile) - 1.0
               : (double)ds_floor_div(p.n + size - 1, tile);
}
DS_INLINE double ds_cell_ceiling(ds_num p, long tile) {
  return p.flo ? ceil(p.d / (double)tile) : (double)(ds_floor_div(p.n - 1, tile) + 1);
}

/* Whether `line * tile` (an exact integer, a whole pixel) is at or past
   `top`, compared as Scheme compares an integer with a flonum: exactly
   (the product is well inside 2^53, so its double is exact). */
DS_INLINE int ds_at_or_past(long at_px, ds_num top) {
  return top.flo ? (double)at_px >= top.d : at_px >= top.n;
}

/* tile-collisions.scm's tile-stop for fixnum-or-flonum numbers: where a
   body that moved by v (not 0) to pos stops on one axis, or 0 when no
   solid line is in its way. start is where the frame's motion on this
   axis started; lines and cells as in ds_tile_stop. The stop is a whole
   pixel, a fixnum, as tile-push-pos makes it. */
DS_INLINE int ds_flo_tile_stop(ds_num v, ds_num pos, long size, ds_num across, long across_size,
                               int swept, ds_num start, int one_way, long tile, long tile_across,
                               const unsigned char *bytes, long ls, long cs, long line_origin,
                               long cell_origin, long line_count, long cell_count, long *stop)
{
  int forward = ds_num_positive(v);
  double l0 = ds_span_first(pos, tile), l1 = ds_span_last(pos, size, tile);
  double lo = ds_span_first(across, tile_across) - (double)cell_origin;
  double hi = ds_span_last(across, across_size, tile_across) - (double)cell_origin;
  ds_num top = one_way ? ds_num_add(start, ds_num_int(size)) : ds_num_int(0);
  double from, to;
  long line, cell, ilo, ihi, ifrom, ito;
  if (forward) {
    from = l0;
    if (swept) { double s = ds_span_first(ds_num_add(start, ds_num_int(size)), tile); if (s < from) from = s; }
    to = l1;
  } else {
    from = l1;
    if (swept) { double s = ds_cell_ceiling(start, tile) - 1.0; if (s > from) from = s; }
    to = l0;
  }
  from -= (double)line_origin;
  to -= (double)line_origin;
  if (lo < 0.0) lo = 0.0;
  if (hi > (double)(cell_count - 1)) hi = (double)(cell_count - 1);
  if (forward) { if (from < 0.0) from = 0.0; if (to > (double)(line_count - 1)) to = (double)(line_count - 1); }
  else { if (from > (double)(line_count - 1)) from = (double)(line_count - 1); if (to < 0.0) to = 0.0; }
  if (lo > hi || (forward ? from > to : from < to)) return 0;
  ilo = (long)lo; ihi = (long)hi; ifrom = (long)from; ito = (long)to;
  for (line = ifrom; ; line += forward ? 1 : -1) {
    const unsigned char *base = bytes + line * ls;
    for (cell = ilo; cell <= ihi; cell++)
      if (base[cell * cs] &&
          (base[cell * cs] == 1 ||
           (one_way && DS_ONE_WAY(base[cell * cs]) && ds_at_or_past((line + line_origin) * tile, top)))) {
        long at = line + line_origin;
        *stop = forward ? at * tile - size : (at + 1) * tile;
        return 1;
      }
    if (line == ito) return 0;
  }
}

/* The grid byte of the cell (col, row), whole doubles: 0 outside the map. */
DS_INLINE int ds_cell_at(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                         double col, double row)
{
  double c = col - (double)col0, r = row - (double)row0;
  return c >= 0.0 && c < (double)cols && r >= 0.0 && r < (double)rows ? bytes[(long)r * cols + (long)c] : 0;
}

/* Whether the box [x, x + w) x [y, y + h) covers a solid cell (byte 1):
   the escape's question (escape.scm), whose answer the kernel leaves to it. */
DS_INLINE int ds_flo_box_solid(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                               long tw, long th, ds_num x, long w, ds_num y, long h)
{
  double c0 = ds_span_first(x, tw) - (double)col0, c1 = ds_span_last(x, w, tw) - (double)col0;
  double r0 = ds_span_first(y, th) - (double)row0, r1 = ds_span_last(y, h, th) - (double)row0;
  long r, c;
  if (c0 < 0.0) c0 = 0.0;
  if (r0 < 0.0) r0 = 0.0;
  if (c1 > (double)(cols - 1)) c1 = (double)(cols - 1);
  if (r1 > (double)(rows - 1)) r1 = (double)(rows - 1);
  if (c0 > c1 || r0 > r1) return 0;
  for (r = (long)r0; r <= (long)r1; r++)
    for (c = (long)c0; c <= (long)c1; c++)
      if (bytes[r * cols + c] == 1) return 1;
  return 0;
}

/* The escape's number (escape.c) for a kernel number, 0 when the escape's
   C does not take it (a fixnum beyond its range). */
DS_INLINE int ds_esc_of(ds_num v, int size, ds_esc_num *e) {
  return ds_esc_plain(v.flo, v.n, v.d, size, e);
}

/* Scheme's eqv? of two kernel numbers: the same fixnum, or doubles of the
   same bits */
DS_INLINE int ds_num_eqv(ds_num a, ds_num b) {
  if (a.flo != b.flo) return 0;
  return a.flo ? memcmp(&a.d, &b.d, sizeof(double)) == 0 : a.n == b.n;
}

/* escape.scm's step-on: the next double after p toward the sign of d (p
   itself when d is the fixnum 0 or p is a fixnum) */
DS_INLINE ds_num ds_num_step_on(ds_num p, ds_num d) {
  if ((!d.flo && d.n == 0) || !p.flo) return p;
  p.d = nextafter(p.d, (d.flo ? d.d < 0.0 : d.n < 0) ? -INFINITY : INFINITY);
  return p;
}

/* escape.scm's escape-place, for a box of fixnum size at (x, y) of
   integers and doubles inside solid tiles, where the escape's search ends
   with a straight move: escape.c decides the move (ds_escape_decide, the
   race, and ds_esc_diagonal_may, whether a move on both axes could be
   nearer), and the move's numbers are made here as escape.scm makes
   them, with Scheme's generic operations taken as ds_num_add takes them,
   then settled on as escape-place settles a flonum move. 1 with (*nx,
   *ny); 0 when the escape's C does not take the numbers, or the search
   on both axes may be needed: the readable steps then run it. */
static int ds_flo_escape(const unsigned char *bytes, long long nbytes, C_word map, long tw, long th,
                         ds_num x, ds_num y, long w, long h, ds_num *nx, ds_num *ny)
{
  ds_esc_num ex, ey, ew, eh, dist;
  ds_num dx, dy, zero = ds_num_int(0);
  C_word r;
  long long p, line;
  int i, tries;
  if (!(ds_esc_of(x, 0, &ex) && ds_esc_of(y, 0, &ey) && ds_esc_of(ds_num_int(w), 1, &ew) &&
        ds_esc_of(ds_num_int(h), 1, &eh)))
    return 0;
  r = ds_escape_decide(bytes, nbytes, map, 1, ex, ey, ew, eh);
  if (r == C_SCHEME_FALSE) return 0;
  if (r == C_SCHEME_TRUE) { *nx = x; *ny = y; return 1; }
  i = (int)(C_unfix(r) & 3);
  line = (C_unfix(r) - i) / 4;
  /* runner-place and runner-move */
  p = i == 0 ? line * th - h : i == 1 ? (line + 1) * th : i == 2 ? line * tw - w : (line + 1) * tw;
  dx = i < 2 ? zero : ds_num_sub(ds_num_int((long)p), x);
  dy = i < 2 ? ds_num_sub(ds_num_int((long)p), y) : zero;
  {
    ds_num m = (!dx.flo && dx.n == 0) ? dy : dx;
    if (!ds_esc_of(m, 0, &dist)) return 0;
    if (dist.flo) dist.f = fabs(dist.f); else if (dist.n < 0) dist.n = -dist.n;
    if (ds_esc_diagonal_may(dist, ex, ey, ew, eh, tw, th)) return 0;
  }
  if (!dx.flo && dx.n == 0 && !dy.flo && dy.n == 0) { *nx = x; *ny = y; return 1; }
  *nx = ds_num_add(x, dx);
  *ny = ds_num_add(y, dy);
  for (tries = 0; tries < 8; tries++) {
    ds_esc_num fx, fy;
    if (!(ds_num_near(*nx) && ds_num_near(*ny) && ds_esc_of(*nx, 0, &fx) && ds_esc_of(*ny, 0, &fy)))
      return 0;
    r = ds_escape_decide(bytes, nbytes, map, 0, fx, fy, ew, eh);
    if (r == C_SCHEME_FALSE) return 0;
    if (r == C_SCHEME_TRUE) break;
    *nx = ds_num_step_on(*nx, dx);
    *ny = ds_num_step_on(*ny, dy);
  }
  return 1;
}

/* Whether a map's tile stops, in whole pixels, stay small fixnums: every
   line of cells inside the map, times the tile size, within DS_LIMIT
   (with room for a body's size), on both axes. */
static int ds_map_small(long cols, long rows, long col0, long row0, long tw, long th) {
  double reach_x = (fabs((double)col0) + (double)cols + 1.0) * (double)tw;
  double reach_y = (fabs((double)row0) + (double)rows + 1.0) * (double)th;
  return tw > 0 && th > 0 && reach_x < (double)DS_LIMIT / 2 && reach_y < (double)DS_LIMIT / 2;
}

/* The flonum kernel: an entity the fixnum kernel leaves whose position,
   velocities, acceleration and gravity are finite flonums or small
   fixnums, and whose size is a small fixnum. Without a map: the
   velocity steps. With one (bytes and map as for ds_fixnum_motion): the
   tile steps too, discrete or swept, as tile-collisions.scm takes them
   on a map without slopes; a map with slopes, a body inside solid tiles
   at the start of a swept frame (the escape's), a number beyond
   DS_FLO_LIMIT, is left to the readable steps (-1). Each number is a
   fixnum or a double, and each operation is taken as CHICKEN's generic
   one takes it: two fixnums exactly, else both as doubles, in the
   readable steps' order, so every double is the one the readable steps
   make. A sum that is not finite is their error to raise: the entity
   goes to them (-1). Not inlined: its frame lasts only as long as the
   call, and is no part of the C frame of the pass's walk (motion.scm's
   motion-pass), which every body spends of the nursery. */
static C_word __attribute__((noinline)) ds_flonum_motion(C_word out, C_word grid, C_word map,
                               C_word flags_, C_word gravity_, C_word skips,
                               C_word x_, C_word y_, C_word w_, C_word h_,
                               C_word vx_, C_word vy_, C_word ay_, C_word on)
{
  long flags = C_unfix(flags_);
  int grav = (flags & DS_GRAVITY) != 0, has_map = (flags & DS_HAS_MAP) != 0, writes = 0;
  int swept = (flags & DS_SWEPT) != 0, x_stopped = 0, y_stopped = 0;
  ds_num x, y, vx, vy0, ay, g, vy, x2, y2;
  long cols = 0, rows = 0, col0 = 0, row0 = 0, tw = 1, th = 1, w, h, stop;
  const unsigned char *bytes = NULL;
  if ((flags & (DS_NOT_HERE | DS_SLOPES)) || (skips != C_SCHEME_FALSE && skips != C_SCHEME_END_OF_LIST) ||
      !DS_SIZE(w_) || !DS_SIZE(h_) ||
      !(ds_num_of(x_, &x) && ds_num_of(y_, &y) && ds_num_of(vx_, &vx) && ds_num_of(vy_, &vy0)) ||
      (grav && !(ds_num_of(ay_, &ay) && ds_num_of(gravity_, &g))))
    return C_fix(-1);
  w = C_unfix(w_);
  h = C_unfix(h_);
  if (has_map) {
    bytes = C_c_u8vector(grid);         /* the u8vector's bytes, only now */
    cols = C_unfix(C_block_item(map, 0)); rows = C_unfix(C_block_item(map, 1));
    col0 = C_unfix(C_block_item(map, 2)); row0 = C_unfix(C_block_item(map, 3));
    tw = C_unfix(C_block_item(map, 4)); th = C_unfix(C_block_item(map, 5));
    if (!ds_map_small(cols, rows, col0, row0, tw, th) || !ds_num_near(x) || !ds_num_near(y))
      return C_fix(-1);
  }
  /* acceleration: an #:ay of fixnum 0 that is present is nothing to consume */
  int accelerate = grav && !(ay_ == C_fix(0) && (flags & DS_HAS_AY));
  vy = accelerate ? ds_num_add(vy0, ay) : vy0;
  if (grav) vy = ds_num_add(vy, g);
  x2 = ds_num_add(x, vx);
  if (vy.flo && vy.d - vy.d != 0.0) return C_fix(-1);
  if (has_map) {
    ds_num sx;
    if (!ds_num_near(x2)) return C_fix(-1);
    /* the x pass: a swept body that moves first leaves solid tiles from
       where its frame started, (x2 - vx, y + 0) (leave-solids): the
       kernel takes only a body already out of them, which the escape
       leaves where it is, and not a y of -0.0, which y + 0 would make
       0.0 there */
    sx = ds_num_sub(x2, vx);
    if (swept && !(ds_num_zero(vx) && ds_num_zero(vy))) {
      if ((y.flo && y.d == 0.0 && signbit(y.d)) || !ds_num_near(sx)) return C_fix(-1);
      if (ds_flo_box_solid(bytes, cols, rows, col0, row0, tw, th, sx, w, y, h)) {
        /* inside solid tiles: leave-solids, where the escape takes the
           body by a straight move (ds_flo_escape); the body keeps its
           distance from the start, and the x pass starts where the
           escape put it */
        ds_num nx, ny;
        if (!(flags & DS_ESCAPE)) return C_fix(DS_INSIDE);
        if (!ds_flo_escape(bytes, C_unfix(C_u_i_8vector_length(grid)), map, tw, th, sx, y, w, h, &nx, &ny))
          return C_fix(-1);
        if (!ds_num_eqv(nx, sx)) x2 = ds_num_add(nx, vx);
        if (!ds_num_eqv(ny, y)) y = ds_num_add(ny, ds_num_int(0));
        sx = nx;
        if (!ds_num_near(x2) || !ds_num_near(y) || !ds_num_near(sx)) return C_fix(-1);
      }
    }
    if (!ds_num_zero(vx) &&
        ds_flo_tile_stop(vx, x2, w, y, h, swept, sx, 0, tw, th, bytes, 1, cols, col0, row0, cols, rows,
                         &stop)) {
      x_stopped = 1;
      x2 = ds_num_int(stop);
    }
  }
  y2 = ds_num_add(y, vy);
  if ((x2.flo && x2.d - x2.d != 0.0) || (y2.flo && y2.d - y2.d != 0.0))
    return C_fix(-1);
  if (has_map) {
    /* the y pass, from y2 - vy, where this frame's y motion started */
    ds_num sy = ds_num_sub(y2, vy);
    if (!ds_num_near(y2) || !ds_num_near(sy)) return C_fix(-1);
    if (!ds_num_zero(vy) &&
        ds_flo_tile_stop(vy, y2, h, x2, w, swept, sy, ds_num_positive(vy) && !(flags & DS_DROP), th, tw,
                         bytes, cols, 1, row0, col0, rows, cols, &stop)) {
      y_stopped = 1;
      y2 = ds_num_int(stop);
    }
  }
  /* ground detection (step 8), on the tiles only: with ground? no entity
     is solid. The row one pixel below the feet, (y + h) + 1, under either
     lower corner (tile-collisions.scm's box-ground?). */
  C_word ground = C_SCHEME_FALSE;
  if ((flags & DS_GROUND) && grav && has_map) {
    ds_num bottom = ds_num_add(y2, ds_num_int(h));
    double row = ds_span_first(ds_num_add(bottom, ds_num_int(1)), th);
    double c0 = ds_span_first(x2, tw), c1 = ds_span_last(x2, w, tw);
    int b0, b1;
    if (c1 < c0) c1 = c0;
    b0 = ds_cell_at(bytes, cols, rows, col0, row0, c0, row);
    b1 = b0 == 1 ? 0 : ds_cell_at(bytes, cols, rows, col0, row0, c1, row);
    /* a one-way tile holds a body whose bottom is at or above its top;
       such a cell is inside the map, so row * th is a small fixnum */
    ground = C_mk_bool(b0 == 1 || b1 == 1 ||
                       ((DS_ONE_WAY(b0) || DS_ONE_WAY(b1)) && !(flags & DS_DROP) &&
                        (bottom.flo ? bottom.d <= (double)((long)row * th) : bottom.n <= (long)row * th)));
  }
  if (!((flags & DS_HAS_X) && ds_num_is(x_, x2)))
    writes |= DS_WRITE_X | ds_num_put(out, 0, x2, DS_X_FLONUM);
  if (!((flags & DS_HAS_Y) && ds_num_is(y_, y2)))
    writes |= DS_WRITE_Y | ds_num_put(out, 1, y2, DS_Y_FLONUM);
  if (x_stopped && !((flags & DS_HAS_VX) && vx_ == C_fix(0))) {
    C_set_block_item(out, 2, C_fix(0));
    writes |= DS_WRITE_VX;
  }
  if (y_stopped || grav) {
    ds_num v = y_stopped ? ds_num_int(0) : vy;
    if (!((flags & DS_HAS_VY) && ds_num_is(vy_, v)))
      writes |= DS_WRITE_VY | ds_num_put(out, 3, v, DS_VY_FLONUM);
  }
  if (accelerate) {                    /* consumed: a fixnum 0 */
    C_set_block_item(out, 4, C_fix(0));
    writes |= DS_WRITE_AY;
  }
  if ((flags & DS_GROUND) && grav && !((flags & DS_HAS_ON) && on == ground)) {
    C_set_block_item(out, 5, ground);   /* without a map: no tile, and no solid entity */
    writes |= DS_WRITE_ON;
  }
  return C_fix(writes);
}

/* Whether a rational position n/d leaves room for the kernel's sums: every
   one is n plus a few multiples of d by a velocity, a size, a tile size or
   a pixel the body spans (each at most m), within 2^61 when
   |n| + 8 m d is (64-bit only; integers are small fixnums, which always
   have room). */
static int ds_room(long n, long d, long m) {
#ifdef C_SIXTY_FOUR
  long limit = 1L << 61, a = n < 0 ? -n : n;
  return d == 1 || (a < limit && d <= (limit - a) / (8 * m));
#else
  return d == 1;
#endif
}

/* -1 when this entity is not for this code (a number the kernel does not
   take, a non-empty #:skip-pipelines, an unknown mode: DS_NOT_HERE), else
   the keys to write. Velocities are fixnums, so a rational position keeps
   its denominator (n/d + v = (n + v d)/d, still in lowest terms) until a
   tile stops it on a whole pixel. */
static C_word ds_fixnum_motion(C_word out, const unsigned char *bytes, C_word map,
                               C_word flags_, C_word gravity_, C_word skips,
                               C_word x_, C_word y_, C_word w_, C_word h_,
                               C_word vx_, C_word vy_, C_word ay_, C_word on)
{
  long flags = C_unfix(flags_), g;
  long xn, xd, yn, yd;
  /* *gravity* may have been tuned to any number: only a small fixnum is ours */
  if ((flags & DS_NOT_HERE) || (skips != C_SCHEME_FALSE && skips != C_SCHEME_END_OF_LIST) ||
      !(ds_position(x_, &xn, &xd) && ds_position(y_, &yn, &yd) && DS_SMALL(vx_) && DS_SMALL(vy_) &&
        DS_SIZE(w_) && DS_SIZE(h_) &&
        (!(flags & DS_GRAVITY) || (DS_SMALL(ay_) && DS_SMALL(gravity_)))))
    return C_fix(-1);
  g = C_unfix(gravity_);
  long w = C_unfix(w_), h = C_unfix(h_);
  long vx = C_unfix(vx_), vy0 = C_unfix(vy_), ay = C_unfix(ay_);
  long cols = C_unfix(C_block_item(map, 0)), rows = C_unfix(C_block_item(map, 1));
  long col0 = C_unfix(C_block_item(map, 2)), row0 = C_unfix(C_block_item(map, 3));
  long tw = C_unfix(C_block_item(map, 4)), th = C_unfix(C_block_item(map, 5));
  int has_map = flags & DS_HAS_MAP, grav = flags & DS_GRAVITY, swept = (flags & DS_SWEPT) != 0;
  if (xd > 1 || yd > 1) {              /* the largest multiplier of a denominator below */
    long vy_reach = (vy0 < 0 ? -vy0 : vy0) + (grav ? (ay < 0 ? -ay : ay) + (g < 0 ? -g : g) : 0);
    long m = ds_max(ds_max(ds_max(vx, -vx), vy_reach), ds_max(ds_max(w, h), ds_max(tw, th))) + 2;
    if (!(ds_room(xn, xd, m) && ds_room(yn, yd, m))) return C_fix(-1);
  }
  int accelerate = grav && !(ay == 0 && (flags & DS_HAS_AY));
  long vy = grav ? (accelerate ? vy0 + ay : vy0) + g : vy0;
  if ((flags & DS_SLOPES) &&          /* set only with a map */
      ds_near_slope(bytes, cols, rows, col0, row0, tw, th, xn, xd, w, vx, yn, yd, h, vy))
    return C_fix(-1);
  if (has_map && swept && (vx != 0 || vy != 0) &&
      ds_box_solid(bytes, cols, rows, col0, row0, tw, th, xn, xd, w, yn, yd, h))
    return C_fix(-1);
  long x2n = xn + vx * xd, x2d = xd, y2n, y2d = yd, stop;
  int x_stopped = 0, y_stopped = 0, writes = 0;
  if (has_map && vx != 0 &&
      ds_tile_stop(vx, x2n, x2d, w, yn, yd, h, swept, 0, tw, th, bytes, 1, cols, col0, row0, cols, rows,
                   &stop)) {
    x_stopped = 1;
    x2n = stop;
    x2d = 1;
  }
  y2n = yn + vy * yd;
  if (has_map && vy != 0 &&
      ds_tile_stop(vy, y2n, y2d, h, x2n, x2d, w, swept, vy > 0 && !(flags & DS_DROP), th, tw, bytes,
                   cols, 1, row0, col0, rows, cols, &stop)) {
    y_stopped = 1;
    y2n = stop;
    y2d = 1;
  }
  if (!((flags & DS_HAS_X) && xn == x2n && xd == x2d)) {
    C_set_block_item(out, 0, C_fix(x2n));
    writes |= DS_WRITE_X;
    if (x2d != 1) { C_set_block_item(out, 6, C_fix(x2d)); writes |= DS_X_RATIO; }
  }
  if (!((flags & DS_HAS_Y) && yn == y2n && yd == y2d)) {
    C_set_block_item(out, 1, C_fix(y2n));
    writes |= DS_WRITE_Y;
    if (y2d != 1) { C_set_block_item(out, 7, C_fix(y2d)); writes |= DS_Y_RATIO; }
  }
  if (x_stopped && !((flags & DS_HAS_VX) && vx == 0)) {
    C_set_block_item(out, 2, C_fix(0));
    writes |= DS_WRITE_VX;
  }
  if (y_stopped || grav) {
    long v = y_stopped ? 0 : vy;
    if (!((flags & DS_HAS_VY) && vy0 == v)) { C_set_block_item(out, 3, C_fix(v)); writes |= DS_WRITE_VY; }
  }
  if (accelerate && !((flags & DS_HAS_AY) && ay == 0)) {
    C_set_block_item(out, 4, C_fix(0));
    writes |= DS_WRITE_AY;
  }
  if ((flags & DS_GROUND) && grav) {   /* the row one pixel below the feet */
    long row = ds_floor_div(y2n + (h + 1) * y2d, y2d * th);
    long c0 = ds_first(x2n, x2d, tw), c1 = ds_max(c0, ds_last(x2n, x2d, w, tw));
    int b0 = has_map ? ds_cell(bytes, cols, rows, col0, row0, c0, row) : 0;
    int b1 = has_map && b0 != 1 ? ds_cell(bytes, cols, rows, col0, row0, c1, row) : 0;
    /* a one-way tile holds a body whose bottom is at or above its top */
    C_word ground = C_mk_bool(b0 == 1 || b1 == 1 ||
                              ((DS_ONE_WAY(b0) || DS_ONE_WAY(b1)) && !(flags & DS_DROP) &&
                               y2n + h * y2d <= row * th * y2d));
    if (!((flags & DS_HAS_ON) && on == ground)) { C_set_block_item(out, 5, ground); writes |= DS_WRITE_ON; }
  }
  return C_fix(writes);
}

/* (downstroke escape)'s C: the first part of the escape search, the test
   whether a box covers a solid tile and the race of the four straight
   moves (escape.scm's search-way-out and shortest-straight), for boxes
   whose numbers it can take exactly. Included by escape.scm, one
   compilation unit with it; the Scheme comments there say what the
   search is and why this part is C.

   It answers only which straight move wins and the tile line that ends
   it; escape.scm computes the move's numbers from those with the same
   Scheme arithmetic as before, so they are the same numbers. What it
   must get exactly right is every decision: the cells a span covers,
   and which of two moves has gone less far. */

#include <math.h>

/* Integers, a position's integer part and every tile edge of the map stay
   below 2^24 in magnitude, so a distance is below 2^26 and its square
   below 2^52: a double holds each exactly, whatever the fixnums' width. */
#define DS_ESC_LIMIT (1LL << 24)
/* Cell indices made from a flonum are clamped here: far past the map on
   the same side, so every comparison with the map's lines is unchanged. */
#define DS_ESC_CLAMP (1LL << 40)

/* Exact rational positions n/d (fixnums, d below 2^48) on 64-bit builds
   with 128-bit integers: a distance's numerator is then below 2^75, and
   the product of one with the other's denominator below 2^123. */
#if defined(C_SIXTY_FOUR) && defined(__SIZEOF_INT128__)
typedef __int128 ds_esc_wide;
# define DS_ESC_RATIONALS 1
# define DS_ESC_DEN_LIMIT (1LL << 48)
#else
typedef long long ds_esc_wide;
# define DS_ESC_RATIONALS 0
#endif

/* A number as the search holds it: exact n/d (d >= 1, lowest terms), or
   the double f. */
typedef struct { int flo; ds_esc_wide n; long long d; double f; } ds_esc_num;

static long long ds_esc_floor(long long a, long long d) {   /* floor(a / d), d > 0 */
  return a >= 0 ? a / d : (a + 1) / d - 1;
}
static long long ds_esc_ceil(long long a, long long d) { return -ds_esc_floor(-a, d); }

/* A fixnum n or a finite double f (flo) as the search holds it: a
   coordinate (size 0) of magnitude below DS_ESC_LIMIT, or a size (size 1)
   not negative and, a fixnum, below it. 0 for anything else. */
static int ds_esc_plain(int flo, long long n, double f, int size, ds_esc_num *v) {
  if (!flo) {
    if (n >= DS_ESC_LIMIT || n < (size ? 0 : -DS_ESC_LIMIT + 1)) return 0;
    v->flo = 0; v->n = n; v->d = 1;
    return 1;
  }
  if (f - f != 0.0 || (size && !(f >= 0.0))) return 0;   /* NaN, an infinity */
  v->flo = 1; v->f = f; v->d = 1;
  return 1;
}

/* Reads a coordinate (size 0) or a size (size 1): a fixnum or finite
   flonum as ds_esc_plain takes it, or a position that is a rational of
   fixnums as above. 0 for anything else, which the Scheme search takes. */
static int ds_esc_read(C_word o, int size, ds_esc_num *v) {
  if (o & C_FIXNUM_BIT) return ds_esc_plain(0, C_unfix(o), 0.0, size, v);
  if (C_immediatep(o)) return 0;
  if (C_block_header(o) == C_FLONUM_TAG) return ds_esc_plain(1, 0, C_flonum_magnitude(o), size, v);
#if DS_ESC_RATIONALS
  if (!size && C_block_header(o) == C_RATNUM_TAG) {
    C_word a = C_block_item(o, 0), b = C_block_item(o, 1);
    long long n, d, q;
    if (!(a & C_FIXNUM_BIT) || !(b & C_FIXNUM_BIT)) return 0;
    n = C_unfix(a); d = C_unfix(b);
    if (d <= 1 || d >= DS_ESC_DEN_LIMIT) return 0;
    q = ds_esc_floor(n, d);
    if (q >= DS_ESC_LIMIT - 1 || q < -DS_ESC_LIMIT + 1) return 0;
    v->flo = 0; v->n = n; v->d = d;
    return 1;
  }
#endif
  return 0;
}

/* A double cell index as an integer, clamped; 0 where Scheme could not
   make it exact (an infinity: its search raises the error). */
static int ds_esc_index(double q, long long *out) {
  if (q - q != 0.0) return 0;
  if (q > (double)DS_ESC_CLAMP) q = (double)DS_ESC_CLAMP;
  if (q < -(double)DS_ESC_CLAMP) q = -(double)DS_ESC_CLAMP;
  *out = (long long)q;
  return 1;
}

static double ds_esc_double(ds_esc_num v) { return v.flo ? v.f : (double)v.n; }   /* d is 1 here */

/* tile-grid.scm's span-first, floor(pos / tile): for a rational,
   floor(floor(n/d) / tile), the same integer. */
static int ds_esc_first(ds_esc_num p, long long tile, long long *out) {
  if (p.flo) return ds_esc_index(floor(p.f / (double)tile), out);
  *out = ds_esc_floor(ds_esc_floor((long long)p.n, p.d), tile);
  return 1;
}

/* span-last: floor((pos + size - 1) / tile) for integers, else
   ceiling((pos + size) / tile) - 1, in doubles when either is a flonum
   (Scheme's + and / take a fixnum as a double), and for a rational
   ceiling((ceiling(n/d) + size) / tile) - 1, the same integer. A size
   is never a rational here. */
static int ds_esc_last(ds_esc_num p, ds_esc_num s, long long tile, long long *out) {
  if (p.flo || s.flo) {
    long long q;
    if (!ds_esc_index(ceil((ds_esc_double(p) + ds_esc_double(s)) / (double)tile), &q)) return 0;
    *out = q - 1;
  } else if (p.d == 1)
    *out = ds_esc_floor((long long)p.n + (long long)s.n - 1, tile);
  else
    *out = ds_esc_ceil(ds_esc_ceil((long long)p.n, p.d) + (long long)s.n, tile) - 1;
  return 1;
}

/* tile-grid.scm's axis-grid: cell (line, cell) is byte line*ls + cell*cs,
   both counted from the origins */
typedef struct {
  const unsigned char *bytes;
  long long ls, cs, line_origin, cell_origin, line_count, cell_count;
} ds_esc_grid;

/* nearest-solid-line without one-way cells: the nearest line from `from`
   to `to` (step +1 or -1) holding a solid cell (byte 1) in cells lo..hi,
   in *line; 0 when none does. */
static int ds_esc_nearest(const ds_esc_grid *g, long long from, long long to, int step,
                          long long lo, long long hi, long long *line) {
  long long last = g->line_count - 1, l, c;
  lo -= g->cell_origin; hi -= g->cell_origin;
  if (lo < 0) lo = 0;
  if (hi > g->cell_count - 1) hi = g->cell_count - 1;
  from -= g->line_origin; to -= g->line_origin;
  if (step > 0) { if (from < 0) from = 0; if (to > last) to = last; }
  else { if (from > last) from = last; if (to < 0) to = 0; }
  if (lo > hi || (step > 0 ? from > to : from < to)) return 0;
  for (l = from; ; l += step) {
    const unsigned char *base = g->bytes + l * g->ls;
    for (c = lo; c <= hi; c++)
      if (base[c * g->cs] == 1) { *line = l + g->line_origin; return 1; }
    if (l == to) return 0;
  }
}

/* escape.scm's blocking: the solid line of the box nearest its side
   `toward` along the grid's axis, in *line, *found 0 when the box is
   free; 0 when a span is not for this code. */
static int ds_esc_blocking(const ds_esc_grid *g, ds_esc_num pos, ds_esc_num size, long long tile,
                           ds_esc_num across, ds_esc_num across_size, long long tile_across,
                           int toward, int *found, long long *line) {
  long long l0, l1, a0, a1;
  if (!(ds_esc_first(pos, tile, &l0) && ds_esc_last(pos, size, tile, &l1) &&
        ds_esc_first(across, tile_across, &a0) && ds_esc_last(across, across_size, tile_across, &a1)))
    return 0;
  *found = ds_esc_nearest(g, toward > 0 ? l1 : l0, toward > 0 ? l0 : l1, -toward, a0, a1, line);
  return 1;
}

/* How far a runner has gone, at - base, as Scheme's - gives it: exact when
   both are, else a double. */
static ds_esc_num ds_esc_minus(ds_esc_num at, ds_esc_num base) {
  ds_esc_num r;
  if (!at.flo && !base.flo) {   /* at is base itself (0) or an integer */
    r.flo = 0; r.d = base.d;
    r.n = at.d == 1 ? at.n * base.d - base.n : 0;
  } else {
    r.flo = 1; r.f = ds_esc_double(at) - ds_esc_double(base);
  }
  return r;
}

/* Scheme's (< (square a) (square b)): exact squares compare as the
   magnitudes do, cross-multiplied; with a double, both squares are
   doubles, an exact one (an integer below 2^26) exactly. */
static int ds_esc_less(ds_esc_num a, ds_esc_num b) {
  if (!a.flo && !b.flo) {
    ds_esc_wide x = a.n < 0 ? -a.n : a.n, y = b.n < 0 ? -b.n : b.n;
    return x * b.d < y * a.d;
  }
  return (a.flo ? a.f * a.f : (double)(a.n * a.n)) < (b.flo ? b.f * b.f : (double)(b.n * b.n));
}

/* A coordinate a runner moves to: escape.scm's runner-place. */
static ds_esc_num ds_esc_place(int i, long long line, long long tw, long long th, ds_esc_num w, ds_esc_num h) {
  ds_esc_num r, size = i < 2 ? h : w;
  long long tile = i < 2 ? th : tw;
  r.flo = 0; r.d = 1;
  if (i == 1 || i == 3) r.n = (line + 1) * tile;
  else if (size.flo) { r.flo = 1; r.f = (double)(line * tile) - size.f; }
  else r.n = line * tile - size.n;
  return r;
}

/* escape.scm's diagonal-may-be-nearer? and edge-closer-than? for numbers
   that are integers or doubles (no rationals: d is 1), each operation as
   Scheme's generic one takes it: exact when both operands are, else one
   IEEE operation on both as doubles (an integer here is below 2^26, a
   double exactly). */
static ds_esc_num ds_esc_sum(ds_esc_num a, ds_esc_num b, int sign) {
  ds_esc_num r;
  r.d = 1;
  if (!a.flo && !b.flo) { r.flo = 0; r.n = sign > 0 ? a.n + b.n : a.n - b.n; }
  else { r.flo = 1; r.f = sign > 0 ? ds_esc_double(a) + ds_esc_double(b) : ds_esc_double(a) - ds_esc_double(b); }
  return r;
}
static int ds_esc_lt(ds_esc_num a, ds_esc_num b) {
  return (!a.flo && !b.flo) ? a.n < b.n : ds_esc_double(a) < ds_esc_double(b);
}

/* near? of edge-closer-than?: a multiple of `tile` within d of side,
   other than side itself */
static int ds_esc_edge_near(ds_esc_num side, ds_esc_num d, long long tile) {
  ds_esc_num reach, e, t, far;
  t.flo = 0; t.n = tile; t.d = 1;
  if (!side.flo && !d.flo) {
    reach = d;
    e.flo = 0; e.d = 1;
    e.n = (ds_esc_floor((long long)(side.n - reach.n), tile) + 1) * tile;
  } else {
    /* (* 1e-9 (+ 1 (abs side) d)), then d + margin, then
       (* (+ (floor (/ (- side reach) tile)) 1) tile), all doubles */
    ds_esc_num one, a, margin;
    one.flo = 0; one.n = 1; one.d = 1;
    a = side;
    if (a.flo) a.f = fabs(a.f); else if (a.n < 0) a.n = -a.n;
    a = ds_esc_sum(ds_esc_sum(one, a, 1), d, 1);
    margin.flo = 1; margin.d = 1; margin.f = 1e-9 * ds_esc_double(a);
    reach = ds_esc_sum(d, margin, 1);
    e.flo = 1; e.d = 1;
    e.f = (floor(ds_esc_double(ds_esc_sum(side, reach, -1)) / (double)tile) + 1.0) * (double)tile;
  }
  far = ds_esc_sum(side, reach, 1);
  if (e.flo ? e.f == ds_esc_double(side) : (!side.flo ? e.n == side.n : (double)e.n == side.f))
    return ds_esc_lt(ds_esc_sum(e, t, 1), far);
  return ds_esc_lt(e, far);
}

/* Whether a move on both axes could be nearer than the straight move of
   length d (its offset that is not 0, made positive): both axes have a
   tile edge closer than d to a side of the box. */
static int ds_esc_diagonal_may(ds_esc_num d, ds_esc_num x, ds_esc_num y, ds_esc_num w, ds_esc_num h,
                               long long tw, long long th) {
  return (ds_esc_edge_near(x, d, tw) || ds_esc_edge_near(ds_esc_sum(x, w, 1), d, tw)) &&
         (ds_esc_edge_near(y, d, th) || ds_esc_edge_near(ds_esc_sum(y, h, 1), d, th));
}

/* ds_escape_straight's answer for numbers already read (ds_esc_read,
   ds_esc_plain); the motion kernel (motion.c) asks it too. */
static C_word ds_escape_decide(const unsigned char *bytes, long long nbytes, C_word map, int race,
                               ds_esc_num x, ds_esc_num y, ds_esc_num w, ds_esc_num h) {
  ds_esc_num at[4];
  ds_esc_grid rows, cols;
  long long ncols, nrows, col0, row0, tw, th, lines[4] = {0, 0, 0, 0}, line;
  int done[4] = {0, 0, 0, 0}, moved[4] = {0, 0, 0, 0}, found, k, iter, cap;
  /* a flonum and a rational together: Scheme's sums would round the
     rational to a double, which this code does not do */
  if ((x.flo || y.flo || w.flo || h.flo) && (x.d > 1 || y.d > 1)) return C_SCHEME_FALSE;
  for (k = 0; k < 6; k++)
    if (!(C_block_item(map, k) & C_FIXNUM_BIT)) return C_SCHEME_FALSE;
  ncols = C_unfix(C_block_item(map, 0)); nrows = C_unfix(C_block_item(map, 1));
  col0 = C_unfix(C_block_item(map, 2)); row0 = C_unfix(C_block_item(map, 3));
  tw = C_unfix(C_block_item(map, 4)); th = C_unfix(C_block_item(map, 5));
  if (ncols < 0 || nrows < 0 || ncols >= DS_ESC_LIMIT || nrows >= DS_ESC_LIMIT ||
      col0 >= DS_ESC_LIMIT || col0 <= -DS_ESC_LIMIT || row0 >= DS_ESC_LIMIT || row0 <= -DS_ESC_LIMIT ||
      tw < 1 || th < 1 || tw >= DS_ESC_LIMIT || th >= DS_ESC_LIMIT ||
      ((col0 < 0 ? -col0 : col0) + ncols + 1) * tw >= DS_ESC_LIMIT ||
      ((row0 < 0 ? -row0 : row0) + nrows + 1) * th >= DS_ESC_LIMIT ||
      ncols * nrows > nbytes)
    return C_SCHEME_FALSE;
  rows.bytes = cols.bytes = bytes;
  rows.ls = ncols; rows.cs = 1; rows.line_origin = row0; rows.cell_origin = col0;
  rows.line_count = nrows; rows.cell_count = ncols;
  cols.ls = 1; cols.cs = ncols; cols.line_origin = col0; cols.cell_origin = row0;
  cols.line_count = ncols; cols.cell_count = nrows;
  /* free? */
  if (!ds_esc_blocking(&rows, y, h, th, x, w, tw, 1, &found, &line)) return C_SCHEME_FALSE;
  if (!found) return C_SCHEME_TRUE;
  if (!race) return C_fix(0);
  /* the race: each runner moves past a line of the map, so it is done
     within the map's lines; the cap only guards the loop */
  at[0] = at[1] = y; at[2] = at[3] = x;
  cap = 4 * (int)(ncols + nrows + 4);
  for (iter = 0; iter < cap; iter++) {
    int i = 0, j;
    ds_esc_num far = ds_esc_minus(at[0], y);
    for (j = 1; j < 4; j++) {
      ds_esc_num d = ds_esc_minus(at[j], j < 2 ? y : x);
      if (ds_esc_less(d, far)) { i = j; far = d; }
    }
    if (done[i])
      return moved[i] ? C_fix(lines[i] * 4 + i) : C_SCHEME_FALSE;
    if (!(i < 2 ? ds_esc_blocking(&rows, at[i], h, th, x, w, tw, i == 0 ? 1 : -1, &found, &line)
                : ds_esc_blocking(&cols, at[i], w, tw, y, h, th, i == 2 ? 1 : -1, &found, &line)))
      return C_SCHEME_FALSE;
    if (found) {
      lines[i] = line; moved[i] = 1;
      at[i] = ds_esc_place(i, line, tw, th, w, h);
    } else
      done[i] = 1;
  }
  return C_SCHEME_FALSE;
}

/* #f: not for this code; #t: the box covers no solid tile; else, with
   race #f, the fixnum 0 (it covers one), and with race #t the fixnum
   4 line + i: straight move i (0 up, 1 down, 2 left, 3 right) is the
   nearest, ended by tile line `line`. map is tile-grid.scm's pass-map,
   bytes its solid grid (nbytes long). */
static C_word ds_escape_straight(const unsigned char *bytes, C_word nbytes, C_word map, C_word race,
                                 C_word x_, C_word y_, C_word w_, C_word h_) {
  ds_esc_num x, y, w, h;
  if (!(ds_esc_read(x_, 0, &x) && ds_esc_read(y_, 0, &y) && ds_esc_read(w_, 1, &w) && ds_esc_read(h_, 1, &h)))
    return C_SCHEME_FALSE;
  return ds_escape_decide(bytes, C_unfix(nbytes), map, race != C_SCHEME_FALSE, x, y, w, h);
}

/* For tests (escape.scm's diagonal-in-c): ds_esc_diagonal_may for the
   straight move (dx, dy) of a box at (x, y) of w x h on tiles tw x th,
   as diagonal-may-be-nearer? is asked it; #f when a number is not one
   it takes (a rational, a NaN, an infinity, beyond its range). */
static C_word ds_escape_diagonal(C_word dx_, C_word dy_, C_word x_, C_word y_, C_word w_, C_word h_,
                                 C_word tw_, C_word th_) {
  ds_esc_num dx, dy, x, y, w, h, d;
  long long tw, th;
  if (!(ds_esc_read(dx_, 0, &dx) && ds_esc_read(dy_, 0, &dy) && ds_esc_read(x_, 0, &x) &&
        ds_esc_read(y_, 0, &y) && ds_esc_read(w_, 1, &w) && ds_esc_read(h_, 1, &h)) ||
      dx.d > 1 || dy.d > 1 || x.d > 1 || y.d > 1 ||
      !(tw_ & C_FIXNUM_BIT) || !(th_ & C_FIXNUM_BIT))
    return C_SCHEME_FALSE;
  tw = C_unfix(tw_); th = C_unfix(th_);
  if (tw < 1 || th < 1 || tw >= DS_ESC_LIMIT || th >= DS_ESC_LIMIT) return C_SCHEME_FALSE;
  d = (dx_ == C_fix(0)) ? dy : dx;
  if (d.flo) d.f = fabs(d.f); else if (d.n < 0) d.n = -d.n;
  return ds_esc_diagonal_may(d, x, y, w, h, tw, th) ? C_fix(1) : C_fix(0);
}

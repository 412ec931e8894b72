/* (downstroke physics)'s C: the type test for entity numbers and the
   fixnum motion kernel, steps 2-7 of the contract (and tile ground
   detection) for entities of small fixnums. Included by physics.scm, one
   compilation unit with it; the Scheme comments there say why it is C. */

#include "motion.h"

static C_word ds_plain_number(C_word v) {
  if (v & C_FIXNUM_BIT) return C_fix(1);
  if (C_immediatep(v)) return C_fix(0);
  switch (C_block_header(v)) {
  case C_RATNUM_TAG: case C_BIGNUM_TAG: return C_fix(1);
  case C_FLONUM_TAG: { double d = C_flonum_magnitude(v); return C_fix(d - d == 0.0); }
  default: return C_fix(0);
  }
}


static long ds_floor_div(long a, long d) { return a >= 0 ? a / d : (a + 1) / d - 1; }
static long ds_min(long a, long b) { return a < b ? a : b; }
static long ds_max(long a, long b) { return a > b ? a : b; }

/* tile-stop: where a body that moved by v (not 0) to pos stops on one
   axis, or 0 when no solid line is in its way. Cell (line, cell) of the
   grid is byte line*ls + cell*cs, both counted from the map's origin. */
static int ds_tile_stop(long v, long pos, long size, long across, long across_size, int swept,
                        long tile, long tile_across, const unsigned char *bytes,
                        long ls, long cs, long line_origin, long cell_origin,
                        long line_count, long cell_count, long *stop)
{
  int forward = v > 0;
  long l0 = ds_floor_div(pos, tile), l1 = ds_floor_div(pos + size - 1, tile);
  long lo = ds_max(ds_floor_div(across, tile_across) - cell_origin, 0);
  long hi = ds_min(ds_floor_div(across + across_size - 1, tile_across) - cell_origin,
                   cell_count - 1);
  long from = forward ? l0 : l1, to = forward ? l1 : l0, line, cell;
  if (swept) {      /* from the line the leading edge was in before the move */
    long s0 = ds_floor_div(pos - v, tile), s1 = ds_floor_div(pos - v + size - 1, tile);
    from = forward ? ds_min(ds_max(s0, s1), l0) : ds_max(ds_min(s0, s1), l1);
  }
  from -= line_origin;
  to -= line_origin;
  from = forward ? ds_max(from, 0) : ds_min(from, line_count - 1);
  to = forward ? ds_min(to, line_count - 1) : ds_max(to, 0);
  if (lo > hi || (forward ? from > to : from < to)) return 0;
  for (line = from; ; line += forward ? 1 : -1) {
    const unsigned char *base = bytes + line * ls;
    for (cell = lo; cell <= hi; cell++)
      if (base[cell * cs] == 1) {
        long at = line + line_origin;
        *stop = forward ? at * tile - size : (at + 1) * tile;
        return 1;
      }
    if (line == to) return 0;
  }
}

static int ds_solid(const unsigned char *bytes, long cols, long rows, long col0, long row0,
                    long col, long row)
{
  long c = col - col0, r = row - row0;
  return c >= 0 && c < cols && r >= 0 && r < rows && bytes[r * cols + c] == 1;
}

/* map is #(cols rows col0 row0 tile-width tile-height). */
/* Fixnums below this stay fixnums, and fit a long, through the sums below:
   2^40 on 64-bit CHICKEN (62-bit fixnums), 2^27 on 32-bit (30-bit). */
#ifdef C_SIXTY_FOUR
# define DS_LIMIT (1L << 40)
#else
# define DS_LIMIT (1L << 27)
#endif
#define DS_SMALL(o) (C_truep(C_fixnump(o)) && C_unfix(o) < DS_LIMIT && C_unfix(o) > -DS_LIMIT)
#define DS_SIZE(o) (C_truep(C_fixnump(o)) && C_unfix(o) >= 0 && C_unfix(o) < DS_LIMIT)

/* -1 when this entity is not for this code (a number that is not a small
   fixnum, a non-empty #:skip-pipelines, an unknown mode: DS_NOT_HERE), else
   the keys to write. */
static C_word ds_fixnum_motion(C_word out, const unsigned char *bytes, C_word map,
                               C_word flags_, C_word gravity_, C_word skips,
                               C_word x_, C_word y_, C_word w_, C_word h_,
                               C_word vx_, C_word vy_, C_word ay_, C_word on)
{
  long flags = C_unfix(flags_), g = C_unfix(gravity_);
  if ((flags & DS_NOT_HERE) || (skips != C_SCHEME_FALSE && skips != C_SCHEME_END_OF_LIST) ||
      !(DS_SMALL(x_) && DS_SMALL(y_) && DS_SMALL(vx_) && DS_SMALL(vy_) &&
        DS_SIZE(w_) && DS_SIZE(h_) && (!(flags & DS_GRAVITY) || DS_SMALL(ay_))))
    return C_fix(-1);
  long x = C_unfix(x_), y = C_unfix(y_), w = C_unfix(w_), h = C_unfix(h_);
  long vx = C_unfix(vx_), vy0 = C_unfix(vy_), ay = C_unfix(ay_);
  long cols = C_unfix(C_block_item(map, 0)), rows = C_unfix(C_block_item(map, 1));
  long col0 = C_unfix(C_block_item(map, 2)), row0 = C_unfix(C_block_item(map, 3));
  long tw = C_unfix(C_block_item(map, 4)), th = C_unfix(C_block_item(map, 5));
  int has_map = flags & DS_HAS_MAP, grav = flags & DS_GRAVITY, swept = (flags & DS_SWEPT) != 0;
  int accelerate = grav && !(ay == 0 && (flags & DS_HAS_AY));
  long vy = grav ? (accelerate ? vy0 + ay : vy0) + g : vy0;
  long x2 = x + vx, y2, stop;
  int x_stopped = 0, y_stopped = 0, writes = 0;
  if (has_map && vx != 0 &&
      ds_tile_stop(vx, x2, w, y, h, swept, tw, th, bytes, 1, cols, col0, row0, cols, rows, &stop)) {
    x_stopped = 1;
    x2 = stop;
  }
  y2 = y + vy;
  if (has_map && vy != 0 &&
      ds_tile_stop(vy, y2, h, x2, w, swept, th, tw, bytes, cols, 1, row0, col0, rows, cols, &stop)) {
    y_stopped = 1;
    y2 = stop;
  }
  if (!((flags & DS_HAS_X) && x == x2)) { C_set_block_item(out, 0, C_fix(x2)); writes |= DS_WRITE_X; }
  if (!((flags & DS_HAS_Y) && y == y2)) { C_set_block_item(out, 1, C_fix(y2)); writes |= DS_WRITE_Y; }
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
    long row = ds_floor_div(y2 + h + 1, th);
    long c0 = ds_floor_div(x2, tw), c1 = ds_floor_div(x2 + w - 1, tw);
    C_word ground = C_mk_bool(has_map &&
                              (ds_solid(bytes, cols, rows, col0, row0, c0, row) ||
                               ds_solid(bytes, cols, rows, col0, row0, ds_max(c0, c1), row)));
    if (!((flags & DS_HAS_ON) && on == ground)) { C_set_block_item(out, 5, ground); writes |= DS_WRITE_ON; }
  }
  return C_fix(writes);
}

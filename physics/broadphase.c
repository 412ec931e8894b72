/* (downstroke broadphase)'s C: a box's hash cells, the comparison of two
   spans, and the gathering and unfiling of boxes in the hash's buckets.
   Included by broadphase.scm, one compilation unit with it; the Scheme
   comments there say what each is for and why it is C. */
#include "physics/arith.h"

/* floor(v), or 0 with *ok cleared when v is not a fixnum or a rational
   of fixnums */
static C_word ds_floor(C_word v, int *ok) {
  if (v & C_FIXNUM_BIT) return C_unfix(v);
  if (!C_immediatep(v) && C_block_header(v) == C_RATNUM_TAG) {
    C_word n = C_block_item(v, 0), d = C_block_item(v, 1);
    if ((n & C_FIXNUM_BIT) && (d & C_FIXNUM_BIT)) {
      C_word a = C_unfix(n), b = C_unfix(d);     /* b > 1 */
      return ds_floor_div(a, b);
    }
  }
  *ok = 0;
  return 0;
}
/* floor((floor(v) + w) / size): floor(v + w) is floor(v) + w for an
   integer w, and floor(floor(u) / size) is floor(u / size) */
static C_word ds_cell(C_word v, C_word w, C_word size, int *ok) {
  C_word f = ds_floor(v, ok) + w;
  C_word c = ds_floor_div(f, size);
  if (!C_fitsinfixnump(c)) *ok = 0;
  return c;
}
/* Cells of flonum coordinates are taken below this magnitude: within the
   fixnums, and where a double still tells integers apart. */
#define DS_CELL_LIMIT ((double)C_MOST_POSITIVE_FIXNUM < 1e15 ? (double)C_MOST_POSITIVE_FIXNUM : 1e15)
/* A flonum coordinate's cell, with the operations of broadphase.scm's
   cell-of and end-cell on a flonum, in the same order, so the same
   doubles: floor((v + w) / size), v + w only when w is not 0 (Scheme adds
   0 too, which changes no double but -0.0, whose floor is the same). The
   floor is the conversion to an integer (towards zero), one less for a
   negative non-integer: no call, and a double out of range (or a NaN)
   is never converted, which C leaves undefined. */
static C_word ds_flonum_cell(double v, C_word w, C_word size, int *ok) {
  double q = (w == 0 ? v : v + (double)w) / (double)size;
  C_word c;
  if (!(q > -DS_CELL_LIMIT && q < DS_CELL_LIMIT)) { *ok = 0; return 0; }
  c = (C_word)q;
  return (double)c > q ? c - 1 : c;
}
/* the cell of coordinate v (a fixnum, a rational of fixnums or a flonum)
   plus the integer w */
static C_word ds_coord_cell(C_word v, C_word w, C_word size, int *ok) {
  if (!C_immediatep(v) && C_block_header(v) == C_FLONUM_TAG)
    return ds_flonum_cell(C_flonum_magnitude(v), w, size, ok);
  return ds_cell(v, w, size, ok);
}
static C_word ds_span(C_word span, C_word x, C_word y, C_word w, C_word h,
                      C_word size, C_word large) {
  int ok = (w & C_FIXNUM_BIT) && (h & C_FIXNUM_BIT) && (size & C_FIXNUM_BIT)
           && C_unfix(size) > 0;
  C_word cx0, cy0, cx1, cy1;
  if (!ok) return C_fix(0);
  cx0 = ds_coord_cell(x, 0, C_unfix(size), &ok);
  cy0 = ds_coord_cell(y, 0, C_unfix(size), &ok);
  cx1 = ds_coord_cell(x, C_unfix(w), C_unfix(size), &ok);
  cy1 = ds_coord_cell(y, C_unfix(h), C_unfix(size), &ok);
  if (!ok) return C_fix(0);
  if (cx1 - cx0 > C_unfix(large) || cy1 - cy0 > C_unfix(large)) return C_fix(2);
  C_set_block_item(span, 0, C_fix(cx0));
  C_set_block_item(span, 1, C_fix(cy0));
  C_set_block_item(span, 2, C_fix(cx1));
  C_set_block_item(span, 3, C_fix(cy1));
  return C_fix(1);
}

/* both 'large (the same symbol), or both four equal fixnum cells; bignum
   cells (astronomically far out) compare unequal, which only costs a
   needless re-filing */
static int ds_same_span(C_word a, C_word b) {
  if (a == b) return (1);
  if (C_immediatep(a) || C_immediatep(b) || C_header_bits(a) != C_VECTOR_TYPE
      || C_header_bits(b) != C_VECTOR_TYPE) return (0);
  return (C_block_item(a, 0) == C_block_item(b, 0) && C_block_item(a, 1) == C_block_item(b, 1)
           && C_block_item(a, 2) == C_block_item(b, 2) && C_block_item(a, 3) == C_block_item(b, 3));
}

static C_word ds_bucket(C_word cx, C_word cy, C_word mask) {
  return C_fixnum_and(C_fixnum_xor(C_fixnum_times(cx, C_fix(73856093)),
                                   C_fixnum_times(cy, C_fix(19349663))), mask);
}
static C_word ds_take(C_word ls, C_word buf, C_word n, C_word p, C_word after,
                      C_word stamp) {
  for (; ls != C_SCHEME_END_OF_LIST; ls = C_block_item(ls, 1)) {
    C_word q = C_block_item(ls, 0);
    if (q > after && C_block_item(stamp, C_unfix(q)) != p) {
      C_set_block_item(stamp, C_unfix(q), p);
      C_set_block_item(buf, n++, q);
    }
  }
  return n;
}
/* Takes box k out of the buckets of its span of fixnum cells (which the
   Scheme side filed it in, one pair per cell): the lists are the spatial
   hash's own, so they are unlinked in place. */
static C_word ds_unfile(C_word k, C_word span, C_word buckets, C_word mask) {
  C_word cx, cy, b, ls, prev;
  for (cy = C_unfix(C_block_item(span, 1)); cy <= C_unfix(C_block_item(span, 3)); cy++)
    for (cx = C_unfix(C_block_item(span, 0)); cx <= C_unfix(C_block_item(span, 2)); cx++) {
      b = C_unfix(ds_bucket(C_fix(cx), C_fix(cy), mask));
      prev = C_SCHEME_FALSE;
      for (ls = C_block_item(buckets, b); ls != C_SCHEME_END_OF_LIST; ls = C_block_item(ls, 1)) {
        if (C_block_item(ls, 0) == k) {
          if (prev == C_SCHEME_FALSE) C_mutate(&C_block_item(buckets, b), C_block_item(ls, 1));
          else C_mutate(&C_block_item(prev, 1), C_block_item(ls, 1));
          break;
        }
        prev = ls;
      }
    }
  return C_SCHEME_UNDEFINED;
}
/* 1 when span is four fixnum cells */
static C_word ds_fixnum_span(C_word span) {
  return C_fix(!C_immediatep(span) && C_header_bits(span) == C_VECTOR_TYPE
               && (C_block_item(span, 0) & C_block_item(span, 1) & C_block_item(span, 2)
                   & C_block_item(span, 3) & C_FIXNUM_BIT));
}
static C_word ds_gather(C_word buf, C_word p, C_word after, C_word span,
                        C_word buckets, C_word large, C_word stamp, C_word mask) {
  C_word n = 0, cx, cy, i, j, q;
  if (C_immediatep(span) || C_header_bits(span) != C_VECTOR_TYPE) return C_fix(-1);
  for (i = 0; i < 4; i++)
    if (!(C_block_item(span, i) & C_FIXNUM_BIT)) return C_fix(-1);
  n = ds_take(large, buf, n, p, after, stamp);
  for (cy = C_unfix(C_block_item(span, 1)); cy <= C_unfix(C_block_item(span, 3)); cy++)
    for (cx = C_unfix(C_block_item(span, 0)); cx <= C_unfix(C_block_item(span, 2)); cx++)
      n = ds_take(C_block_item(buckets, C_unfix(ds_bucket(C_fix(cx), C_fix(cy), mask))),
                  buf, n, p, after, stamp);
  for (i = 1; i < n; i++) {          /* a few boxes: insertion sort */
    q = C_block_item(buf, i);
    for (j = i; j > 0 && C_block_item(buf, j - 1) > q; j--)
      C_set_block_item(buf, j, C_block_item(buf, j - 1));
    C_set_block_item(buf, j, q);
  }
  return C_fix(n);
}

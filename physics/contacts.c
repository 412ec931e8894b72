/* (downstroke contacts)'s C: the overlap test of two boxes whose numbers
   are fixnums or flonums. Included by contacts.scm, one compilation unit
   with it; the Scheme comments there (boxes-overlap?) say why it is C. */

/* Below this magnitude a fixnum is a double exactly, and so is the sum of
   two of them. Every 32-bit fixnum is. */
#ifdef C_SIXTY_FOUR
# define DS_EXACT_DOUBLE ((C_word)1 << 52)
#else
# define DS_EXACT_DOUBLE ((C_word)1 << 29)
#endif

/* *d = the number o, when it is a fixnum below DS_EXACT_DOUBLE or a
   finite flonum; 0 for anything else (a rational, a bignum, not a
   number, an infinity, a NaN). */
static inline __attribute__((always_inline)) int ds_overlap_real(C_word o, double *d) {
  if (o & C_FIXNUM_BIT) {
    C_word n = C_unfix(o);
    *d = (double)n;
    return n < DS_EXACT_DOUBLE && n > -DS_EXACT_DOUBLE;
  }
  if (C_immediatep(o) || C_block_header(o) != C_FLONUM_TAG) return 0;
  *d = C_flonum_magnitude(o);
  return *d - *d == 0.0;
}

/* Whether [x1, x1+w1) x [y1, y1+h1) and [x2, x2+w2) x [y2, y2+h2) overlap
   (1) or not (0), with exactly the answer of Scheme's (< x1 (+ x2 w2))
   and the three others, or -1 when a number is not for this code. Every
   number is a double exactly (above), a sum is Scheme's: two fixnums'
   is exact, since it stays below 2^53, and a flonum's is the one IEEE
   sum (double)n + d, as CHICKEN's + takes it; and a comparison of two
   doubles that hold an exact integer and a flonum is CHICKEN's exact
   comparison of the two. */
static C_word ds_boxes_overlap(C_word x1, C_word y1, C_word w1, C_word h1,
                               C_word x2, C_word y2, C_word w2, C_word h2) {
  double a, b, c, d, e, f, g, h;
  if (!(ds_overlap_real(x1, &a) & ds_overlap_real(y1, &b) & ds_overlap_real(w1, &c) &
        ds_overlap_real(h1, &d) & ds_overlap_real(x2, &e) & ds_overlap_real(y2, &f) &
        ds_overlap_real(w2, &g) & ds_overlap_real(h2, &h)))
    return C_fix(-1);
  return C_fix(a < e + g && e < a + c && b < f + h && f < b + d);
}

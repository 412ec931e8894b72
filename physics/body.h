/* The type test behind (downstroke body)'s macros: 1 for the numbers
   check-entity-number lets through (fixnums, bignums, exact rationals,
   finite flonums), 0 for anything else, read from the type tags with no
   call. Every module that reads a body's numbers includes this file. */
#ifndef DS_BODY_H
#define DS_BODY_H

static inline C_word ds_plain_number(C_word v) {
  if (v & C_FIXNUM_BIT) return C_fix(1);
  if (C_immediatep(v)) return C_fix(0);
  switch (C_block_header(v)) {
  case C_RATNUM_TAG: case C_BIGNUM_TAG: return C_fix(1);
  case C_FLONUM_TAG: { double d = C_flonum_magnitude(v); return C_fix(d - d == 0.0); }
  default: return C_fix(0);
  }
}

#endif

/* Integer arithmetic the physics C shares (motion.c, broadphase.c). Its
   Scheme twin is floor-div in base/arith.scm. */
#ifndef DS_ARITH_H
#define DS_ARITH_H

/* floor(a / d) for a positive d (C's / truncates towards zero) */
static inline C_word ds_floor_div(C_word a, C_word d) {
  return a >= 0 ? a / d : (a + 1) / d - 1;
}

#endif

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

/* Ground detection's test of a candidate supporter (contacts.scm,
   supports?), for the candidates a query of the support index put in
   buf[from..count): the solid s = solids[buf[i]]. Each is judged in
   supports?'s order, reading s's pairs as entity-ref and num read them;
   a candidate is left to the Scheme (its position i is returned) as soon
   as the test needs a number that is not a fixnum below DS_EXACT_DOUBLE
   or a finite flonum, finds s not a proper list of pairs up to the key,
   or finds s one-way (whose test reads the mover further). Otherwise:
   -2 when a candidate holds the mover up, -1 when none does, -3 when a
   number of the mover's (x, w, bottom, tol) is not for this code.
   keys is #(#:solid? #:one-way? #:x #:width #:y). */

#define DS_PAIR(x) (!C_immediatep(x) && C_block_header(x) == C_PAIR_TAG)

/* The pair of key in the list of pairs e (*p), or C_SCHEME_FALSE when e
   has none; 0 when e is not a proper list of pairs before key. */
static inline int ds_find(C_word e, C_word key, C_word *p) {
  for (; e != C_SCHEME_END_OF_LIST; e = C_u_i_cdr(e)) {
    if (!DS_PAIR(e) || !DS_PAIR(C_u_i_car(e))) return 0;
    if (C_u_i_car(C_u_i_car(e)) == key) { *p = C_u_i_car(e); return 1; }
  }
  *p = C_SCHEME_FALSE;
  return 1;
}
/* num's reading of key in e, as a double in *d (0 when absent); 0 when
   this code cannot take it */
static inline int ds_find_real(C_word e, C_word key, double *d) {
  C_word p;
  if (!ds_find(e, key, &p)) return 0;
  if (p == C_SCHEME_FALSE) { *d = 0.0; return 1; }
  return ds_overlap_real(C_u_i_cdr(p), d);
}

static C_word ds_ground_scan(C_word buf, C_word from, C_word count, C_word solids,
                             C_word entity, C_word x, C_word w, C_word bottom,
                             C_word tol, C_word keys) {
  double mx, mw, mb, t, sx, sw, sy;
  C_word i, s, p;
  if (!(ds_overlap_real(x, &mx) & ds_overlap_real(w, &mw) & ds_overlap_real(bottom, &mb)
        & ds_overlap_real(tol, &t)))
    return C_fix(-3);
  for (i = C_unfix(from); i < C_unfix(count); i++) {
    s = C_block_item(solids, C_unfix(C_block_item(buf, i)));
    if (s == entity) continue;
    if (!ds_find(s, C_block_item(keys, 0), &p)) return C_fix(i);
    if (p == C_SCHEME_FALSE || C_u_i_cdr(p) == C_SCHEME_FALSE) continue;
    if (!ds_find_real(s, C_block_item(keys, 2), &sx) || !ds_find_real(s, C_block_item(keys, 3), &sw))
      return C_fix(i);
    if (!(mx < sx + sw) || !(sx < mx + mw)) continue;
    if (!ds_find_real(s, C_block_item(keys, 4), &sy)) return C_fix(i);
    if (!(fabs(sy - mb) <= t)) continue;
    if (!ds_find(s, C_block_item(keys, 1), &p)) return C_fix(i);
    if (p == C_SCHEME_FALSE || C_u_i_cdr(p) == C_SCHEME_FALSE) return C_fix(-2);
    return C_fix(i);
  }
  return C_fix(-1);
}

/* The box of the entity e as resolve-colliding-pair reads it (a key's
   first pair, 0 when absent): ds_find_real of the four keys in e, in one
   walk of e: each key's first pair is the one ds_find finds, and a key
   is missing (0.0) or unreadable (0) exactly when ds_find_real says so.
   keys is #(#:x #:y #:width #:height ...). */
static inline int ds_find_box(C_word e, C_word keys, double *v) {
  C_word k[4], p;
  int found = 0, i;
  for (i = 0; i < 4; i++) { k[i] = C_block_item(keys, i); v[i] = 0.0; }
  for (; e != C_SCHEME_END_OF_LIST && found != 15; e = C_u_i_cdr(e)) {
    if (!DS_PAIR(e) || !DS_PAIR(p = C_u_i_car(e))) return 0;
    for (i = 0; i < 4; i++)
      if (!(found & (1 << i)) && C_u_i_car(p) == k[i]) {
        found |= 1 << i;
        if (!ds_overlap_real(C_u_i_cdr(p), &v[i])) return 0;
        break;
      }
  }
  return 1;
}

/* push-apart's two decisions for the boxes of a and b (read as
   ds_find_box reads them), when every number is a fixnum below 2^50 in
   magnitude or a finite flonum: the axis of least overlap (shallow-axis:
   x when the x overlap is less than the y overlap) and whether a goes to
   the negative side (goes-negative?: its 2 pos + size is less than b's).
   0: x, a negative; 1: x, a positive; 2: y, a negative; 3: y, a positive;
   -1 for anything else, which the Scheme decides. Every sum and
   difference below is then Scheme's: of two fixnums an integer below
   2^53, which a double holds exactly, else the one IEEE operation on both
   as doubles that CHICKEN's generic arithmetic makes; min and max pick
   the same value either way. Nothing is made: contacts.scm makes the
   numbers of the push. */
#ifdef C_SIXTY_FOUR
# define DS_PUSH_LIMIT ((C_word)1 << 50)
#else
# define DS_PUSH_LIMIT ((C_word)1 << 29)
#endif
/* The decision from the eight numbers as doubles: v[0..3] a's x, y,
   width, height, v[4..7] b's. */
static inline int ds_push_decide(const double *v) {
  double ox = fmin(v[0] + v[2], v[4] + v[6]) - fmax(v[0], v[4]);
  double oy = fmin(v[1] + v[3], v[5] + v[7]) - fmax(v[1], v[5]);
  int axis = ox < oy ? 0 : 1;
  double ca = 2.0 * v[axis] + v[axis + 2], cb = 2.0 * v[4 + axis] + v[6 + axis];
  return 2 * axis + (ca < cb ? 0 : 1);
}

/* *d = o as a double when it is a number ds_push_sides takes (a fixnum
   below DS_PUSH_LIMIT in magnitude or a finite flonum); 0 otherwise. */
static inline int ds_push_real(C_word o, double *d) {
  if (o & C_FIXNUM_BIT) {
    if (C_unfix(o) >= DS_PUSH_LIMIT || C_unfix(o) <= -DS_PUSH_LIMIT) return 0;
    *d = (double)C_unfix(o);
    return 1;
  }
  return ds_overlap_real(o, d);
}

static C_word ds_push_sides(C_word a, C_word b, C_word keys) {
  double v[8];
  C_word p, o;
  int i;
  for (i = 0; i < 8; i++) {
    if (!ds_find(i < 4 ? a : b, C_block_item(keys, i & 3), &p)) return C_fix(-1);
    o = p == C_SCHEME_FALSE ? C_fix(0) : C_u_i_cdr(p);
    if (!ds_push_real(o, &v[i])) return C_fix(-1);
  }
  return C_fix(ds_push_decide(v));
}

/* push-apart's whole push, for the boxes ds_push_sides decides: the two
   new versions of the bodies made here in one pass, with the numbers and
   the structure push-by and entity-set* give (contacts.scm, push-by;
   core/entity.c, ds_entity_set_star), without the generic arithmetic, the
   calls and the flonums between. A denser crowd pushes more pairs per
   body (docs/performance.org, "S5: the pushes and the pair test in C").

   The numbers: when the four numbers on the axis (a's and b's position
   and size) are fixnums, the overlap is an exact integer and half of it
   one too when it is even (an odd one is a rational: left to the
   Scheme); else the overlap is a flonum, and every sum, min, max and
   difference push-by's generic arithmetic makes is the one IEEE
   operation below on the same doubles (each fixnum below 2^50 is a
   double exactly, and so is the sum of two). A body is taken only when
   it is a proper list of pairs (at most DS_PUSH_MAX_COPY long) holding
   the axis's position and velocity keys once each; anything else, and
   an overlap that is not positive, answers #f, and contacts.scm pushes
   the pair as before; -1 when the bodies are proper lists but a number
   of their boxes is not one ds_push_sides takes (a rational, a bignum),
   so that contacts.scm goes to the Scheme push at once, where
   ds_push_sides would answer -1 too after walking them again.
   keys is #(#:x #:y #:width #:height #:vx #:vy). */
#define DS_PUSH_MAX_COPY 1024

/* One walk of the alist e for the six keys (#(#:x #:y #:width #:height
   #:vx #:vy)): the first pair of each (C_SCHEME_FALSE: none) in pair[],
   its place in place[], and in twice a bit for each key held more than
   once; 0 when e is not a proper list of pairs of at most
   DS_PUSH_MAX_COPY. */
static int ds_push_walk(C_word e, C_word keys, C_word *pair, int *place, int *twice) {
  C_word p, k;
  int n, i;
  *twice = 0;
  for (i = 0; i < 6; i++) { pair[i] = C_SCHEME_FALSE; place[i] = -1; }
  for (n = 0; e != C_SCHEME_END_OF_LIST; e = C_u_i_cdr(e), n++) {
    if (n == DS_PUSH_MAX_COPY || !DS_PAIR(e) || !DS_PAIR(p = C_u_i_car(e))) return 0;
    k = C_u_i_car(p);
    for (i = 0; i < 6; i++)
      if (k == C_block_item(keys, i)) {
        if (place[i] >= 0) *twice |= 1 << i;
        else { place[i] = n; pair[i] = p; }
        break;
      }
  }
  return 1;
}

/* entity-set*'s new version of e (ds_entity_set_star): the pairs up to
   the last one whose value changes copied, each changed key's pair
   replaced, the rest shared; e itself when nothing changes. last is
   that place (-1: none). */
static C_word ds_push_version(C_word **ptr, C_word e, int last, int ipos, C_word vpos,
                              int ivel, C_word vvel) {
  C_word head = e, tail = C_SCHEME_FALSE, cell, p;
  int n;
  for (n = 0; n <= last; e = C_u_i_cdr(e), n++) {
    p = C_u_i_car(e);
    if (n == ipos && C_u_i_cdr(p) != vpos) p = C_a_pair(ptr, C_u_i_car(p), vpos);
    else if (n == ivel && C_u_i_cdr(p) != vvel) p = C_a_pair(ptr, C_u_i_car(p), vvel);
    cell = C_a_pair(ptr, p, C_SCHEME_END_OF_LIST);
    if (tail == C_SCHEME_FALSE) head = cell; else C_set_block_item(tail, 1, cell);
    tail = cell;
  }
  if (tail != C_SCHEME_FALSE) C_set_block_item(tail, 1, e);
  return head;
}

static inline double ds_push_double(C_word o) {
  return (o & C_FIXNUM_BIT) ? (double)C_unfix(o) : C_flonum_magnitude(o);
}

static void C_ccall ds_push_pair(C_word c, C_word *av) C_noret;
static void C_ccall ds_push_pair(C_word c, C_word *av) {
  C_word k = av[1], a, b, keys, pa, sa, pb, sb, ppa, pva, ppb, pvb;
  C_word va = 0, vb = 0, vela, velb, *mem, pairs[12], box[8];
  int axis, sides, a_negative, exact, ipa, iva, ipb, ivb, lasta, lastb, words, i;
  int places[12], twice, twice_b;
  double da = 0.0, db = 0.0, v[8];
  if (c != 5) C_kontinue(k, C_SCHEME_FALSE);
  a = av[2]; b = av[3]; keys = av[4];
  if (C_immediatep(keys) || C_header_bits(keys) != C_VECTOR_TYPE || C_header_size(keys) < 6)
    C_kontinue(k, C_SCHEME_FALSE);
  if (!ds_push_walk(a, keys, pairs, places, &twice) || !ds_push_walk(b, keys, pairs + 6, places + 6, &twice_b))
    C_kontinue(k, C_SCHEME_FALSE);
  /* the box numbers as num reads them (0 when absent), as ds_push_sides
     takes them */
  for (i = 0; i < 8; i++) {
    C_word p = pairs[(i & 3) + (i < 4 ? 0 : 6)];
    box[i] = p == C_SCHEME_FALSE ? C_fix(0) : C_u_i_cdr(p);
    if (!ds_push_real(box[i], &v[i])) C_kontinue(k, C_fix(-1));
  }
  sides = ds_push_decide(v);
  axis = sides >> 1;
  a_negative = (sides & 1) == 0;
  /* the axis's position and velocity: held once each by both */
  if (places[axis] < 0 || places[4 + axis] < 0 || places[6 + axis] < 0 || places[10 + axis] < 0 ||
      ((twice | twice_b) & (0x11 << axis)))
    C_kontinue(k, C_SCHEME_FALSE);
  pa = box[axis]; sa = box[2 + axis]; pb = box[4 + axis]; sb = box[6 + axis];
  exact = (pa & sa & pb & sb & C_FIXNUM_BIT) != 0;
  if (exact) {
    /* overlap-1d on integers below 2^50: no fixnum overflows */
    C_word ea = C_unfix(pa) + C_unfix(sa), eb = C_unfix(pb) + C_unfix(sb);
    C_word depth = (ea < eb ? ea : eb) - (C_unfix(pa) > C_unfix(pb) ? C_unfix(pa) : C_unfix(pb));
    C_word half, na, nb;
    if (depth <= 0 || (depth & 1)) C_kontinue(k, C_SCHEME_FALSE);
    half = depth / 2;
    na = C_unfix(pa) + (a_negative ? -half : half);
    nb = C_unfix(pb) + (a_negative ? half : -half);
    if (!C_fitsinfixnump(na) || !C_fitsinfixnump(nb)) C_kontinue(k, C_SCHEME_FALSE);
    va = C_fix(na); vb = C_fix(nb);
  } else {
    double xa = ds_push_double(pa), xb = ds_push_double(pb);
    double ea = xa + ds_push_double(sa), eb = xb + ds_push_double(sb);
    double depth = (ea < eb ? ea : eb) - (xa > xb ? xa : xb), half;
    if (!(depth > 0.0)) C_kontinue(k, C_SCHEME_FALSE);
    half = depth / 2.0;
    da = xa + (a_negative ? -half : half);
    db = xb + (a_negative ? half : -half);
  }
  vela = C_fix(a_negative ? -1 : 1);
  velb = C_fix(a_negative ? 1 : -1);
  ipa = places[axis]; ppa = pairs[axis]; iva = places[4 + axis]; pva = pairs[4 + axis];
  ipb = places[6 + axis]; ppb = pairs[6 + axis]; ivb = places[10 + axis]; pvb = pairs[10 + axis];
  /* the last place whose value changes: a new flonum always does */
  lasta = (!exact || C_u_i_cdr(ppa) != va) ? ipa : -1;
  if (C_u_i_cdr(pva) != vela && iva > lasta) lasta = iva;
  lastb = (!exact || C_u_i_cdr(ppb) != vb) ? ipb : -1;
  if (C_u_i_cdr(pvb) != velb && ivb > lastb) lastb = ivb;
  words = 3 * (lasta + 1) + 3 * (lastb + 1) + 12 + 3 + (exact ? 0 : 2 * C_SIZEOF_FLONUM);
  if (!C_demand(words)) C_save_and_reclaim((void *)ds_push_pair, c, av);
  mem = C_alloc(words);
  if (!exact) { va = C_flonum(&mem, da); vb = C_flonum(&mem, db); }
  C_kontinue(k, C_a_pair(&mem, ds_push_version(&mem, a, lasta, ipa, va, iva, vela),
                         ds_push_version(&mem, b, lastb, ipb, vb, ivb, velb)));
}

/* The pair pass's boxes, kept (contacts.scm, resolve-entity-collisions):
   each collider's four numbers as ds_find_box reads them, read once per
   pass and again only when a visit gives the body a new version, so that
   the test of a pair the hash offers is four comparisons, not two walks
   of two alists. A denser crowd is offered more pairs per body. The
   blob holds 5 doubles a collider, from its first 8-aligned byte: x, y,
   width, height, and 1.0 when ds_find_box took the body (0.0: a pair of
   it is the Scheme's to test). */
static inline double *ds_kept_boxes(C_word blob) {
  C_uword at = (C_uword)C_data_pointer(blob);
  return (double *)((at + 7) & ~(C_uword)7);
}

static C_word ds_keep_box(C_word blob, C_word p, C_word e, C_word keys) {
  double *v = ds_kept_boxes(blob) + 5 * C_unfix(p);
  v[4] = ds_find_box(e, keys, v) ? 1.0 : 0.0;
  return C_SCHEME_UNDEFINED;
}

/* Whether the colliders p and q are apart, from their kept boxes: 1
   apart, 0 for the Scheme to decide; and 2 when both boxes are
   taken and overlap, which is ds_boxes_overlap's 1 for the numbers
   resolve-colliding-pair reads (the same first pairs, the same tests). */
static C_word ds_kept_apart(C_word blob, C_word p, C_word q) {
  double *a = ds_kept_boxes(blob) + 5 * C_unfix(p), *b = ds_kept_boxes(blob) + 5 * C_unfix(q);
  if (a[4] == 0.0 || b[4] == 0.0) return C_fix(0);
  return C_fix(a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3] ? 2 : 1);
}

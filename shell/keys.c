/* (downstroke renderer)'s one walk over an entity: the values of the keys
   it draws by, instead of one assq per key. Included by renderer.scm.

   ds_entity_keys(alist, keys, out): for each key keys[i] (at most 30)
   that the alist holds, out[i] is its value (the first pair's, as assq
   would find), else #f; the answer is a fixnum with bit i set when keys[i]
   is held with a value other than #f, or -1 when the alist is not a list
   of pairs (the caller then reads it with entity-ref, which raises the
   error). Most keys of an entity are none of `keys` and fail the first
   test, the mask of a ds_key_table (core/entity.h). */
#include "core/entity.h"

#define DS_MAX_DRAWN_KEYS 30

/* The walk itself, into a C array out[0..n) (n at most
   DS_MAX_DRAWN_KEYS), with the table of the same keys: shell/sprites.c
   reads every entity's keys with it. Answers the bits as above, or -1;
   out[i] is written only where bit i is set (the caller reads no other). */
static inline C_word ds_read_keys_with(const ds_key_table *t, C_word alist, C_word keys, int n, C_word *out) {
  C_word ps, p, k;
  int i;
  C_word bits = 0, seen = 0;
  for (ps = alist; ps != C_SCHEME_END_OF_LIST; ps = C_block_item(ps, 1)) {
    if (C_immediatep(ps) || !C_truep(C_i_pairp(ps))) return -1;
    p = C_block_item(ps, 0);
    if (C_immediatep(p) || !C_truep(C_i_pairp(p))) return -1;
    k = C_block_item(p, 0);
    if ((i = ds_key_index(t, keys, n, k)) < 0) continue;
    if (!(seen & ((C_word)1 << i))) {
      seen |= (C_word)1 << i;
      if (C_block_item(p, 1) != C_SCHEME_FALSE) {
        bits |= (C_word)1 << i;
        out[i] = C_block_item(p, 1);
      }
    }
  }
  return bits;
}

static C_word ds_read_keys(C_word alist, C_word keys, int n, C_word *out) {
  ds_key_table t;
  int i;
  for (i = 0; i < n; i++) out[i] = C_SCHEME_FALSE;
  ds_key_table_init(&t, keys, n);
  return ds_read_keys_with(&t, alist, keys, n, out);
}

static C_word ds_entity_keys(C_word alist, C_word keys, C_word out) {
  C_word v[DS_MAX_DRAWN_KEYS], bits;
  int n = C_header_size(keys), i;
  if (n > DS_MAX_DRAWN_KEYS) n = DS_MAX_DRAWN_KEYS;
  bits = ds_read_keys(alist, keys, n, v);
  for (i = 0; i < n; i++) C_mutate(&C_block_item(out, i), bits < 0 ? C_SCHEME_FALSE : v[i]);
  return C_fix(bits);
}

/* Whether any alist of a list holds `key` with a value other than #f
   (the draw order key: without it no entity list is sorted). A malformed
   entity is passed over here; drawing it raises the error. */
static C_word ds_any_has_key(C_word alists, C_word key) {
  C_word es, ps, p;
  for (es = alists; C_truep(C_i_pairp(es)); es = C_block_item(es, 1))
    for (ps = C_block_item(es, 0); C_truep(C_i_pairp(ps)); ps = C_block_item(ps, 1)) {
      p = C_block_item(ps, 0);
      if (C_truep(C_i_pairp(p)) && C_block_item(p, 0) == key) {
        if (C_block_item(p, 1) != C_SCHEME_FALSE) return C_SCHEME_TRUE;
        break;                  /* the first pair of the key decides */
      }
    }
  return C_SCHEME_FALSE;
}

/* (downstroke renderer)'s test of an entity for the drawing keys it may
   hold: which of a vector of keys (at most 30) an alist holds with a true
   value, as bit i for keys[i]. Included by renderer.scm. Most entities
   hold none of them, and most of their keys fail the first test (one bit
   per key from bits 4-9 of its address, as in needs.c), so an entity
   without the keys costs a shift and a mask per pair. -1 when the alist
   is not a list of pairs (the caller then draws it as before, and
   entity-ref raises the error). */
#define DS_KEYS_BIT(k) ((C_uword)1 << (((C_uword)(k) >> 4) & 63))

static C_word ds_keys_mask(C_word alist, C_word keys) {
  C_word ps, p, k;
  int n = C_header_size(keys), i;
  C_uword mask = 0;
  C_word bits = 0;
  for (i = 0; i < n; i++) mask |= DS_KEYS_BIT(C_block_item(keys, i));
  for (ps = alist; ps != C_SCHEME_END_OF_LIST; ps = C_block_item(ps, 1)) {
    if (C_immediatep(ps) || !C_truep(C_i_pairp(ps))) return C_fix(-1);
    p = C_block_item(ps, 0);
    if (C_immediatep(p) || !C_truep(C_i_pairp(p))) return C_fix(-1);
    k = C_block_item(p, 0);
    if (!(mask & DS_KEYS_BIT(k)) || C_block_item(p, 1) == C_SCHEME_FALSE) continue;
    for (i = 0; i < n; i++)
      if (C_block_item(keys, i) == k) { bits |= (C_word)1 << i; break; }
  }
  return C_fix(bits);
}

/* Whether any alist of a list holds keys[0] with a true value (the draw
   order key: without it no entity list is sorted). */
static C_word ds_any_has_key(C_word alists, C_word keys) {
  C_word es;
  for (es = alists; !C_immediatep(es) && C_truep(C_i_pairp(es)); es = C_block_item(es, 1)) {
    C_word m = ds_keys_mask(C_block_item(es, 0), keys);
    if (m != C_fix(0) && m != C_fix(-1)) return C_SCHEME_TRUE;
  }
  return C_SCHEME_FALSE;
}

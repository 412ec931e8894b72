/* (downstroke pipeline)'s walk over a frame's entities: which steps some
   entity needs. Included by pipeline.scm (one compilation unit with it). */

/* need-keys (pipeline.scm): seven keys, #:solid? the third (index 2) */

/* A cheap first test of a key against the seven: one bit per key from bits
   4-9 of its address (symbols are aligned blocks); a key whose bit is not
   in the mask is none of them, which is the answer for most keys. */
#define DS_KEY_BIT(k) ((C_uword)1 << (((C_uword)(k) >> 4) & 63))

static C_word ds_pipeline_needs(C_word entities, C_word keys) {
  C_word es, ps, p, k, bits = 0, solids = 0;
  C_word k0 = C_block_item(keys, 0), k1 = C_block_item(keys, 1), k2 = C_block_item(keys, 2),
         k3 = C_block_item(keys, 3), k4 = C_block_item(keys, 4), k5 = C_block_item(keys, 5),
         k6 = C_block_item(keys, 6);
  C_uword mask = DS_KEY_BIT(k0) | DS_KEY_BIT(k1) | DS_KEY_BIT(k2) | DS_KEY_BIT(k3) |
                 DS_KEY_BIT(k4) | DS_KEY_BIT(k5) | DS_KEY_BIT(k6);
  int solid;
  for (es = entities; es != C_SCHEME_END_OF_LIST; es = C_block_item(es, 1)) {
    if (!C_truep(C_i_pairp(es))) return C_fix(-1);
    solid = 0;
    for (ps = C_block_item(es, 0); ps != C_SCHEME_END_OF_LIST; ps = C_block_item(ps, 1)) {
      if (!C_truep(C_i_pairp(ps))) return C_fix(-1);
      p = C_block_item(ps, 0);
      if (!C_truep(C_i_pairp(p))) return C_fix(-1);
      k = C_block_item(p, 0);
      if (!(mask & DS_KEY_BIT(k)) || C_block_item(p, 1) == C_SCHEME_FALSE) continue;
      if (k == k2) solid = 1;
      else if (k == k0) bits |= 1;
      else if (k == k1) bits |= 2;
      else if (k == k3) bits |= 8;
      else if (k == k4) bits |= 16;
      else if (k == k5) bits |= 32;
      else if (k == k6) bits |= 64;
    }
    if (solid && solids < 2) solids++;
  }
  return C_fix(bits | (solids << 8));
}

/* (downstroke pipeline)'s walk over a frame's entities: which steps some
   entity needs. Included by pipeline.scm (one compilation unit with it). */

/* need-keys (pipeline.scm) holds #:solid? at this index */
#define DS_SOLID_KEY 2

static C_word ds_pipeline_needs(C_word entities, C_word keys) {
  C_word es, ps, p, k, bits = 0, solids = 0, i, n = C_header_size(keys);
  int solid;
  for (es = entities; es != C_SCHEME_END_OF_LIST; es = C_block_item(es, 1)) {
    if (!C_truep(C_i_pairp(es))) return C_fix(-1);
    solid = 0;
    for (ps = C_block_item(es, 0); ps != C_SCHEME_END_OF_LIST; ps = C_block_item(ps, 1)) {
      if (!C_truep(C_i_pairp(ps))) return C_fix(-1);
      p = C_block_item(ps, 0);
      if (!C_truep(C_i_pairp(p))) return C_fix(-1);
      if (C_block_item(p, 1) == C_SCHEME_FALSE) continue;
      k = C_block_item(p, 0);
      for (i = 0; i < n; i++)
        if (k == C_block_item(keys, i)) {
          if (i == DS_SOLID_KEY) solid = 1; else bits |= 1 << i;
          break;
        }
    }
    if (solid && solids < 2) solids++;
  }
  return C_fix(bits | (solids << 8));
}

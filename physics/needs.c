/* (downstroke pipeline)'s walk over a frame's entities: which steps some
   entity needs. Included by pipeline.scm (one compilation unit with it);
   the keys and the answer's bits are needs.h's. The answer is -1 when an
   entity is not a list of pairs: the Scheme walk then raises the error. */
#include "core/entity.h"
#include "physics/needs.h"

/* the step each key asks for; #:solid? is counted instead (one solid
   entity may hold others up, two may also push each other) */
static const C_word ds_need_of_key[DS_NEED_KEYS] = {
  [DS_KEY_TWEEN] = DS_NEED_TWEENS, [DS_KEY_GRAVITY] = DS_NEED_GROUND,
  [DS_KEY_SOLID] = 0, [DS_KEY_GROUP_ID] = DS_NEED_GROUPS,
  [DS_KEY_ANIMATIONS] = DS_NEED_ANIMATION, [DS_KEY_IMMOVABLE] = DS_NEED_START,
  [DS_KEY_EMITTER] = DS_NEED_PARTICLES, [DS_KEY_ONE_WAY] = DS_NEED_START,
  [DS_KEY_CONTACTS] = DS_NEED_CONTACTS,
  [DS_KEY_DRAG] = DS_NEED_CONTROLS, [DS_KEY_AIR_DRAG] = DS_NEED_CONTROLS, [DS_KEY_MAX_VX] = DS_NEED_CONTROLS,
  [DS_KEY_MAX_VY] = DS_NEED_CONTROLS, [DS_KEY_BOUNCE] = DS_NEED_CONTROLS,
  [DS_KEY_CLIMBER] = DS_NEED_CLIMBERS
};

static C_word ds_pipeline_needs(C_word entities, C_word keys) {
  C_word es, ps, p, k, bits = 0;
  ds_key_table t;
  int i, solid, solids = 0;
  if (C_header_size(keys) != DS_NEED_KEYS) return C_fix(-1);
  ds_key_table_init(&t, keys, DS_NEED_KEYS);
  for (es = entities; es != C_SCHEME_END_OF_LIST; es = C_block_item(es, 1)) {
    if (!C_truep(C_i_pairp(es))) return C_fix(-1);
    solid = 0;
    for (ps = C_block_item(es, 0); ps != C_SCHEME_END_OF_LIST; ps = C_block_item(ps, 1)) {
      if (!C_truep(C_i_pairp(ps))) return C_fix(-1);
      p = C_block_item(ps, 0);
      if (!C_truep(C_i_pairp(p))) return C_fix(-1);
      k = C_block_item(p, 0);
      if ((i = ds_key_index(&t, keys, DS_NEED_KEYS, k)) < 0 || C_block_item(p, 1) == C_SCHEME_FALSE) continue;
      if (i == DS_KEY_SOLID) solid = 1; else bits |= ds_need_of_key[i];
    }
    if (solid && solids < 2) solids++;
  }
  if (solids >= 1) bits |= DS_NEED_SUPPORT;
  if (solids >= 2) bits |= DS_NEED_PAIRS;
  return C_fix(bits);
}

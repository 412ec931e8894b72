/* C's view of an entity, an alist of (keyword . value) pairs, for the C
   walks of physics/needs.c, shell/keys.c and core/entity.c: a cheap first
   test of a key against the few a walk looks for. Keywords are aligned
   heap blocks, so the bits from 4 up of a keyword's address spread keys
   over the bits of a word (64, or 32 where words are 32 bits wide); a key
   whose bit is not in a walk's mask is none of its keys, which is the
   answer for most keys. Keywords may move in a garbage collection, so a
   mask is made afresh on each call (the walks allocate nothing, so none
   happens during one). */
#ifndef DS_ENTITY_H
#define DS_ENTITY_H

#define DS_KEY_SLOT(k) ((((C_uword)(k)) >> 4) & (C_WORD_SIZE - 1))
#define DS_KEY_BIT(k) ((C_uword)1 << DS_KEY_SLOT(k))

/* What a walk knows of its keys (a vector of keywords), made once per
   call: the mask of their bits, and for each bit the one key that has it
   (-1: none; -2: several, searched in turn). A key that passes the mask
   is then one comparison, not one per key looked for, so what a walk
   costs hardly depends on where the keywords happen to lie. */
typedef struct {
  C_uword mask;
  signed char slot[C_WORD_SIZE];
} ds_key_table;

static inline void ds_key_table_init(ds_key_table *t, C_word keys, int n) {
  int i;
  t->mask = 0;
  for (i = 0; i < C_WORD_SIZE; i++) t->slot[i] = -1;
  for (i = 0; i < n; i++) {
    C_word k = C_block_item(keys, i);
    int s = (int)DS_KEY_SLOT(k);
    t->mask |= DS_KEY_BIT(k);
    t->slot[s] = t->slot[s] == -1 ? (signed char)i : -2;
  }
}

/* The index of k among the table's n keys (the first, if it is there
   twice), or -1. */
static inline int ds_key_index(const ds_key_table *t, C_word keys, int n, C_word k) {
  int i;
  if (!(t->mask & DS_KEY_BIT(k))) return -1;
  i = t->slot[DS_KEY_SLOT(k)];
  if (i >= 0) return C_block_item(keys, i) == k ? i : -1;
  for (i = 0; i < n && C_block_item(keys, i) != k; i++);
  return i == n ? -1 : i;
}

#endif

/* C's view of an entity, an alist of (keyword . value) pairs, for the C
   walks of physics/needs.c and shell/keys.c: a cheap first test of a key
   against the few a walk looks for. Keywords are aligned heap blocks, so
   the bits from 4 up of a keyword's address spread keys over the bits of
   a word (64, or 32 where words are 32 bits wide); a key whose
   bit is not in a walk's mask is none of its keys, which is the answer
   for most keys. Keywords may move in a garbage collection, so a mask is
   made afresh on each call (the walks allocate nothing, so none happens
   during one). */
#ifndef DS_ENTITY_H
#define DS_ENTITY_H

#define DS_KEY_BIT(k) ((C_uword)1 << (((C_uword)(k) >> 4) & (C_WORD_SIZE - 1)))

#endif

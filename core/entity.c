/* (downstroke entity)'s entity-ref, entity-set and entity-set* as C
   procedures, included by entity.scm. A game calls them for every entity
   every frame; in Scheme each call is a few calls more, whose frames and
   closures fill the nursery (docs/performance.org, "Entities read and
   written in C").

   Each is a closure whose code is the C function below and whose one
   slot holds the Scheme definition (entity.scm's entity-set/scheme and
   the rest). The C takes a proper list of pairs and gives exactly what
   the Scheme gives; for anything else (a plist, an improper list, a
   non-pair element before the key, another count of arguments, a copy
   too long to allocate at once) it calls the Scheme definition with the
   same arguments, which answers or raises the error it always raised. */

/* The longest prefix copied here (its cells are allocated on the stack
   at once); a longer one is the Scheme's: 3 words a cell. */
#define DS_ENTITY_MAX_COPY 1024
/* entity-set* settings taken here (a bit each); more are the Scheme's. */
#define DS_ENTITY_MAX_SETTINGS 16

#include "core/entity.h"

#define DS_PAIRP(x) (!C_immediatep(x) && C_block_header(x) == C_PAIR_TAG)

/* The closure's Scheme definition, called with the same arguments. */
static void ds_entity_scheme(C_word c, C_word *av) C_noret;
static void ds_entity_scheme(C_word c, C_word *av) {
  C_word proc = C_block_item(av[0], 1);
  av[0] = proc;
  ((C_proc)(void *)C_block_item(proc, 0))(c, av);
}

/* (entity-ref e key [default]): the first pair of key, as assq finds it. */
static void C_ccall ds_entity_ref(C_word c, C_word *av) C_noret;
static void C_ccall ds_entity_ref(C_word c, C_word *av) {
  C_word ps, p, key;
  if (c != 4 && c != 5) ds_entity_scheme(c, av);
  key = av[3];
  for (ps = av[2]; ps != C_SCHEME_END_OF_LIST; ps = C_u_i_cdr(ps)) {
    if (!DS_PAIRP(ps) || !DS_PAIRP(p = C_u_i_car(ps))) ds_entity_scheme(c, av);
    if (C_u_i_car(p) == key) C_kontinue(av[1], C_u_i_cdr(p));
  }
  C_kontinue(av[1], c == 5 ? av[4] : C_SCHEME_FALSE);
}

/* (entity-set e key value): the pairs before key's copied, its own
   replaced, the rest shared; e itself when key holds this very value; a
   key not held goes in front. */
static void C_ccall ds_entity_set(C_word c, C_word *av) C_noret;
static void C_ccall ds_entity_set(C_word c, C_word *av) {
  C_word e, key, value, ps, p, q, head, last, cell, *a;
  int n = 0, i;
  if (c != 5) ds_entity_scheme(c, av);
  e = av[2]; key = av[3]; value = av[4];
  for (ps = e; ps != C_SCHEME_END_OF_LIST; ps = C_u_i_cdr(ps), n++) {
    if (n == DS_ENTITY_MAX_COPY || !DS_PAIRP(ps) || !DS_PAIRP(p = C_u_i_car(ps)))
      ds_entity_scheme(c, av);
    if (C_u_i_car(p) == key) break;
  }
  if (ps != C_SCHEME_END_OF_LIST && C_u_i_cdr(C_u_i_car(ps)) == value) C_kontinue(av[1], e);
  if (!C_demand(3 * (n + 2))) C_save_and_reclaim((void *)ds_entity_set, c, av);
  a = C_alloc(3 * (n + 2));
  if (ps == C_SCHEME_END_OF_LIST)
    C_kontinue(av[1], C_a_pair(&a, C_a_pair(&a, key, value), e));
  head = last = C_SCHEME_FALSE;
  for (q = e, i = 0; i < n; q = C_u_i_cdr(q), i++) {
    cell = C_a_pair(&a, C_u_i_car(q), C_SCHEME_END_OF_LIST);
    if (last == C_SCHEME_FALSE) head = cell; else C_set_block_item(last, 1, cell);
    last = cell;
  }
  cell = C_a_pair(&a, C_a_pair(&a, key, value), C_u_i_cdr(ps));
  if (last == C_SCHEME_FALSE) head = cell; else C_set_block_item(last, 1, cell);
  C_kontinue(av[1], head);
}

/* (entity-set* e k1 v1 k2 v2 ...): entity.scm's entity-set*, in one walk
   and one copy. Setting i is av[3 + 2i], av[4 + 2i]; the last setting of
   a key is the one that counts. An entity holding a key twice is the
   Scheme's. */
static void C_ccall ds_entity_set_star(C_word c, C_word *av) C_noret;
static void C_ccall ds_entity_set_star(C_word c, C_word *av) {
  C_word e, ps, p, q, k, head, last, cell, tail, *a;
  int m, i, j, n, changed = -1, absent = 0;
  int last_of[DS_ENTITY_MAX_SETTINGS], at[DS_ENTITY_MAX_SETTINGS], later[DS_ENTITY_MAX_SETTINGS];
  C_uword keymask = 0;
  if (c < 3 || (c - 3) % 2 != 0 || (m = (c - 3) / 2) > DS_ENTITY_MAX_SETTINGS) ds_entity_scheme(c, av);
  e = av[2];
  /* last_of[i]: the last setting of setting i's key; later[i]: 1 when an
     earlier setting has the same key; at[i]: where e holds it (-1: not) */
  for (i = 0; i < m; i++) {
    last_of[i] = i; later[i] = 0; at[i] = -1;
    keymask |= DS_KEY_BIT(av[3 + 2 * i]);
  }
  for (i = 0; i < m; i++)
    for (j = i + 1; j < m; j++)
      if (av[3 + 2 * j] == av[3 + 2 * i]) { last_of[i] = j; later[j] = 1; }
  /* the walk: where e holds each key, and the last pair whose value changes */
  for (ps = e, n = 0; ps != C_SCHEME_END_OF_LIST; ps = C_u_i_cdr(ps), n++) {
    if (n == DS_ENTITY_MAX_COPY || !DS_PAIRP(ps) || !DS_PAIRP(p = C_u_i_car(ps)))
      ds_entity_scheme(c, av);
    k = C_u_i_car(p);
    if (!(keymask & DS_KEY_BIT(k))) continue;
    for (i = 0; i < m && av[3 + 2 * i] != k; i++);
    if (i == m) continue;
    i = last_of[i];
    if (at[i] >= 0) ds_entity_scheme(c, av);             /* e holds k twice */
    at[i] = n;
    if (C_u_i_cdr(p) != av[4 + 2 * i]) changed = n;
  }
  for (i = 0; i < m; i++) if (!later[i] && at[last_of[i]] < 0) absent++;
  if (!C_demand(3 * (changed + 1) + 3 * m + 6 * absent))
    C_save_and_reclaim((void *)ds_entity_set_star, c, av);
  a = C_alloc(3 * (changed + 1) + 3 * m + 6 * absent);
  /* the copy of pairs 0..changed, each set key's pair replaced */
  head = last = C_SCHEME_FALSE;
  for (q = e, n = 0; n <= changed; q = C_u_i_cdr(q), n++) {
    p = C_u_i_car(q);
    for (i = 0; i < m; i++)
      if (at[i] == n) {
        if (C_u_i_cdr(p) != av[4 + 2 * i]) p = C_a_pair(&a, C_u_i_car(p), av[4 + 2 * i]);
        break;
      }
    cell = C_a_pair(&a, p, C_SCHEME_END_OF_LIST);
    if (last == C_SCHEME_FALSE) head = cell; else C_set_block_item(last, 1, cell);
    last = cell;
  }
  if (last == C_SCHEME_FALSE) tail = e;
  else { C_set_block_item(last, 1, q); tail = head; }
  /* the keys e does not hold, in front, in the order first set: the last
     one set first */
  for (i = 0; i < m; i++)
    if (!later[i] && at[last_of[i]] < 0)
      tail = C_a_pair(&a, C_a_pair(&a, av[3 + 2 * i], av[4 + 2 * last_of[i]]), tail);
  C_kontinue(av[1], tail);
}

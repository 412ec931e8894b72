/* What ds_pipeline_needs (needs.c) answers to pipeline.scm: the keys it is
   given, by index in the vector it gets, and the bits of its answer.
   pipeline.scm names each value here with define-c-constant, which the C
   compiler checks, so the two sides cannot drift apart. */
#ifndef DS_NEEDS_H
#define DS_NEEDS_H

/* the keys, by index: an entity holding one with a true value needs a step */
enum {
  DS_KEY_TWEEN, DS_KEY_GRAVITY, DS_KEY_SOLID, DS_KEY_GROUP_ID,
  DS_KEY_ANIMATIONS, DS_KEY_IMMOVABLE, DS_KEY_EMITTER, DS_KEY_ONE_WAY, DS_KEY_CONTACTS,
  DS_KEY_DRAG, DS_KEY_AIR_DRAG, DS_KEY_MAX_VX, DS_KEY_MAX_VY, DS_KEY_BOUNCE, DS_KEY_CLIMBER,
  DS_NEED_KEYS                  /* how many */
};

/* the answer's bits: which steps some entity of the list needs */
enum {
  DS_NEED_TWEENS = 1,           /* an entity has a #:tween */
  DS_NEED_GROUND = 2,           /* an entity has #:gravity? */
  DS_NEED_PAIRS = 4,            /* two or more entities have #:solid? */
  DS_NEED_GROUPS = 8,           /* an entity has a #:group-id */
  DS_NEED_ANIMATION = 16,       /* an entity has #:animations */
  DS_NEED_SUPPORT = 32,         /* an entity has #:solid? (it may hold others up) */
  DS_NEED_START = 64,           /* an entity has #:immovable? (a platform may carry)
                                   or #:one-way? (landings read where bodies began) */
  DS_NEED_PARTICLES = 128,      /* an entity has an #:emitter */
  DS_NEED_CONTACTS = 256,       /* an entity has #:contacts? */
  DS_NEED_CONTROLS = 512,       /* an entity has a body control (#:drag ... #:bounce) */
  DS_NEED_CLIMBERS = 1024       /* an entity has #:climber? (the climbing step) */
};

#endif

/* The motion kernel's interface with motion.scm: the flags it is given
   for an entity and the keys it answers to write. motion.scm names every
   value below as a constant that the C compiler checks against this file
   (define-c-constant), so the two sides cannot drift apart. */
#ifndef DS_MOTION_H
#define DS_MOTION_H

/* what the scene and the entity hold */
enum {
  DS_HAS_MAP = 1,       /* the scene has a map */
  DS_GRAVITY = 2,       /* #:gravity? is true */
  DS_SWEPT = 4,         /* swept collision mode */
  DS_GROUND = 8,        /* ground detection joins the pass */
  DS_HAS_X = 16, DS_HAS_Y = 32, DS_HAS_VX = 64, DS_HAS_VY = 128,
  DS_HAS_AY = 256, DS_HAS_ON = 512,   /* the key is present */
  DS_NOT_HERE = 1024,   /* an unknown #:collision-mode: not for the kernel */
  DS_DROP = 2048,       /* #:drop-through?: one-way tiles do not hold it */
  DS_SLOPES = 4096,     /* the map has slope cells: a body near one is not for the kernel */
  DS_ESCAPE = 8192      /* the entity has no #:tween: the flonum kernel may take it out of solid tiles */
};

/* The flonum kernel's answer for a swept body that moves and starts the
   frame inside solid tiles, asked without DS_ESCAPE: motion.scm asks
   again with it, unless the body has a #:tween (the escape leaves such a
   body to the tile passes). */
#define DS_INSIDE (-2)

/* the keys to write; their new values are out[0] .. out[5] in this order.
   With DS_X_RATIO the new x is the rational out[0] / out[6], with
   DS_Y_RATIO y is out[1] / out[7]. */
enum {
  DS_WRITE_X = 1, DS_WRITE_Y = 2, DS_WRITE_VX = 4, DS_WRITE_VY = 8,
  DS_WRITE_AY = 16, DS_WRITE_ON = 32, DS_X_RATIO = 64, DS_Y_RATIO = 128,
  /* the flonum kernel's answers: the new x, y or vy is the double
     ds_flonum_out[0], [1] or [3] (motion.c) */
  DS_X_FLONUM = 256, DS_Y_FLONUM = 512, DS_VY_FLONUM = 1024
};

/* A solid-grid byte whose cell holds a body landing from above and lets
   one through from below: a one-way tile or a ladder's top (2), a ceiling
   slope (4), whose top edge is solid (core/map.scm's one-way-byte?). */
#define DS_ONE_WAY(b) ((b) == 2 || (b) == 4)

#endif

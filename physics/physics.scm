;;; (downstroke physics): every step of the pipeline docs/physics.org lists, under the one name games import.
;;;
;;; Units: positions in pixels, velocities in pixels per frame, gravity in
;;; pixels per frame squared. Per-entity steps have the signature
;;; (step scene entity dt) and return a new entity; the bulk steps map an
;;; entity list to an entity list. Numbers may be fixnums, flonums, bignums
;;; or exact rationals: integer inputs give integer results, and exact
;;; rationals stay exact. A NaN or infinite position, size or velocity is an
;;; error naming the entity and the key (see `entity-number`).
;;;
;;; The rules live in this folder, one module each: (downstroke tuning)
;;; the constants, (downstroke body) reading a body's numbers,
;;; (downstroke tile-grid) the cells and the map's solid grid,
;;; (downstroke escape) the way out of solid tiles, (downstroke
;;; tile-collisions) the tile steps, (downstroke contacts) ground and
;;; bodies against bodies, (downstroke motion) the motion steps and the
;;; motion pass, (downstroke groups) groups, (downstroke touch) contacts
;;; per side, (downstroke ladders) climbing ladders, (downstroke slopes)
;;; slope tiles, the body's foot and its head.

(module (downstroke physics) ()
  ;; imported too, not only re-exported, so that loading this module loads
  ;; the code of all of them
  (import (chicken module) (downstroke tuning) (downstroke tile-grid) (downstroke escape)
          (downstroke tile-collisions) (downstroke contacts) (downstroke motion)
          (downstroke groups) (downstroke touch) (downstroke ladders) (downstroke slopes))
  ;; without the names after ";; for sibling modules only" in tile-grid.scm's,
  ;; escape.scm's, tile-collisions.scm's, contacts.scm's and motion.scm's export lists (tests/layout-test.scm checks
  ;; that games do not see them)
  (reexport (downstroke tuning)
            (except (downstroke tile-grid)
                    ->integer cell-of cell-ceiling span-first span-last nearest-solid-line grids
                    column-grid row-grid pass-map one-way-map?)
            (except (downstroke escape) escape-place straight-in-c search-way-out
                    diagonal-in-c diagonal-may-be-nearer?)
            (except (downstroke tile-collisions)
                    swept-mode? stop-at-tiles-x stop-at-tiles-y tile-ground? climbing? slope-cut-of ceiling-cut-of)
            (except (downstroke contacts) push-apart/scheme) (except (downstroke motion) motion-kernel-declines)
            (downstroke groups) (downstroke touch) (downstroke ladders) (only (downstroke slopes) slope-surface ceiling-surface)))

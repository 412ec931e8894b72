;;; (downstroke tilemap): what a game imports for maps, the map data of
;;; (downstroke map), the Tiled loader of (downstroke tmx) and the objects
;;; as entities of (downstroke objects) under one name, without the names
;;; those modules export only for each other. The pure core (physics,
;;; scene) imports (downstroke map) alone, so it never loads expat, zlib or
;;; zstd.

(module (downstroke tilemap) ()
  ;; imported too, not only re-exported, so that loading this module loads
  ;; the code of all three
  (import (chicken module) (downstroke map) (downstroke tmx) (downstroke objects))
  ;; the names after ";; for sibling modules only" in map.scm's and
  ;; objects.scm's export lists (tests/layout-test.scm checks the two agree)
  (reexport (except (downstroke map)
                    %make-layer make-image make-tile make-tileset make-map-object
                    tileset-tile-table tileset-tile-ids gid-mask check-integer tilemap-slopes)
            (downstroke tmx)
            (except (downstroke objects) object-layer-selector)))

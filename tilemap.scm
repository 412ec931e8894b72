;;; (downstroke tilemap): what a game imports for maps, the map data of
;;; (downstroke map), the Tiled loader of (downstroke tmx) and the objects
;;; as entities of (downstroke objects) under one name. The pure core (physics, scene) imports (downstroke map) alone,
;;; so it never loads expat, zlib or zstd.

(module (downstroke tilemap) ()
  ;; imported too, not only re-exported, so that loading this module loads
  ;; the code of both
  (import (chicken module) (downstroke map) (downstroke tmx) (downstroke objects))
  (reexport (downstroke map) (downstroke tmx) (downstroke objects)))

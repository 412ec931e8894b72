(import (downstroke test) (downstroke prefabs) (downstroke entity)
        (downstroke animation)
        scheme (chicken base) (chicken string) (chicken file) (chicken io))

;;; Helpers (prefixed pf- because every suite is loaded into one toplevel).

(define (pf-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

(define (pf-dedup l)
  (let loop ((l l) (out '()))
    (cond ((null? l) (reverse out))
          ((member (car l) out) (loop (cdr l) out))
          (else (loop (cdr l) (cons (car l) out))))))

(define pf-files '())

;; A prefab file with this text, written now; its path.
(define (pf-file text)
  (let ((p (create-temporary-file ".prefabs")))
    (call-with-output-file p (lambda (port) (write-string text #f port)))
    (set! pf-files (cons p pf-files))
    p))

(define pf-main
  (pf-file #<<EOF
;; test prefabs
((mixins
  (body   #:width 8 #:height 8 #:vx 0 #:vy 0 #:solid? #f)
  (solid  #:solid? #t #:color (1 2 3))
  (heavy  #:solid? heavy #:mass 10))
 (prefabs
  (crate  body solid #:width 16 #:tile-id 7)
  (rock   body solid heavy #:height 12)
  (brick  body heavy solid)
  (plain  #:hp 1)
  (hero   body animated #:tags (player)
          #:animations ((#:name idle #:frames (1 2) #:duration 5)
                        (#:name walk #:frames (3 (4 . 2)) #:duration 3 #:loop? #f)))
  (boss   animated #:anim-name walk
          #:animations ((#:name idle #:frames (1)) (#:name walk #:frames (2))))
  (config #:stats (#:hp 3 #:speed 2) #:list (1 2 3))))
EOF
))

(define (pf-bad text) (pf-file text))

(test-group "prefabs"
  (define p (load-prefabs pf-main))

  (test-group "loading"
    (test-assert "a prefab collection" (prefabs? p))
    (test "prefab names in file order" '(crate rock brick plain hero boss config)
          (prefab-names p))
    (test "mixin names in file order" '(body solid heavy) (mixin-names p))
    (test "source is the file" pf-main (prefabs-source p)))

  (test-group "mixins in order, then the prefab's keys"
    (let ((crate (instantiate-prefab p 'crate)))
      (test "#:type is the prefab's name" 'crate (entity-ref crate #:type))
      (test "prefab key beats mixin" 16 (entity-ref crate #:width))
      (test "mixin key kept" 8 (entity-ref crate #:height))
      (test "later mixin wins" #t (entity-ref crate #:solid?))
      (test "exact alist" '((#:type . crate) (#:width . 16) (#:height . 8) (#:vx . 0)
                            (#:vy . 0) (#:solid? . #t) (#:color . (1 2 3)) (#:tile-id . 7))
            crate))
    (test "rock: heavy after solid" 'heavy (entity-ref (instantiate-prefab p 'rock) #:solid?))
    (test "brick: solid after heavy" #t (entity-ref (instantiate-prefab p 'brick) #:solid?))
    (test "rock keeps every mixin's keys" 10 (entity-ref (instantiate-prefab p 'rock) #:mass))
    (test "rock's own height" 12 (entity-ref (instantiate-prefab p 'rock) #:height))
    (test "no mixins" '((#:type . plain) (#:hp . 1)) (instantiate-prefab p 'plain)))

  (test-group "overrides"
    (let ((c (instantiate-prefab p 'crate overrides: '(#:x 100 #:y 50 #:width 32))))
      (test "override beats the prefab" 32 (entity-ref c #:width))
      (test "new keys" '(100 50) (list (entity-ref c #:x) (entity-ref c #:y)))
      (test "no duplicate keys" (length (pf-dedup (map car c))) (length c)))
    (test "alist overrides" 'box
          (entity-ref (instantiate-prefab p 'crate overrides: '((#:type . box))) #:type))
    (test "override's nested plist becomes an alist" '((#:a . 1))
          (entity-ref (instantiate-prefab p 'plain overrides: '(#:cfg (#:a 1))) #:cfg))
    (test-error "malformed overrides" (pf-says? "overrides")
                (instantiate-prefab p 'crate overrides: '(#:x)))
    (test-error "overrides of the wrong shape" (pf-says? "overrides")
                (instantiate-prefab p 'crate overrides: 42))
    (test "instances are independent" 8
          (begin (instantiate-prefab p 'crate overrides: '(#:height 99))
                 (entity-ref (instantiate-prefab p 'crate) #:height))))

  (test-group "nested plists"
    (let ((hero (instantiate-prefab p 'hero)))
      (test "#:animations is a list of alists"
            '(((#:name . idle) (#:frames . (1 2)) (#:duration . 5))
              ((#:name . walk) (#:frames . (3 (4 . 2))) (#:duration . 3) (#:loop? . #f)))
            (entity-ref hero #:animations))
      (test "plain lists stay" '(player) (entity-ref hero #:tags))
      (test "animated: frame 0" 0 (entity-ref hero #:anim-frame))
      (test "animated: tick 0" 0 (entity-ref hero #:anim-tick))
      (test "animated: #:anim-name is the first animation's" 'idle
            (entity-ref hero #:anim-name))
      (test "apply-animation runs on it" 1
            (entity-ref (apply-animation #f hero 16) #:tile-id)))
    (test "a prefab's #:anim-name beats animated's" 'walk
          (entity-ref (instantiate-prefab p 'boss) #:anim-name))
    (test "a nested plist value" '((#:hp . 3) (#:speed . 2))
          (entity-ref (instantiate-prefab p 'config) #:stats))
    (test "a list of numbers stays" '(1 2 3)
          (entity-ref (instantiate-prefab p 'config) #:list))
    (test "nested-plists->alists" '(((#:a . ((#:b . 1)))) ((#:c . (1 2))))
          (nested-plists->alists '((#:a (#:b 1)) (#:c (1 2))))))

  (test-group "engine-mixins"
    (test-assert "animated is there" (assq 'animated engine-mixins))
    (test "animated's defaults" '((#:anim-name . #f) (#:anim-frame . 0) (#:anim-tick . 0))
          (cdr (assq 'animated engine-mixins))))

  (test-group "errors"
    (test-error "unknown prefab names it and the file" (pf-says? "dragon" pf-main)
                (instantiate-prefab p 'dragon))
    (test-error "unknown mixin names file, prefab and mixin"
                (pf-says? "flying" "bat" "unknown mixin")
                (load-prefabs (pf-bad "((prefabs (bat flying #:hp 1)))")))
    (let ((f (pf-bad "((prefabs (bat flying #:hp 1)))")))
      (test-error "the unknown mixin's file is named" (pf-says? f) (load-prefabs f)))
    (let ((f (pf-bad "((mixins (m #:a 1)) (prefabs (x m #:a))")))
      (test-error "a file that does not parse" (pf-says? f "does not parse")
                  (load-prefabs f)))
    (let ((f (pf-bad "((mixins (m #:a 1)) (prefabs (x m #:a)))")))
      (test-error "key without value" (pf-says? f "prefab x" "malformed" "#:a")
                  (load-prefabs f)))
    (let ((f (pf-bad "((mixins (m #:a 1 b 2)))")))
      (test-error "non-keyword in a mixin" (pf-says? f "mixin m" "malformed")
                  (load-prefabs f)))
    (let ((f (pf-bad "((prefabs (x #:a 1 #:a 2)))")))
      (test-error "a key given twice" (pf-says? f "prefab x" "twice") (load-prefabs f)))
    (let ((f (pf-bad "((prefabs (x #:a 1) (x #:a 2)))")))
      (test-error "a prefab defined twice" (pf-says? f "prefab x" "twice")
                  (load-prefabs f)))
    (let ((f (pf-bad "((prefabs (\"x\" #:a 1)))")))
      (test-error "a name that is not a symbol" (pf-says? f "malformed" "\"x\"")
                  (load-prefabs f)))
    (let ((f (pf-bad "((prefabs (x 42 #:a 1)))")))
      (test-error "a mixin name that is not a symbol" (pf-says? f "prefab x" "42")
                  (load-prefabs f)))
    (let ((f (pf-bad "((prefabs x))")))
      (test-error "an entry that is not a list" (pf-says? f "malformed")
                  (load-prefabs f)))
    (let ((f (pf-bad "((monsters (x #:a 1)))")))
      (test-error "an unknown section" (pf-says? f "monsters") (load-prefabs f)))
    (let ((f (pf-bad "(prefabs (x #:a 1))")))
      (test-error "a file that is not a list of sections" (pf-says? f "malformed")
                  (load-prefabs f)))
    (let ((f (pf-bad "42")))
      (test-error "a file that is a number" (pf-says? f "malformed") (load-prefabs f)))
    (let ((f (pf-bad "")))
      (test-error "an empty file" (pf-says? f "empty") (load-prefabs f)))
    (let ((f (pf-bad "((prefabs)) ((mixins))")))
      (test-error "two forms" (pf-says? f "more than one form") (load-prefabs f)))
    (test-error "a missing file" (pf-says? "/tmp/no-such-prefabs.scm")
                (load-prefabs "/tmp/no-such-prefabs.scm"))
    (test-error "not a collection" (pf-says? "prefab")
                (instantiate-prefab '() 'crate)))

  (test-group "other shapes"
    (let ((f (pf-bad "((prefabs (a animated #:animations ((#:name run #:frames (9)))))
                       (mixins))")))
      (test "sections in any order; empty sections" 'run
            (entity-ref (instantiate-prefab (load-prefabs f) 'a) #:anim-name)))
    (test "an empty file form" '() (prefab-names (load-prefabs (pf-bad "()"))))
    (let ((f (pf-bad "((mixins (animated #:anim-frame 5)) (prefabs (a animated)))")))
      (test "a file's mixin replaces an engine mixin" 5
            (entity-ref (instantiate-prefab (load-prefabs f) 'a) #:anim-frame)))
    (test "parse-prefabs on data" '((#:type . q) (#:v . 1))
          (instantiate-prefab (parse-prefabs '((prefabs (q #:v 1)))) 'q))))

(for-each delete-file* pf-files)

;;; (downstroke text): text on an SDL renderer.
;;;
;;; TrueType text through SDL2_ttf (Debian's libsdl2-ttf-dev):
;;;
;;;   (open-font path size)            a font record; TTF_Init is called the
;;;                                    first time. A missing or unreadable
;;;                                    file is an error naming the path.
;;;   (close-font! font)               frees the font; any number of calls.
;;;                                    A finalizer closes a forgotten font.
;;;   (draw-text! renderer font string x y #!key (color '(255 255 255)))
;;;                                    draws UTF-8 `string` with its top-left
;;;                                    corner at (x, y) (floored to whole
;;;                                    pixels); color is (r g b [a]). Answers
;;;                                    (values w h), the size drawn.
;;;   (text-size font string)          (values w h) in pixels of `string`.
;;;
;;; draw-text! renders with TTF_RenderUTF8_Blended (anti-aliased) into a
;;; surface, makes a texture of it and copies it. The textures of the last
;;; 16 texts drawn (each of at most 256 x 256 pixels) are kept, and the
;;; same text drawn again (same renderer, font, string and colour) is
;;; copied from its texture: a text drawn every frame is rendered once.
;;; A larger text's texture is freed at once; closing a font frees its
;;; texts' textures, and a renderer's end frees its own. So drawing text
;;; every frame holds on to at most those 16 textures.
;;; (text-textures-made) answers how many textures draw-text! has made.
;;; The empty string draws nothing. A newline starts a new line.
;;;
;;; Layout, for both kinds of font (as LÖVE's love.graphics.printf lays
;;; out): (text-layout font string #!key width align scale) answers
;;; (values lines w h), lines a list of (text x y w), each line's text, its
;;; place from the block's top-left corner and its width. A newline always
;;; breaks a line; with width: (pixels) a line also breaks at the last
;;; space that lets it fit (the spaces at the break are dropped), and a word
;;; wider than the width on its own breaks between characters. align: is
;;; left, center (or centre) or right, within the width when one is given,
;;; else within the widest line. w is the width when given, else the
;;; widest line's; h is the font's height plus one line skip for each
;;; further line (TTF_FontLineSkip; a sprite font's glyph height times the
;;; scale). draw-text! and draw-sprite-text! take the same width: and
;;; align: and draw that layout at (x, y), answering its (values w h).
;;;
;;; Bitmap sprite fonts: a texture holding a grid of equal glyph cells,
;;; `columns` cells to a row, the cell of character c at index
;;; (char->integer c) - (char->integer first-char), row by row:
;;;
;;;   (make-sprite-font texture #!key glyph-width glyph-height
;;;                     (first-char #\space) (columns 16))
;;;   (draw-sprite-text! renderer sprite-font string x y #!key (scale 1))
;;;                                    copies each character's cell to
;;;                                    x + i * glyph-width * scale; a newline
;;;                                    starts a new line glyph-height * scale
;;;                                    lower. A character with no cell on the
;;;                                    sheet (before first-char, or past its
;;;                                    last row) leaves a blank of one glyph.
;;;                                    Answers (values w h) of the text.
;;;   (sprite-text-size sprite-font string #!key (scale 1))   (values w h)
;;;
;;; Strings are CHICKEN strings, that is bytes: a sprite font indexes bytes,
;;; so it suits ASCII sheets; TTF text takes any UTF-8.

(module (downstroke text)
  (open-font close-font! font? font-alive?
   draw-text! text-size text-layout font-line-skip text-textures-made
   make-sprite-font sprite-font? sprite-font-texture sprite-font-glyph-width
   sprite-font-glyph-height sprite-font-first-char sprite-font-columns
   draw-sprite-text! sprite-text-size
   max-font-size max-text-length)

  (import (downstroke keywords) (only (downstroke media-header) file-problem))
  (import scheme (chicken base) (chicken foreign) (chicken gc) (chicken format)
          (chicken file) (chicken condition)
          (downstroke sdl2))

  (foreign-declare #<<EOF
#include <SDL.h>
#include <SDL_ttf.h>

/* A text's texture: rendered, made a texture (blended when copied).
   NULL with *status -1 for a TTF failure, -2 for an SDL failure (the
   error in SDL_GetError). Its size goes to *w and *h. */
static SDL_Texture *downstroke_text_texture(SDL_Renderer *r, TTF_Font *font, const char *s,
                                            int cr, int cg, int cb, int ca,
                                            int *w, int *h, int *status) {
  SDL_Color c;
  SDL_Surface *surf;
  SDL_Texture *tex;
  c.r = (Uint8)cr; c.g = (Uint8)cg; c.b = (Uint8)cb; c.a = (Uint8)ca;
  *status = 0;
  surf = TTF_RenderUTF8_Blended(font, s, c);
  if (!surf) { *status = -1; return NULL; }
  tex = SDL_CreateTextureFromSurface(r, surf);
  *w = surf->w; *h = surf->h;
  SDL_FreeSurface(surf);
  if (!tex) { *status = -2; return NULL; }
  SDL_SetTextureBlendMode(tex, SDL_BLENDMODE_BLEND);
  return tex;
}

/* The texture copied with its top-left corner at (x, y): 0, or -2 for an
   SDL failure. */
static int downstroke_text_copy(SDL_Renderer *r, SDL_Texture *tex, int x, int y, int w, int h) {
  SDL_Rect dst;
  dst.x = x; dst.y = y; dst.w = w; dst.h = h;
  return SDL_RenderCopy(r, tex, NULL, &dst) < 0 ? -2 : 0;
}
EOF
)

  ;;; ------------------------------------------------------------------
  ;;; Errors: kinds exn and text, the message naming the call.

  (define ttf-get-error (foreign-lambda c-string "TTF_GetError"))

  (define (text-error who msg . args)
    (signal
     (make-composite-condition
      (make-property-condition 'exn 'location who 'message msg 'arguments args)
      (make-property-condition 'text))))

  ;;; ------------------------------------------------------------------
  ;;; TTF

  (define ttf-ready? #f)

  (define (ttf-init! who)
    (unless ttf-ready?
      (when (< ((foreign-lambda int "TTF_Init")) 0)
        (text-error who (sprintf "TTF_Init: ~a" (ttf-get-error))))
      (set! ttf-ready? #t)))

  ;; ptr: the TTF_Font*, #f once closed.
  (define-record-type font
    (%make-font ptr path size)
    font?
    (ptr font-ptr font-ptr-set!)
    (path font-path)
    (size font-point-size))

  (define (font-alive? f) (and (font-ptr f) #t))

  ;; Limits that keep a mistaken or hostile value from exhausting memory
  ;; (a glyph cache of 2^32-point glyphs, a texture for a megabyte of
  ;; text); parameters, so a game that needs more says so.
  (define max-font-size (make-parameter 1000))       ; points
  (define max-text-length (make-parameter 10000))    ; characters drawn at once

  (define (open-font path size)
    (unless (string? path) (error 'open-font "the font path must be a string" path))
    (unless (and (exact-integer? size) (> size 0))
      (error 'open-font "the point size must be a positive integer" size))
    (when (> size (max-font-size))
      (error (sprintf "open-font: ~s at ~a points is above max-font-size (~a); (max-font-size N) allows more"
                      path (if (> size 1000000000) "more than 10^9" size) (max-font-size))))
    (let ((why (file-problem path)))
      (cond ((equal? why "not found")
             (text-error 'open-font (sprintf "TTF_OpenFont: cannot open ~s: no such file" path)))
            (why (text-error 'open-font (sprintf "TTF_OpenFont: cannot open ~s: it ~a" path why)))))
    (ttf-init! 'open-font)
    (let ((p ((foreign-lambda c-pointer "TTF_OpenFont" c-string int) path size)))
      (unless p
        (text-error 'open-font (sprintf "TTF_OpenFont: cannot open ~s: ~a" path (ttf-get-error))))
      (set-finalizer! (%make-font p path size) close-font!)))

  (define (close-font! f)
    (let ((p (font-ptr f)))
      (when p
        (forget-texts! (lambda (e) (eq? (text-font e) f)))
        (font-ptr-set! f #f)
        ((foreign-lambda void "TTF_CloseFont" c-pointer) p)))
    (void))

  (define (live-font who f)
    (unless (and (font? f) (font-ptr f))
      (error who (sprintf "~a: not an open font" who) f))
    (font-ptr f))

  (define (text-string who s)
    (unless (string? s) (error who "the text must be a string" s))
    (when (> (string-length s) (max-text-length))
      (error (sprintf "~a: a text of ~a characters is above max-text-length (~a); (max-text-length N) allows more"
                      who (string-length s) (max-text-length))))
    s)

  (define (text-size font string)
    (let ((p (live-font 'text-size font)))
      (text-string 'text-size string)
      (let-location ((w int 0) (h int 0))
        (when (< ((foreign-lambda int "TTF_SizeUTF8" c-pointer c-string (c-pointer int) (c-pointer int))
                  p string (location w) (location h))
                 0)
          (text-error 'text-size (sprintf "TTF_SizeUTF8: ~a" (ttf-get-error))))
        (values w h))))

  (define (color-bytes who c)
    (unless (and (list? c) (<= 3 (length c) 4)
                 (let ok ((l c)) (or (null? l) (and (fixnum? (car l)) (<= 0 (car l) 255) (ok (cdr l))))))
      (error who "color: must be (r g b [a]) of integers 0..255" c))
    (if (= (length c) 3) (append c '(255)) c))

  ;; A text's position, as a whole pixel; NaN, an infinity or a non-number
  ;; is an error naming the procedure and the coordinate.
  (define (pixel who name v)
    (unless (and (real? v) (or (exact? v) (finite? v)))
      (error who (sprintf "~a is ~s, not a finite number" name v)))
    (let ((f (floor v))) (if (exact? f) f (inexact->exact f))))

  ;; A TrueType text that starts this far away (px) is not drawn: it
  ;; cannot reach any view, and SDL's C ints cannot hold where it is.
  (define far-text (expt 2 24))

;;; ------------------------------------------------------------------
  ;;; The textures of the texts drawn last. A game draws the same texts
  ;;; frame after frame (a score, a title), and rendering one, making its
  ;;; texture and freeing it each time is most of what drawing it costs:
  ;;; in the browser each is a texture made, uploaded and deleted in WebGL
  ;;; (docs/performance.org, "Where the platformer's frame goes"). So the
  ;;; last `text-cache-entries` texts drawn, each of at most
  ;;; `text-cache-pixels`, keep their textures, and the same text (same
  ;;; renderer, font, string and colour) is copied from it again. A larger
  ;;; text is made and freed as before. An entry whose renderer has ended
  ;;; is dropped (SDL freed its texture with the renderer); closing a font
  ;;; frees its entries' textures.

  (define text-cache-entries 16)
  (define text-cache-pixels (* 256 256))

  (define-record-type text-entry
    (make-text-entry renderer font string color texture w h)
    text-entry?
    (renderer text-renderer)
    (font text-font)
    (string text-string-drawn)
    (color text-color)
    (texture text-texture)
    (w text-w)
    (h text-h))

  ;; Most recently drawn first.
  (define text-cache '())
  ;; Textures made by draw-text! since the start (text-textures-made).
  (define textures-made 0)
  (define (text-textures-made) textures-made)

  (define destroy-c-texture! (foreign-lambda void "SDL_DestroyTexture" c-pointer))

  ;; Frees the entry's texture, unless its renderer has freed it already.
  (define (free-entry! e)
    (when (renderer-alive? (text-renderer e))
      (destroy-c-texture! (text-texture e))))

  ;; Drops (and frees) the entries `drop?` answers true for.
  (define (forget-texts! drop?)
    (set! text-cache
      (let keep ((es text-cache))
        (cond ((null? es) '())
              ((drop? (car es)) (free-entry! (car es)) (keep (cdr es)))
              (else (cons (car es) (keep (cdr es))))))))

  (define (cached-text renderer font string c)
    (let find ((es text-cache))
      (cond ((null? es) #f)
            ((let ((e (car es)))
               (and (eq? (text-renderer e) renderer) (eq? (text-font e) font)
                    (equal? (text-color e) c) (string=? (text-string-drawn e) string)))
             (car es))
            (else (find (cdr es))))))

  ;; The entry first, the ended renderers' entries gone, at most
  ;; text-cache-entries kept.
  (define (remember-text! e)
    (let keep ((es (cons e (remove-entry e text-cache))) (n 0) (out '()))
      (cond ((null? es) (set! text-cache (reverse out)))
            ((not (renderer-alive? (text-renderer (car es)))) (keep (cdr es) n out))
            ((>= n text-cache-entries) (free-entry! (car es)) (keep (cdr es) n out))
            (else (keep (cdr es) (+ n 1) (cons (car es) out))))))

  (define (remove-entry e es)
    (cond ((null? es) '())
          ((eq? (car es) e) (cdr es))
          (else (cons (car es) (remove-entry e (cdr es))))))

  (define c-text-texture
    (foreign-lambda c-pointer "downstroke_text_texture" c-pointer c-pointer c-string
                    int int int int (c-pointer int) (c-pointer int) (c-pointer int)))
  (define c-text-copy
    (foreign-lambda int "downstroke_text_copy" c-pointer c-pointer int int int int))

  (define (copy-text! who rp tex x y w h)
    (when (< (c-text-copy rp tex x y w h) 0)
      (text-error who (sprintf "SDL: ~a" (get-error)))))

  ;; One line of TrueType text at whole pixels (x, y): (values w h) drawn.
  (define (draw-line! who renderer rp fp font c string x y)
    (cond
     ((zero? (string-length string)) (values 0 0))
     ((or (> (abs x) far-text) (> (abs y) far-text)) (text-size font string))
     ((cached-text renderer font string c)
      => (lambda (e)
           (unless (eq? e (car text-cache)) (remember-text! e))
           (copy-text! who rp (text-texture e) x y (text-w e) (text-h e))
           (values (text-w e) (text-h e))))
     (else
      (let-location ((w int 0) (h int 0) (status int 0))
        (let ((tex (c-text-texture rp fp string (car c) (cadr c) (caddr c) (cadddr c)
                                   (location w) (location h) (location status))))
          (case status
            ((-1) (text-error who (sprintf "TTF_RenderUTF8_Blended: ~a" (ttf-get-error))))
            ((-2) (text-error who (sprintf "SDL: ~a" (get-error)))))
          (set! textures-made (+ textures-made 1))
          (if (<= (* w h) text-cache-pixels)
              (begin
                ;; copies of the string and colour: the caller may change its own
                (remember-text! (make-text-entry renderer font (string-copy string) (append c '())
                                                 tex w h))
                (copy-text! who rp tex x y w h))
              (let ((status (c-text-copy rp tex x y w h)))
                (destroy-c-texture! tex)
                (when (< status 0) (text-error who (sprintf "SDL: ~a" (get-error))))))
          (values w h))))))

  (define/keywords (draw-text! renderer font string x y #!key (color '(255 255 255))
                               (width #f) (align 'left))
    (let ((rp (renderer-pointer 'draw-text! renderer))
          (fp (live-font 'draw-text! font))
          (c (color-bytes 'draw-text! color))
          (x (pixel 'draw-text! "x" x))
          (y (pixel 'draw-text! "y" y)))
      (text-string 'draw-text! string)
      (check-layout-options 'draw-text! width align)
      (if (and (not width) (eq? align 'left) (not (has-newline? string)))
          ;; one line, as SDL_ttf draws it: no layout to compute
          (draw-line! 'draw-text! renderer rp fp font c string x y)
          (receive (lines w h) (layout 'draw-text! font string width align 1)
            (for-each (lambda (l)
                        (draw-line! 'draw-text! renderer rp fp font c (car l) (+ x (cadr l)) (+ y (caddr l))))
                      lines)
            (values w h)))))

  ;;; ------------------------------------------------------------------
  ;;; Layout: lines broken at newlines and, given a width, at spaces.

  (define (has-newline? s)
    (let loop ((i 0))
      (and (< i (string-length s))
           (or (char=? (string-ref s i) #\newline) (loop (+ i 1))))))

  (define (check-layout-options who width align)
    (unless (or (not width) (and (exact-integer? width) (> width 0)))
      (error who (sprintf "width: must be a positive integer (pixels) or #f, got ~s" width)))
    (unless (memq align '(left center centre right))
      (error who (sprintf "align: must be left, center or right, got ~s" align))))

  ;; The distance between two lines' tops.
  (define (font-line-skip font)
    ((foreign-lambda int "TTF_FontLineSkip" c-pointer) (live-font 'font-line-skip font)))

  (define (font-height font)
    ((foreign-lambda int "TTF_FontHeight" c-pointer) (live-font 'text-layout font)))

  ;; The paragraphs of s: the pieces between newlines.
  (define (split-lines s)
    (let loop ((i 0) (start 0) (out '()))
      (cond ((= i (string-length s)) (reverse (cons (substring s start i) out)))
            ((char=? (string-ref s i) #\newline) (loop (+ i 1) (+ i 1) (cons (substring s start i) out)))
            (else (loop (+ i 1) start out)))))

  ;; A paragraph as (word . spaces-after) pieces; leading spaces are a
  ;; first piece with an empty word, so they are kept.
  (define (words s)
    (let ((n (string-length s)))
      (define (run i space?)
        (if (and (< i n) (eq? space? (char=? (string-ref s i) #\space))) (run (+ i 1) space?) i))
      (let loop ((i 0) (out '()))
        (if (>= i n)
            (reverse out)
            (let* ((we (run i #f)) (se (run we #t)))
              (loop se (cons (cons (substring s i we) (substring s we se)) out)))))))

  ;; The index just past the character that starts at byte i (UTF-8:
  ;; continuation bytes are 10xxxxxx), so a long word breaks between
  ;; characters, never inside one.
  (define (next-char s i)
    (let loop ((j (+ i 1)))
      (if (and (< j (string-length s))
               (= 2 (quotient (char->integer (string-ref s j)) 64)))
          (loop (+ j 1))
          j)))

  ;; A word too wide for any line: its longest prefixes that fit (at
  ;; least one character each), as lines; answers (values lines rest).
  (define (break-word measure word width)
    (let loop ((word word) (out '()))
      (cond
       ;; the last character alone was too wide: it is the line in progress
       ((and (string=? word "") (pair? out)) (values (reverse (cdr out)) (car out)))
       ((<= (measure word) width) (values (reverse out) word))
       (else
          (let fit ((end (next-char word 0)))
            (let ((next (next-char word end)))
              (if (and (< end (string-length word)) (<= (measure (substring word 0 next)) width))
                  (fit next)
                  (loop (substring word end) (cons (substring word 0 end) out)))))))))

  ;; The lines of one paragraph, greedily filled to width.
  (define (wrap-paragraph measure para width)
    (if (not width)
        (list para)
        (let loop ((ws (words para)) (line #f) (pending "") (out '()))
          ;; line: the text so far (#f: a line not started); pending: the
          ;; spaces after it, kept only when a word follows on this line
          ;; (a paragraph's leading spaces are kept: its first word is "")
          (if (null? ws)
              (reverse (cons (or line "") out))
              (let* ((word (caar ws)) (spaces (cdar ws))
                     (candidate (if (and line (not (string=? line "")))
                                    (string-append line pending word)
                                    word)))
                (cond ((and (not line) (string=? word ""))
                       (loop (cdr ws) spaces "" out))
                      ((<= (measure candidate) width)
                       (loop (cdr ws) candidate spaces out))
                      ((and line (not (string=? line "")))
                       ;; the word goes to a new line, its spaces before dropped
                       (loop ws #f "" (cons line out)))
                      (else
                       (receive (full rest) (break-word measure word width)
                         (loop (cdr ws) rest spaces (append (reverse full) out))))))))))

  ;; (values lines w h) for a font with the given measure and line metrics.
  (define (lay-out measure string width align skip height)
    (let* ((texts (let loop ((ps (split-lines string)) (out '()))
                    (if (null? ps)
                        out
                        (loop (cdr ps) (append out (wrap-paragraph measure (car ps) width))))))
           (widths (map measure texts))
           (box (or width (foldl max 0 widths))))
      (let loop ((ts texts) (ws widths) (y 0) (out '()))
        (if (null? ts)
            (values (reverse out) box (if (null? texts) 0 (+ height (* skip (- (length texts) 1)))))
            (loop (cdr ts) (cdr ws) (+ y skip)
                  (cons (list (car ts)
                              (case align
                                ((left) 0)
                                ((right) (- box (car ws)))
                                (else (quotient (- box (car ws)) 2)))
                              y (car ws))
                        out))))))

  (define (layout who font string width align scale)
    (cond ((font? font)
           (unless (eqv? scale 1)
             (error who "scale: is for sprite fonts; a TrueType font's size is its point size" scale))
           (lay-out (lambda (s) (if (string=? s "") 0 (receive (w h) (text-size font s) w)))
                    string width align (font-line-skip font) (font-height font)))
          ((sprite-font? font)
           (check-scale who scale)
           (let ((gw (* scale (sprite-font-glyph-width font)))
                 (gh (* scale (sprite-font-glyph-height font))))
             (lay-out (lambda (s) (* gw (string-length s))) string width align gh gh)))
          (else (error who "not a font (open-font) or a sprite font (make-sprite-font)" font))))

  (define/keywords (text-layout font string #!key (width #f) (align 'left) (scale 1))
    (text-string 'text-layout string)
    (check-layout-options 'text-layout width align)
    (if (string=? string "")
        (values '() (or width 0) 0)
        (layout 'text-layout font string width align scale)))

  ;;; ------------------------------------------------------------------
  ;;; Sprite fonts

  (define-record-type sprite-font
    (%make-sprite-font texture glyph-width glyph-height first-char columns)
    sprite-font?
    (texture sprite-font-texture)
    (glyph-width sprite-font-glyph-width)
    (glyph-height sprite-font-glyph-height)
    (first-char sprite-font-first-char)
    (columns sprite-font-columns))

  (define (positive-int? v) (and (exact-integer? v) (> v 0)))

  (define/keywords (make-sprite-font texture #!key (glyph-width #f) (glyph-height #f)
                            (first-char #\space) (columns 16))
    (unless (texture? texture) (error 'make-sprite-font "not a texture" texture))
    (unless (positive-int? glyph-width)
      (error 'make-sprite-font "glyph-width: must be a positive integer" glyph-width))
    (unless (positive-int? glyph-height)
      (error 'make-sprite-font "glyph-height: must be a positive integer" glyph-height))
    (unless (char? first-char) (error 'make-sprite-font "first-char: must be a character" first-char))
    (unless (positive-int? columns)
      (error 'make-sprite-font "columns: must be a positive integer" columns))
    (%make-sprite-font texture glyph-width glyph-height first-char columns))

  ;; Walk the text: (emit! index col line) for each non-newline character,
  ;; index its cell index (may be out of the sheet); answers (values cols lines)
  ;; with cols the widest line's length.
  (define (walk-text string emit!)
    (let ((n (string-length string)))
      (let loop ((i 0) (col 0) (line 0) (widest 0))
        (if (= i n)
            (values (max widest col) (if (zero? n) 0 (+ line 1)))
            (let ((c (string-ref string i)))
              (if (char=? c #\newline)
                  (loop (+ i 1) 0 (+ line 1) (max widest col))
                  (begin (emit! c col line)
                         (loop (+ i 1) (+ col 1) line widest))))))))

  (define (check-scale who scale)
    (unless (positive-int? scale) (error who "scale: must be a positive integer" scale)))

  (define/keywords (sprite-text-size sf string #!key (scale 1))
    (check-scale 'sprite-text-size scale)
    (text-string 'sprite-text-size string)
    (receive (cols lines) (walk-text string void)
      (values (* cols (sprite-font-glyph-width sf) scale)
              (* lines (sprite-font-glyph-height sf) scale))))

  (define/keywords (draw-sprite-text! renderer sf string x y #!key (scale 1) (width #f) (align 'left))
    (check-scale 'draw-sprite-text! scale)
    (text-string 'draw-sprite-text! string)
    (check-layout-options 'draw-sprite-text! width align)
    (let ((x0 (pixel 'draw-sprite-text! "x" x))
          (y0 (pixel 'draw-sprite-text! "y" y)))
      (if (and (not width) (eq? align 'left))
          (draw-sprite-lines! renderer sf string x0 y0 scale)
          (receive (lines w h) (if (string=? string "")
                                   (values '() (or width 0) 0)
                                   (layout 'draw-sprite-text! sf string width align scale))
            (for-each (lambda (l)
                        (draw-sprite-lines! renderer sf (car l) (+ x0 (cadr l)) (+ y0 (caddr l)) scale))
                      lines)
            (values w h)))))

  (define (draw-sprite-lines! renderer sf string x0 y0 scale)
    (let* ((tex (sprite-font-texture sf))
           (gw (sprite-font-glyph-width sf))
           (gh (sprite-font-glyph-height sf))
           (columns (sprite-font-columns sf))
           (first (char->integer (sprite-font-first-char sf))))
      (receive (tw th) (texture-size tex)
        (let ((sheet-cols (min columns (quotient tw gw)))
              (sheet-rows (quotient th gh)))
          (receive (cols lines)
              (walk-text
               string
               (lambda (c col line)
                 (let* ((index (- (char->integer c) first))
                        (sc (and (>= index 0) (modulo index columns)))
                        (sr (and (>= index 0) (quotient index columns))))
                   (when (and sc (< sc sheet-cols) (< sr sheet-rows))
                     (render-copy! renderer tex
                                   (make-rect (* sc gw) (* sr gh) gw gh)
                                   (make-rect (+ x0 (* col gw scale)) (+ y0 (* line gh scale))
                                              (* gw scale) (* gh scale)))))))
            (values (* cols gw scale) (* lines gh scale))))))))

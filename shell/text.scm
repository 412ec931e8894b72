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
;;; surface, makes a texture of it, copies it and frees both the texture and
;;; the surface before it returns, so drawing text every frame holds on to
;;; nothing. The empty string draws nothing. A newline is not a line break
;;; (SDL_ttf draws one line).
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
   draw-text! text-size
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

/* Render, make a texture, copy it to (x, y), free both. Answers 0, or -1
   for a TTF failure, -2 for an SDL failure (the error in SDL_GetError).
   The size drawn goes to *w and *h. */
static int downstroke_draw_text(SDL_Renderer *r, TTF_Font *font, const char *s,
                                int x, int y, int cr, int cg, int cb, int ca,
                                int *w, int *h) {
  SDL_Color c;
  SDL_Surface *surf;
  SDL_Texture *tex;
  SDL_Rect dst;
  int status;
  c.r = (Uint8)cr; c.g = (Uint8)cg; c.b = (Uint8)cb; c.a = (Uint8)ca;
  surf = TTF_RenderUTF8_Blended(font, s, c);
  if (!surf) return -1;
  tex = SDL_CreateTextureFromSurface(r, surf);
  if (!tex) { SDL_FreeSurface(surf); return -2; }
  dst.x = x; dst.y = y; dst.w = surf->w; dst.h = surf->h;
  *w = surf->w; *h = surf->h;
  SDL_SetTextureBlendMode(tex, SDL_BLENDMODE_BLEND);
  status = SDL_RenderCopy(r, tex, NULL, &dst);
  SDL_DestroyTexture(tex);
  SDL_FreeSurface(surf);
  return status < 0 ? -2 : 0;
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

  (define c-draw-text
    (foreign-lambda int "downstroke_draw_text" c-pointer c-pointer c-string
                    int int int int int int (c-pointer int) (c-pointer int)))

  (define/keywords (draw-text! renderer font string x y #!key (color '(255 255 255)))
    (let ((rp (renderer-pointer 'draw-text! renderer))
          (fp (live-font 'draw-text! font))
          (c (color-bytes 'draw-text! color))
          (x (pixel 'draw-text! "x" x))
          (y (pixel 'draw-text! "y" y)))
      (text-string 'draw-text! string)
      (cond
       ((zero? (string-length string)) (values 0 0))
       ((or (> (abs x) far-text) (> (abs y) far-text)) (text-size font string))
       (else
          (let-location ((w int 0) (h int 0))
            (let ((status (c-draw-text rp fp string x y
                                       (car c) (cadr c) (caddr c) (cadddr c)
                                       (location w) (location h))))
              (case status
                ((-1) (text-error 'draw-text! (sprintf "TTF_RenderUTF8_Blended: ~a" (ttf-get-error))))
                ((-2) (text-error 'draw-text! (sprintf "SDL: ~a" (get-error))))
                (else (values w h)))))))))

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

  (define/keywords (draw-sprite-text! renderer sf string x y #!key (scale 1))
    (check-scale 'draw-sprite-text! scale)
    (text-string 'draw-sprite-text! string)
    (let* ((tex (sprite-font-texture sf))
           (gw (sprite-font-glyph-width sf))
           (gh (sprite-font-glyph-height sf))
           (columns (sprite-font-columns sf))
           (first (char->integer (sprite-font-first-char sf)))
           (x0 (pixel 'draw-sprite-text! "x" x))
           (y0 (pixel 'draw-sprite-text! "y" y)))
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

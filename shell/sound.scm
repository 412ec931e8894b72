;;; (downstroke sound): sound effects and music through SDL2_mixer
;;; (Debian's libsdl2-mixer-dev), bound with CHICKEN's FFI.
;;;
;;; Only what the library uses is bound. The usual order is
;;;   (init-audio!)
;;;   (load-sounds! '((jump . "jump.wav") (coin . "coin.wav")))
;;;   (load-music! "theme.ogg")
;;;   (play-music! volume: 0.5)
;;;   (play-sound 'jump)
;;;   ...
;;;   (shutdown-audio!)
;;;
;;; Registry. Sounds live in one registry, by name (any value compared
;;; with equal?, usually a symbol). Loading a name again replaces its sound
;;; and frees the old one. There is one current music; load-music! replaces
;;; it (halting and freeing the old one).
;;;
;;; Resources. Every Mix_Chunk and Mix_Music is freed exactly once: when it
;;; is replaced, or by shutdown-audio!, which frees everything and closes
;;; the device; it may be called any number of times. A finalizer on each
;;; chunk or music record is a backstop and does nothing for one already
;;; freed. Call shutdown-audio! before (downstroke sdl2)'s quit!.
;;;
;;; Volumes are numbers from 0.0 (silent) to 1.0 (full), mapped to
;;; SDL_mixer's 0..128 by rounding v * 128; values outside the range are
;;; clamped; anything that is not a real number is an error. The sound
;;; volume applies to every channel; it is remembered and applied again by
;;; init-audio!.
;;;
;;; Music loops: -1 (the default) plays forever, n >= 1 plays n times
;;; (SDL_mixer's meaning of the count).
;;;
;;; Errors. A failing call raises a CHICKEN error (kinds exn and sound)
;;; whose message names the SDL_mixer call, the file when there is one,
;;; and Mix_GetError's text:
;;;   Mix_LoadWAV: cannot load "x.wav": Couldn't open x.wav
;;; Playing a sound name that was never loaded is an error naming it.
;;; Loading or playing before init-audio! is an error.

(module (downstroke sound)
  (init-audio! shutdown-audio! audio-open?
   load-sounds! sound-loaded? sound-names play-sound sound-playing?
   load-music! play-music! stop-music! music-loaded? music-playing?
   sound-volume-set! music-volume-set! sound-volume music-volume
   volume->mixer sound-resource-counts max-sound-file-size)

  (import (downstroke keywords) (downstroke media-header))
  (import scheme (chicken base) (chicken foreign) (chicken condition)
          (chicken gc) (chicken format) (only (chicken file posix) file-size))

  (foreign-declare #<<EOF
#include <SDL.h>
#include <SDL_mixer.h>
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

/* While SDL looks for a device, alsa-lib writes its own complaints to
   stderr (eight lines on a machine without a sound card); the reason
   reaches the game through SDL's error text anyway. stderr goes to
   /dev/null for the open and comes back after it; DOWNSTROKE_AUDIO_DEBUG
   keeps it. Answers the saved descriptor, or -1 when nothing was moved. */
static int ds_mute_stderr(void) {
  int saved, null;
  if (getenv("DOWNSTROKE_AUDIO_DEBUG")) return -1;
  fflush(stderr);
  saved = dup(2);
  if (saved < 0) return -1;
  null = open("/dev/null", O_WRONLY);
  if (null < 0) { close(saved); return -1; }
  dup2(null, 2);
  close(null);
  return saved;
}

static void ds_restore_stderr(int saved) {
  if (saved < 0) return;
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
}

/* SDL's audio subsystem and SDL_mixer's device, opened with stderr muted:
   0 on success, 1 when SDL_InitSubSystem failed, 2 when Mix_OpenAudio did
   (the subsystem is closed again then). */
static int ds_open_audio(int frequency, int channels, int chunk) {
  int saved = ds_mute_stderr(), r = 0;
  if (SDL_InitSubSystem(SDL_INIT_AUDIO) < 0) r = 1;
  else if (Mix_OpenAudio(frequency, MIX_DEFAULT_FORMAT, channels, chunk) < 0) r = 2;
  ds_restore_stderr(saved);
  return r;
}
EOF
)

  ;;; ------------------------------------------------------------------
  ;;; Errors

  (define mix-get-error (foreign-lambda c-string "Mix_GetError"))

  (define (sound-error who message)
    (signal
     (make-composite-condition
      (make-property-condition 'exn 'location who 'message message
                               'arguments '())
      (make-property-condition 'sound))))

  (define (mix-error who call #!optional path)
    (sound-error who
                 (if path
                     (sprintf "~a: cannot load ~s: ~a" call path (mix-get-error))
                     (sprintf "~a: ~a" call (mix-get-error)))))

  ;;; ------------------------------------------------------------------
  ;;; Device

  (define opened? #f)
  (define (audio-open?) opened?)

  (define (check-open who)
    (unless opened?
      (sound-error who (sprintf "~a: audio is not initialised (call init-audio! first)"
                                who))))

  ;; Counts of native chunks and musics loaded and freed (tests, leak checks).
  (define loaded-count 0)
  (define freed-count 0)
  (define (sound-resource-counts) (values loaded-count freed-count))

  (define (check-positive who what v)
    (unless (and (exact-integer? v) (> v 0))
      (error who (sprintf "~a must be an exact integer > 0, got ~s" what v) v)))

  ;; Opening twice is allowed and does nothing; shut down first to change
  ;; the format.
  (define/keywords (init-audio! #!key (frequency 44100) (channels 2) (chunk-size 1024))
    (check-positive 'init-audio! "frequency:" frequency)
    (check-positive 'init-audio! "channels:" channels)
    (check-positive 'init-audio! "chunk-size:" chunk-size)
    (unless opened?
      (case ((foreign-lambda int "ds_open_audio" int int int) frequency channels chunk-size)
        ((1) (sound-error 'init-audio!
                          (sprintf "SDL_InitSubSystem(SDL_INIT_AUDIO): ~a" (mix-get-error))))
        ((2) (let ((text (mix-get-error)))
               ((foreign-lambda void "SDL_QuitSubSystem" unsigned-int)
                (foreign-value "SDL_INIT_AUDIO" unsigned-int))
               (sound-error 'init-audio! (sprintf "Mix_OpenAudio: ~a" text)))))
      (set! opened? #t)
      (apply-sound-volume!))
    (void))

  ;;; ------------------------------------------------------------------
  ;;; Native resources: a record around the pointer, #f once freed.

  (define-record-type chunk
    (%make-chunk ptr path)
    chunk?
    (ptr chunk-ptr chunk-ptr-set!)
    (path chunk-path))

  (define-record-type music
    (%make-music ptr path)
    music?
    (ptr music-ptr music-ptr-set!)
    (path music-path))

  (define (free-chunk! c)
    (let ((p (chunk-ptr c)))
      (when p
        (chunk-ptr-set! c #f)
        (set! freed-count (+ freed-count 1))
        ;; SDL_mixer halts any channel still playing it.
        ((foreign-lambda void "Mix_FreeChunk" c-pointer) p))))

  (define (free-music! m)
    (let ((p (music-ptr m)))
      (when p
        (music-ptr-set! m #f)
        (set! freed-count (+ freed-count 1))
        ;; SDL_mixer halts it first when it is the music playing.
        ((foreign-lambda void "Mix_FreeMusic" c-pointer) p))))

  ;; The largest sound or music file loaded: 128 MB (SDL_mixer decodes a
  ;; sound whole, and a 128 MB WAV is over ten minutes of CD audio).
  (define max-sound-file-size (make-parameter (* 128 1024 1024)))

  ;; Before SDL_mixer sees a file: a regular file, not too large, and no
  ;; WAV header that SDL would divide by zero with.
  (define (check-sound-file who path)
    (let ((why (file-problem path)))
      (cond ((equal? why "not found") #f)           ; SDL says so itself
            (why (error who (sprintf "~s ~a" path why)))
            (else (check-sound-contents who path)))))

  (define (check-sound-contents who path)
    (cond ((> (file-size path) (max-sound-file-size))
           (error who (sprintf "~s is ~a bytes: more than the limit of ~a (max-sound-file-size)"
                               path (file-size path) (max-sound-file-size))))
          ((wav-file-problem path)
           => (lambda (why) (error who (sprintf "~s is not a WAV file SDL_mixer can play: ~a" path why))))))

  (define (load-chunk who path)
    (unless (string? path)
      (error who "sound file must be a string" path))
    (check-sound-file who path)
    ;; Opening the file ourselves keeps SDL's reason ("Couldn't open ...");
    ;; Mix_LoadWAV would replace it with a message about a NULL source.
    (let* ((rw ((foreign-lambda c-pointer "SDL_RWFromFile" c-string c-string) path "rb"))
           (p (and rw ((foreign-lambda c-pointer "Mix_LoadWAV_RW" c-pointer int) rw 1))))
      (unless p (mix-error who "Mix_LoadWAV" path))
      (set! loaded-count (+ loaded-count 1))
      (set-finalizer! (%make-chunk p path) free-chunk!)))

  (define (load-music who path)
    (unless (string? path)
      (error who "music file must be a string" path))
    (check-sound-file who path)
    (let ((p ((foreign-lambda c-pointer "Mix_LoadMUS" c-string) path)))
      (unless p (mix-error who "Mix_LoadMUS" path))
      (set! loaded-count (+ loaded-count 1))
      (set-finalizer! (%make-music p path) free-music!)))

  ;;; ------------------------------------------------------------------
  ;;; Sounds

  ;; name -> chunk, an alist (a game has a handful of sounds).
  (define sounds '())

  (define (sound-names) (map car sounds))
  (define (sound-loaded? name) (and (assoc name sounds) #t))

  ;; specs: ((name . "file.wav") ...). Every file is loaded before any is
  ;; registered, so a bad file leaves the registry as it was (the ones
  ;; loaded before it are freed).
  (define (load-sounds! specs)
    (check-open 'load-sounds!)
    (unless (list? specs)
      (error 'load-sounds! "expected a list of (name . \"file.wav\") pairs" specs))
    (for-each (lambda (s)
                (unless (and (pair? s) (string? (cdr s)))
                  (error 'load-sounds! "expected (name . \"file.wav\")" s)))
              specs)
    (let loop ((rest specs) (loaded '()))
      (if (null? rest)
          (for-each (lambda (entry)
                      (let ((old (assoc (car entry) sounds)))
                        (if old
                            (let ((c (cdr old)))
                              (set-cdr! old (cdr entry))
                              (free-chunk! c))
                            (set! sounds (cons entry sounds)))))
                    (reverse loaded))
          (let ((c (handle-exceptions exn
                       (begin (for-each (lambda (e) (free-chunk! (cdr e))) loaded)
                              (signal exn))
                     (load-chunk 'load-sounds! (cdar rest)))))
            (loop (cdr rest) (cons (cons (caar rest) c) loaded)))))
    (void))

  ;; Plays on the first free channel and answers its number, or #f when
  ;; every channel is busy (the sound is dropped, as games expect).
  (define (play-sound name)
    ;; closed audio first: with it the registry is empty, and "no sound
    ;; named" would hide the real cause
    (check-open 'play-sound)
    (let ((entry (assoc name sounds)))
      (unless entry
        (error 'play-sound (sprintf "no sound named ~s (loaded: ~s)" name (sound-names))
               name))
      (let ((ch ((foreign-lambda int "Mix_PlayChannel" int c-pointer int)
                 -1 (chunk-ptr (cdr entry)) 0)))
        (and (>= ch 0) ch))))

  (define (sound-playing? channel)
    (and opened?
         (not (zero? ((foreign-lambda int "Mix_Playing" int) channel)))))

  ;;; ------------------------------------------------------------------
  ;;; Music

  (define current-music #f)

  (define (music-loaded?) (and current-music #t))

  (define (load-music! path)
    (check-open 'load-music!)
    (let ((m (load-music 'load-music! path)))
      (when current-music (free-music! current-music))
      (set! current-music m))
    (void))

  (define/keywords (play-music! #!key (volume 1.0) (loops -1))
    (check-open 'play-music!)
    (unless current-music
      (error 'play-music! "no music loaded (call load-music! first)"))
    (unless (and (exact-integer? loops) (or (= loops -1) (>= loops 0)))
      (error 'play-music! "loops: must be -1 (forever) or an exact integer >= 0" loops))
    (music-volume-set! volume)
    (when (< ((foreign-lambda int "Mix_PlayMusic" c-pointer int)
              (music-ptr current-music) loops)
             0)
      (mix-error 'play-music! "Mix_PlayMusic"))
    (void))

  (define (stop-music!)
    (when opened? ((foreign-lambda int "Mix_HaltMusic")))
    (void))

  (define (music-playing?)
    (and opened? (not (zero? ((foreign-lambda int "Mix_PlayingMusic"))))))

  ;;; ------------------------------------------------------------------
  ;;; Volumes

  (define (%volume->mixer who v)
    (unless (real? v)
      (error who "volume must be a number from 0.0 to 1.0" v))
    (let ((v (cond ((nan? v) 0) ((< v 0) 0) ((> v 1) 1) (else v))))
      (inexact->exact (round (* v 128)))))

  ;; The mapping, exported for games that show a volume setting.
  (define (volume->mixer v) (%volume->mixer 'volume->mixer v))

  (define sound-level 128)

  (define (apply-sound-volume!)
    (when opened?
      ((foreign-lambda int "Mix_Volume" int int) -1 sound-level)))

  (define (sound-volume-set! v)
    (set! sound-level (%volume->mixer 'sound-volume-set! v))
    (apply-sound-volume!)
    (void))

  (define (music-volume-set! v)
    ((foreign-lambda int "Mix_VolumeMusic" int) (%volume->mixer 'music-volume-set! v))
    (void))

  ;; The volumes as SDL_mixer holds them, 0..128.
  (define (sound-volume)
    (if opened?
        ((foreign-lambda int "Mix_Volume" int int) -1 -1)
        sound-level))

  (define (music-volume)
    ((foreign-lambda int "Mix_VolumeMusic" int) -1))

  ;;; ------------------------------------------------------------------
  ;;; Shutdown

  (define (shutdown-audio!)
    (when opened?
      ((foreign-lambda int "Mix_HaltChannel" int) -1)
      ((foreign-lambda int "Mix_HaltMusic")))
    (for-each (lambda (e) (free-chunk! (cdr e))) sounds)
    (set! sounds '())
    (when current-music
      (free-music! current-music)
      (set! current-music #f))
    (when opened?
      (set! opened? #f)
      ((foreign-lambda void "Mix_CloseAudio"))
      ((foreign-lambda void "SDL_QuitSubSystem" unsigned-int)
       (foreign-value "SDL_INIT_AUDIO" unsigned-int)))
    (void)))

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
;;; Volume groups. Every sound belongs to a group, a symbol: effects
;;; unless load-sounds! is given group:; the music is the group music. A
;;; group's volume (group-volume-set! group v, 1.0 until set, for any
;;; symbol, so a game adds groups by naming them) multiplies the volume of
;;; everything in it, playing now or later:
;;;   a sound's channel: sound volume x its group's x play-sound's volume:
;;;   the music:         music volume x the music group's.
;;;
;;; Channels. init-audio! allocates sound-channels: channels (32 unless
;;; given; SDL_mixer alone gives 8), so that many sounds play at once;
;;; (sound-channels-set! n) changes it while the device is open.
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
   group-volume-set! group-volume sound-group sound-channels sound-channels-set! channel-volume
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
  (define default-sound-channels 32)

  (define/keywords (init-audio! #!key (frequency 44100) (channels 2) (chunk-size 1024)
                                (sound-channels default-sound-channels))
    (check-positive 'init-audio! "frequency:" frequency)
    (check-positive 'init-audio! "channels:" channels)
    (check-positive 'init-audio! "chunk-size:" chunk-size)
    (check-positive 'init-audio! "sound-channels:" sound-channels)
    (unless opened?
      (case ((foreign-lambda int "ds_open_audio" int int int) frequency channels chunk-size)
        ((1) (sound-error 'init-audio!
                          (sprintf "SDL_InitSubSystem(SDL_INIT_AUDIO): ~a" (mix-get-error))))
        ((2) (let ((text (mix-get-error)))
               ((foreign-lambda void "SDL_QuitSubSystem" unsigned-int)
                (foreign-value "SDL_INIT_AUDIO" unsigned-int))
               (sound-error 'init-audio! (sprintf "Mix_OpenAudio: ~a" text)))))
      (set! opened? #t)
      (allocate-channels! sound-channels)
      (apply-sound-volume!))
    (void))

  ;; Each channel's group and play-sound volume, for the volumes applied
  ;; when a group's or the sound volume changes: a vector of (group . v).
  (define channel-groups (make-vector 0 #f))

  (define (allocate-channels! n)
    ((foreign-lambda int "Mix_AllocateChannels" int) n)
    (let ((v (make-vector n #f)))
      (do ((i 0 (+ i 1))) ((= i (min n (vector-length channel-groups))))
        (vector-set! v i (vector-ref channel-groups i)))
      (set! channel-groups v)))

  (define (sound-channels)
    (if opened? ((foreign-lambda int "Mix_AllocateChannels" int) -1) 0))

  ;; Fewer channels stop the sounds on those taken away.
  (define (sound-channels-set! n)
    (check-positive 'sound-channels-set! "the channel count" n)
    (check-open 'sound-channels-set!)
    (allocate-channels! n)
    (apply-sound-volume!)
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

  ;; name -> group, for the sounds not in effects.
  (define groups '())
  (define (sound-group name)
    (unless (assoc name sounds)
      (error 'sound-group (sprintf "no sound named ~s (loaded: ~s)" name (sound-names)) name))
    (let ((g (assoc name groups))) (if g (cdr g) 'effects)))

  ;; specs: ((name . "file.wav") ...). Every file is loaded before any is
  ;; registered, so a bad file leaves the registry as it was (the ones
  ;; loaded before it are freed).
  (define/keywords (load-sounds! specs #!key (group 'effects))
    (unless (symbol? group)
      (error 'load-sounds! "group: must be a symbol (effects, or a group of the game's)" group))
    (load-sound-files! specs)
    (for-each (lambda (s)
                (set! groups (cons (cons (car s) group)
                                   (let drop ((gs groups))
                                     (cond ((null? gs) '())
                                           ((equal? (caar gs) (car s)) (drop (cdr gs)))
                                           (else (cons (car gs) (drop (cdr gs)))))))))
              specs))

  (define (load-sound-files! specs)
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
  (define/keywords (play-sound name #!key (volume 1.0))
    ;; closed audio first: with it the registry is empty, and "no sound
    ;; named" would hide the real cause
    (check-open 'play-sound)
    (let ((entry (assoc name sounds))
          (v (clamp-volume 'play-sound volume)))
      (unless entry
        (error 'play-sound (sprintf "no sound named ~s (loaded: ~s)" name (sound-names))
               name))
      ;; the channel's volume is set before it starts, so no sample plays
      ;; at the volume of the sound before it
      (let ((ch ((foreign-lambda int "Mix_GroupAvailable" int) -1)))
        (and (>= ch 0)
             (let ((ch (begin
                         (vector-set! channel-groups ch (cons (sound-group name) v))
                         (apply-channel-volume! ch)
                         ((foreign-lambda int "Mix_PlayChannel" int c-pointer int)
                          ch (chunk-ptr (cdr entry)) 0))))
               (and (>= ch 0) ch))))))

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

  ;; A volume as given, clamped to 0..1 (NaN is silence).
  (define (clamp-volume who v)
    (unless (real? v)
      (error who "volume must be a number from 0.0 to 1.0" v))
    (cond ((nan? v) 0) ((< v 0) 0) ((> v 1) 1) (else v)))

  (define (%volume->mixer who v)
    (inexact->exact (round (* (clamp-volume who v) 128))))

  ;; The mapping, exported for games that show a volume setting.
  (define (volume->mixer v) (%volume->mixer 'volume->mixer v))

  (define sound-level 128)
  (define music-level 1)

  ;; group -> volume 0..1, for the groups given one.
  (define group-volumes '())

  (define (group-volume group)
    (unless (symbol? group) (error 'group-volume "a volume group is a symbol" group))
    (let ((g (assq group group-volumes))) (if g (cdr g) 1.0)))

  (define (group-volume-set! group v)
    (unless (symbol? group)
      (error 'group-volume-set! "a volume group is a symbol (music, effects, or one of the game's)" group))
    (let ((v (clamp-volume 'group-volume-set! v)))
      (set! group-volumes (cons (cons group v) (let drop ((gs group-volumes))
                                                 (cond ((null? gs) '())
                                                       ((eq? (caar gs) group) (drop (cdr gs)))
                                                       (else (cons (car gs) (drop (cdr gs)))))))))
    (apply-sound-volume!)
    (apply-music-volume!)
    (void))

  (define mix-volume (foreign-lambda int "Mix_Volume" int int))

  ;; A channel's volume: the sound volume times its sound's group's and
  ;; the volume play-sound gave it.
  (define (apply-channel-volume! ch)
    (let ((g (vector-ref channel-groups ch)))
      (mix-volume ch (if g
                         (inexact->exact (round (* sound-level (group-volume (car g)) (cdr g))))
                         sound-level))))

  (define (apply-sound-volume!)
    (when opened?
      (do ((ch 0 (+ ch 1))) ((= ch (vector-length channel-groups)))
        (apply-channel-volume! ch))))

  ;; SDL_mixer's volume of one channel, 0..128.
  (define (channel-volume ch)
    (check-open 'channel-volume)
    (unless (and (exact-integer? ch) (<= 0 ch) (< ch (vector-length channel-groups)))
      (error 'channel-volume (sprintf "no channel ~s (channels 0 to ~a)" ch (- (vector-length channel-groups) 1))))
    (mix-volume ch -1))

  (define (sound-volume-set! v)
    (set! sound-level (%volume->mixer 'sound-volume-set! v))
    (apply-sound-volume!)
    (void))

  (define (apply-music-volume!)
    ((foreign-lambda int "Mix_VolumeMusic" int)
     (inexact->exact (round (* 128 music-level (group-volume 'music))))))

  (define (music-volume-set! v)
    (set! music-level (clamp-volume 'music-volume-set! v))
    (apply-music-volume!)
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
    (set! groups '())
    (set! channel-groups (make-vector 0 #f))
    (when current-music
      (free-music! current-music)
      (set! current-music #f))
    (when opened?
      (set! opened? #f)
      ((foreign-lambda void "Mix_CloseAudio"))
      ((foreign-lambda void "SDL_QuitSubSystem" unsigned-int)
       (foreign-value "SDL_INIT_AUDIO" unsigned-int)))
    (void)))

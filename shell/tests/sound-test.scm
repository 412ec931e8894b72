(import (downstroke test) (downstroke sound)
        scheme (chicken base) (chicken string) (chicken file) (chicken io)
        (chicken condition) (chicken bitwise) (chicken gc) srfi-4)

;;; Helpers (prefixed snd- because every suite is loaded into one toplevel).
;;; Runs on SDL's dummy audio driver (SDL_AUDIODRIVER=dummy).

(define (snd-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

;; Little-endian bytes of n into v at i.
(define (snd-put! v i n size)
  (do ((k 0 (+ k 1))) ((= k size))
    (u8vector-set! v (+ i k) (bitwise-and (arithmetic-shift n (* -8 k)) 255))))

(define (snd-put-tag! v i tag)
  (do ((k 0 (+ k 1))) ((= k 4))
    (u8vector-set! v (+ i k) (char->integer (string-ref tag k)))))

;; A mono 16-bit PCM WAV file: `samples` samples of a 440 Hz sine.
(define (snd-write-wav! path #!key (rate 22050) (samples 2205))
  (let* ((data-size (* 2 samples))
         (v (make-u8vector (+ 44 data-size) 0)))
    (snd-put-tag! v 0 "RIFF")
    (snd-put! v 4 (+ 36 data-size) 4)
    (snd-put-tag! v 8 "WAVE")
    (snd-put-tag! v 12 "fmt ")
    (snd-put! v 16 16 4)              ; fmt chunk size
    (snd-put! v 20 1 2)               ; PCM
    (snd-put! v 22 1 2)               ; mono
    (snd-put! v 24 rate 4)
    (snd-put! v 28 (* rate 2) 4)      ; byte rate
    (snd-put! v 32 2 2)               ; block align
    (snd-put! v 34 16 2)              ; bits per sample
    (snd-put-tag! v 36 "data")
    (snd-put! v 40 data-size 4)
    (do ((i 0 (+ i 1))) ((= i samples))
      (let* ((s (inexact->exact
                 (round (* 12000 (sin (/ (* 2 3.141592653589793 440 i) rate))))))
             (u (if (< s 0) (+ s 65536) s)))
        (snd-put! v (+ 44 (* 2 i)) u 2)))
    (call-with-output-file path
      (lambda (port) (write-u8vector v port))
      #:binary)
    path))

(define snd-wav (snd-write-wav! (create-temporary-file ".wav")))
(define snd-wav2 (snd-write-wav! (create-temporary-file ".wav") samples: 4410))
(define snd-garbage
  (let ((p (create-temporary-file ".wav")))
    (call-with-output-file p (lambda (port) (write-string "this is not a sound file" #f port)))
    p))
(define snd-missing "/tmp/downstroke-no-such-dir/missing-sound.wav")

(define (snd-live)
  (receive (loaded freed) (sound-resource-counts) (- loaded freed)))

(test-group "sound"
  (test-group "before init-audio!"
    (shutdown-audio!)
    (test "not open" #f (audio-open?))
    (test-error "load-sounds! needs init-audio!" (snd-says? "init-audio!")
                (load-sounds! `((beep . ,snd-wav))))
    (test-error "load-music! needs init-audio!" (snd-says? "init-audio!")
                (load-music! snd-wav))
    (test-error "play-sound needs init-audio! (said first, not \"no sound named\")"
                (snd-says? "init-audio!")
                (play-sound 'nope)))

  (test-group "volume mapping"
    (test "0.0 -> 0" 0 (volume->mixer 0.0))
    (test "1.0 -> 128" 128 (volume->mixer 1.0))
    (test "0.5 -> 64" 64 (volume->mixer 0.5))
    (test "0.25 -> 32" 32 (volume->mixer 0.25))
    (test "exact 1 -> 128" 128 (volume->mixer 1))
    (test "0.3 rounds to 38" 38 (volume->mixer 0.3))
    (test "above 1 clamps" 128 (volume->mixer 7.5))
    (test "below 0 clamps" 0 (volume->mixer -0.5))
    (test-assert "result is exact" (exact? (volume->mixer 0.7)))
    (test-error "a string is an error" (snd-says? "volume" "\"loud\"")
                (volume->mixer "loud"))
    (test-error "sound-volume-set! rejects a symbol" (snd-says? "volume")
                (sound-volume-set! 'max))
    (test-error "music-volume-set! rejects #f" (snd-says? "volume")
                (music-volume-set! #f)))

  (test-group "init"
    (test-error "bad frequency" (snd-says? "frequency") (init-audio! frequency: 0))
    (init-audio!)
    (test "open on the dummy driver" #t (audio-open?))
    (init-audio!)
    (test "a second init-audio! is harmless" #t (audio-open?)))

  (test-group "sounds"
    (load-sounds! `((beep . ,snd-wav) (long . ,snd-wav2)))
    (test-assert "beep loaded" (sound-loaded? 'beep))
    (test-assert "long loaded" (sound-loaded? 'long))
    (test "two live chunks" 2 (snd-live))
    (let ((ch (play-sound 'beep)))
      (test-assert "play-sound answers a channel" (and (exact-integer? ch) (>= ch 0)))
      (test-assert "the channel is playing" (sound-playing? ch)))
    (let ((ch (play-sound 'long)))
      (test-assert "a second sound on another channel"
                   (and (exact-integer? ch) (sound-playing? ch))))
    (test-error "unknown sound name is named" (snd-says? "no sound named" "boom")
                (play-sound 'boom))
    (test-error "missing file: error names the path and Mix_GetError's text"
                (snd-says? "Mix_LoadWAV" snd-missing "Couldn't open")
                (load-sounds! `((gone . ,snd-missing))))
    (test-error "unreadable file: error names the path"
                (snd-says? "Mix_LoadWAV" snd-garbage)
                (load-sounds! `((junk . ,snd-garbage))))
    (test-error "a batch with one bad file" (snd-says? snd-missing)
                (load-sounds! `((extra . ,snd-wav) (gone . ,snd-missing))))
    (test "a failed batch registers nothing" #f (sound-loaded? 'extra))
    (test "a failed batch leaks nothing" 2 (snd-live))
    (test-error "malformed spec" (snd-says? "beep")
                (load-sounds! '((beep . 42))))
    ;; Reloading a name frees the chunk it replaces.
    (receive (loaded0 freed0) (sound-resource-counts)
      (load-sounds! `((beep . ,snd-wav2)))
      (receive (loaded1 freed1) (sound-resource-counts)
        (test "replacement loads one" 1 (- loaded1 loaded0))
        (test "replacement frees one" 1 (- freed1 freed0))))
    (test-assert "the replaced sound plays" (play-sound 'beep))
    (test "still two names" 2 (length (sound-names))))

  (test-group "sound volume"
    (sound-volume-set! 0.25)
    (test "0.25 -> 32 on every channel" 32 (sound-volume))
    (sound-volume-set! 3)
    (test "clamped to 128" 128 (sound-volume))
    (sound-volume-set! -1)
    (test "clamped to 0" 0 (sound-volume))
    (sound-volume-set! 1.0))

  ;; SDL_mixer alone gives 8 channels: a ninth coin would be dropped.
  (test-group "channels: more than 8 sounds at once"
    (test "32 channels by default" 32 (sound-channels))
    (let ((chs (let loop ((i 0) (out '())) (if (= i 20) (reverse out) (loop (+ i 1) (cons (play-sound 'long) out))))))
      (test "20 sounds started together each get a channel of their own" 20
            (length (let dedupe ((l chs) (out '()))
                      (cond ((null? l) out)
                            ((or (not (car l)) (memv (car l) out)) (dedupe (cdr l) out))
                            (else (dedupe (cdr l) (cons (car l) out))))))))
    (sound-channels-set! 48)
    (test "sound-channels-set! changes the count" 48 (sound-channels))
    (test-error "a count of 0 is an error" (sound-channels-set! 0))
    (sound-channels-set! 32))

  ;; A channel's volume is sound volume x its group's x play-sound's.
  (test-group "volume groups"
    (load-sounds! `((click . ,snd-wav)) group: 'ui)
    (test "a sound's group: effects unless load-sounds! says" '(effects ui)
          (list (sound-group 'beep) (sound-group 'click)))
    (test "every group is at 1.0 until set, a game's own too" '(1.0 1.0 1.0)
          (map group-volume '(effects music ui)))
    (let ((beep (play-sound 'long))
          (click (play-sound 'click))
          (soft (play-sound 'long volume: 0.5)))
      (test "full volume before any group is turned down" '(128 128 64)
            (map channel-volume (list beep click soft)))
      (group-volume-set! 'effects 0.5)
      (test "effects at 0.5: its playing sounds follow, the ui group does not" '(64 128 32)
            (map channel-volume (list beep click soft)))
      (test "a sound played later gets its group's volume" 64 (channel-volume (play-sound 'beep)))
      (sound-volume-set! 0.5)
      (test "the sound volume multiplies every group" '(32 64 16)
            (map channel-volume (list beep click soft)))
      (sound-volume-set! 1.0)
      (group-volume-set! 'ui 0)
      (test "a game's own group silenced" 0 (channel-volume click))
      (group-volume-set! 'effects 1.0)
      (group-volume-set! 'ui 1.0))
    (test-error "a group is a symbol" (group-volume-set! "music" 0.5))
    (test-error "load-sounds! group: is a symbol" (load-sounds! `((x . ,snd-wav)) group: "ui"))
    (test-error "sound-group of an unknown sound names it" (snd-says? "no sound named" "nope")
                (sound-group 'nope)))

  (test-group "music"
    (test-error "play-music! before load-music!" (snd-says? "load-music!")
                (play-music!))
    (test-error "missing music names the path" (snd-says? "Mix_LoadMUS" snd-missing "Couldn")
                (load-music! snd-missing))
    (load-music! snd-wav2)
    (test-assert "loaded" (music-loaded?))
    (play-music! volume: 0.5)
    (test-assert "playing" (music-playing?))
    (test "volume: 0.5 -> 64" 64 (music-volume))
    (music-volume-set! 2.0)
    (test "music volume clamps" 128 (music-volume))
    (music-volume-set! 0.1)
    (test "0.1 -> 13" 13 (music-volume))
    (music-volume-set! 1.0)
    (group-volume-set! 'music 0.25)
    (test "the music group multiplies the music's volume" 32 (music-volume))
    (music-volume-set! 0.5)
    (test "both at once" 16 (music-volume))
    (group-volume-set! 'music 1.0)
    (test "the music group back at 1.0" 64 (music-volume))
    (music-volume-set! 0.1)
    (stop-music!)
    (test "stopped" #f (music-playing?))
    (play-music! loops: 1)
    (test-assert "plays once" (music-playing?))
    (test "default volume is 1.0" 128 (music-volume))
    (test-error "bad loops" (snd-says? "loops") (play-music! loops: 'forever))
    (receive (loaded0 freed0) (sound-resource-counts)
      (load-music! snd-wav)
      (receive (loaded1 freed1) (sound-resource-counts)
        (test "replacing the music frees the old one" 1 (- freed1 freed0))
        (test "and loads one" 1 (- loaded1 loaded0))))
    (test "replacing halts the old music" #f (music-playing?))
    (play-music!)
    (test-assert "new music plays" (music-playing?)))

  (test-group "shutdown"
    (test "four live resources (beep, long, click, the music)" 4 (snd-live))
    (shutdown-audio!)
    (test "everything freed" 0 (snd-live))
    (test "closed" #f (audio-open?))
    (receive (loaded0 freed0) (sound-resource-counts)
      (shutdown-audio!)
      (receive (loaded1 freed1) (sound-resource-counts)
        (test "a second shutdown frees nothing" freed0 freed1)))
    (test "registry emptied" '() (sound-names))
    (test "no music" #f (music-loaded?))
    (test "music not playing" #f (music-playing?))
    (test "sound names are gone" '() (sound-names))
    (test-error "and play-sound says audio is closed" (snd-says? "init-audio!") (play-sound 'beep))
    (stop-music!)
    (test-assert "stop-music! after shutdown is harmless" #t)
    (gc #t)
    (test "finalizers free nothing twice" 0 (snd-live)))

  (test-group "init again"
    (sound-volume-set! 0.5)
    (test "volume set while closed is remembered" 64 (sound-volume))
    (init-audio! frequency: 22050 channels: 1 chunk-size: 512)
    (test "reopened" #t (audio-open?))
    (test "the sound volume set while closed is applied" 64 (sound-volume))
    (load-sounds! `((beep . ,snd-wav)))
    (test-assert "plays after reopening" (play-sound 'beep))
    (shutdown-audio!)
    (test "freed again" 0 (snd-live))))

;; Files checked before SDL_mixer sees them (downstroke media-header): a
;; WAV header SDL would divide by, a file too large, a device.
(define (snd-bad-wav! path offset value size)
  (let ((v (with-input-from-file snd-wav (lambda () (read-u8vector #f)) #:binary)))
    (snd-put! v offset value size)
    (call-with-output-file path (lambda (port) (write-u8vector v port)) #:binary)
    path))

(test-group "sound: files are checked before SDL_mixer reads them"
  (init-audio!)
  (let ((zero-channels (snd-bad-wav! (create-temporary-file ".wav") 22 0 2))
        (zero-rate (snd-bad-wav! (create-temporary-file ".wav") 24 0 4))
        (zero-align (snd-bad-wav! (create-temporary-file ".wav") 32 0 2)))
    (test-error "a WAV with 0 channels: an error naming the file, not a floating-point exception"
                (snd-says? zero-channels "0 channels")
                (load-sounds! `((a . ,zero-channels))))
    (test-error "the same as music" (snd-says? zero-channels "0 channels") (load-music! zero-channels))
    (test-error "0 samples a second" (snd-says? "0 samples a second") (load-sounds! `((a . ,zero-rate))))
    (test-error "0 bytes a block" (snd-says? "0 bytes a block") (load-sounds! `((a . ,zero-align))))
    (test "nothing was registered" #f (sound-loaded? 'a))
    (for-each delete-file* (list zero-channels zero-rate zero-align)))
  (test-error "/dev/zero is not a regular file (it once took 3.7 GB before failing)"
              (snd-says? "/dev/zero" "not a regular file")
              (load-sounds! '((z . "/dev/zero"))))
  (test-error "a file over max-sound-file-size names the size and the limit"
              (snd-says? snd-wav "4454 bytes" "limit of 1000 (max-sound-file-size)")
              (parameterize ((max-sound-file-size 1000)) (load-sounds! `((big . ,snd-wav)))))
  (load-sounds! `((fine . ,snd-wav)))
  (test-assert "a good WAV under the limit still loads" (sound-loaded? 'fine))
  (shutdown-audio!))

(for-each delete-file* (list snd-wav snd-wav2 snd-garbage))

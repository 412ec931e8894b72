;;; Socket clients for shell/tests/repl-test.scm, which compiles this file when it
;;; runs: they need what CHICKEN's tcp unit does not offer (sending each
;;; write at once with TCP_NODELAY, a reset by SO_LINGER 0, reads that give
;;; up after a while, a forked child that becomes another user).

(import scheme (chicken base) (chicken foreign))

(foreign-declare #<<EOF
#include <sys/types.h>
#include <sys/socket.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <arpa/inet.h>
#include <poll.h>
#include <unistd.h>
#include <errno.h>
#include <string.h>
#include <grp.h>
#include <fcntl.h>
EOF
)

;; A connected socket to 127.0.0.1:port with a 64 KiB receive buffer, or -1.
(define rc-connect
  (foreign-lambda* int ((int port))
    "struct sockaddr_in a; int one = 1; int small = 65536; int fd = socket(AF_INET, SOCK_STREAM, 0);
     if (fd < 0) C_return(-1);
     setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
     /* a fixed receive buffer: Linux would otherwise let it grow up to
        net.ipv4.tcp_rmem's limit (32 MiB on some hosts), and a client
        that reads nothing could then hold a whole large answer */
     setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
     memset(&a, 0, sizeof a); a.sin_family = AF_INET; a.sin_port = htons(port);
     a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
     if (connect(fd, (struct sockaddr *)&a, sizeof a) < 0) { close(fd); C_return(-1); }
     C_return(fd);"))

;; Sends text[start, end) once the socket takes it within ms: the bytes
;; sent, or -1 (the peer has gone, or ms passed).
(define rc-send-some
  (foreign-lambda* int ((int fd) (scheme-pointer buf) (int start) (int end) (int ms))
    "struct pollfd p; ssize_t n; p.fd = fd; p.events = POLLOUT; p.revents = 0;
     if (poll(&p, 1, ms) <= 0) C_return(-1);
     n = send(fd, (char *)buf + start, end - start, MSG_DONTWAIT | MSG_NOSIGNAL);
     C_return(n < 0 ? -1 : (int)n);"))

;; Bytes received into buf within ms: 0 at the end of the connection, -1
;; when nothing came, -2 on an error (a reset).
(define rc-recv
  (foreign-lambda* int ((int fd) (scheme-pointer buf) (int len) (int ms))
    "struct pollfd p; ssize_t n; p.fd = fd; p.events = POLLIN; p.revents = 0;
     if (poll(&p, 1, ms) <= 0) C_return(-1);
     n = recv(fd, buf, len, MSG_DONTWAIT);
     C_return(n < 0 ? -2 : (int)n);"))

;; Whether something (data or the end) is there to read within ms.
(define rc-readable?
  (foreign-lambda* bool ((int fd) (int ms))
    "struct pollfd p; p.fd = fd; p.events = POLLIN; p.revents = 0;
     C_return(poll(&p, 1, ms) > 0);"))

(define rc-close (foreign-lambda* void ((int fd)) "close(fd);"))
(define rc-shutdown-write (foreign-lambda* void ((int fd)) "shutdown(fd, SHUT_WR);"))

;; Closes with a reset (RST) instead of the usual end, as a port scanner does.
(define rc-reset
  (foreign-lambda* void ((int fd))
    "struct linger l; l.l_onoff = 1; l.l_linger = 0;
     setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l); close(fd);"))

;; Becomes user uid (group gid, no others); #t when it worked.
(define rc-become
  (foreign-lambda* bool ((int uid) (int gid))
    "C_return(setgroups(0, NULL) == 0 && setgid(gid) == 0 && setuid(uid) == 0);"))

;; Whether this process can open the file for reading.
(define rc-can-read?
  (foreign-lambda* bool ((c-string path))
    "int fd = path ? open(path, O_RDONLY) : -1; if (fd >= 0) close(fd); C_return(fd >= 0);"))

(define rc-exit (foreign-lambda void "_exit" int))
(define rc-sleep (foreign-lambda* void ((int ms)) "poll(NULL, 0, ms);"))

(define rc-buffer (make-string 65536))

;; Sends all of text; #f when the peer is gone or stops taking bytes for ms.
(define (rc-send fd text #!optional (ms 10000))
  (let ((n (string-length text)))
    (let loop ((start 0))
      (or (= start n)
          (let ((sent (rc-send-some fd text start n ms)))
            (and (> sent 0) (loop (+ start sent))))))))

;; Reads until (done? text) holds, the connection ends, or nothing comes
;; for ms: (values text how), how being done, ended or silent.
(define (rc-read-until fd done? #!optional (ms 10000))
  (let loop ((text ""))
    (if (done? text)
        (values text 'done)
        (let ((n (rc-recv fd rc-buffer (string-length rc-buffer) ms)))
          (cond ((> n 0) (loop (string-append text (substring rc-buffer 0 n))))
                ((= n -1) (values text 'silent))
                (else (values text 'ended)))))))

;; Reads everything until the connection ends (or ms of silence): (values
;; bytes-read ended?). Counts rather than keeps, for large answers.
(define (rc-drain fd #!optional (ms 10000))
  (let loop ((total 0))
    (let ((n (rc-recv fd rc-buffer (string-length rc-buffer) ms)))
      (cond ((> n 0) (loop (+ total n)))
            ((= n -1) (values total #f))
            (else (values total #t))))))

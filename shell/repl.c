/* The REPL's sockets and its secret file (included by repl.scm).
 *
 * Every server call returns at once: sockets are non-blocking, and sends
 * never raise SIGPIPE, so a client that vanishes is an error code for that
 * client alone. Each function returns a count or a descriptor (>= 0), or a
 * negative code; the text of the last failure is in repl_why. */

#include <sys/types.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <unistd.h>
#include <errno.h>
#include <string.h>
#include <stdio.h>
#include <poll.h>
#include <stdint.h>

#ifndef MSG_NOSIGNAL
#define MSG_NOSIGNAL 0          /* where it is missing, SO_NOSIGPIPE below */
#endif
#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

#define REPL_AGAIN (-1)         /* nothing to do now: try on the next poll */
#define REPL_FAILED (-2)        /* this client (or call) failed: see repl_why */
#define REPL_DROPPED (-3)       /* a connection was closed at once: see repl_why */

static char repl_why[256];

static int repl_fail(const char *what) {
  int e = errno;
  strncpy(repl_why, what, sizeof repl_why - 1);
  repl_why[sizeof repl_why - 1] = 0;
  if (e) {
    size_t n = strlen(repl_why);
    snprintf(repl_why + n, sizeof repl_why - n, ": %s", strerror(e));
  }
  return REPL_FAILED;
}

static const char *repl_last_failure(void) { return repl_why; }

/* Non-blocking, closed on exec, and (where MSG_NOSIGNAL is missing) no
 * SIGPIPE. */
static int repl_prepare(int fd) {
  int flags = fcntl(fd, F_GETFL);
  if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) return -1;
  if (fcntl(fd, F_SETFD, FD_CLOEXEC) < 0) return -1;
#ifdef SO_NOSIGPIPE
  { int one = 1; setsockopt(fd, SOL_SOCKET, SO_NOSIGPIPE, &one, sizeof one); }
#endif
  return 0;
}

/* A listening socket on 127.0.0.1:port (0: any free port). */
static int repl_listen(int port, int backlog) {
  struct sockaddr_in a;
  int one = 1;
  int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return repl_fail("cannot make a socket");
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  memset(&a, 0, sizeof a);
  a.sin_family = AF_INET;
  a.sin_port = htons((unsigned short)port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (repl_prepare(fd) < 0) { repl_fail("cannot set up the socket"); close(fd); return REPL_FAILED; }
  if (bind(fd, (struct sockaddr *)&a, sizeof a) < 0) { repl_fail("cannot listen on 127.0.0.1"); close(fd); return REPL_FAILED; }
  if (listen(fd, backlog) < 0) { repl_fail("cannot listen on 127.0.0.1"); close(fd); return REPL_FAILED; }
  return fd;
}

static int repl_bound_port(int fd) {
  struct sockaddr_in a;
  socklen_t n = sizeof a;
  if (getsockname(fd, (struct sockaddr *)&a, &n) < 0) return repl_fail("cannot read the port");
  return ntohs(a.sin_port);
}

/* A descriptor kept open so that, out of descriptors, the REPL can still
 * accept a waiting connection in order to close it. */
static int repl_spare(void) { return open("/dev/null", O_RDONLY | O_CLOEXEC); }

/* The next waiting connection; REPL_AGAIN when none is waiting;
 * REPL_DROPPED when, out of descriptors, the waiting one was accepted with
 * the spare descriptor *spare (then reopened) and closed at once, so that
 * it does not wait in vain; REPL_FAILED on any other error. */
static int repl_accept(int lfd, int32_t *spare) {
  int fd = accept(lfd, NULL, NULL);
  if (fd >= 0) {
    /* answers go at once: each poll sends all it has in one call */
    int one = 1;
    if (repl_prepare(fd) < 0) { close(fd); return REPL_AGAIN; }
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    return fd;
  }
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNABORTED
      || errno == EPROTO)
    return REPL_AGAIN;
  if ((errno == EMFILE || errno == ENFILE) && *spare >= 0) {
    int e = errno;
    close(*spare);
    fd = accept(lfd, NULL, NULL);
    if (fd >= 0) close(fd);
    *spare = repl_spare();
    errno = e;
    repl_fail("closed a connection at once, being out of descriptors");
    return fd >= 0 && *spare >= 0 ? REPL_DROPPED : REPL_FAILED;
  }
  return repl_fail("cannot accept a connection");
}

/* Bytes read into buf[0..len), 0 at the end of the client's input. */
static int repl_recv(int fd, char *buf, int len) {
  ssize_t n = recv(fd, buf, (size_t)len, MSG_DONTWAIT);
  if (n >= 0) return (int)n;
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return REPL_AGAIN;
  return repl_fail("cannot read from the client");
}

/* Bytes of buf[start..start+len) sent. */
static int repl_send(int fd, const char *buf, int start, int len) {
  ssize_t n = send(fd, buf + start, (size_t)len, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (n >= 0) return (int)n;
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return REPL_AGAIN;
  return repl_fail("cannot write to the client");
}

static void repl_close(int fd) { if (fd >= 0) close(fd); }

/* len bytes from the system's random source. */
static int repl_random(char *buf, int len) {
  int got = 0;
  int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return repl_fail("cannot open /dev/urandom");
  while (got < len) {
    ssize_t n = read(fd, buf + got, (size_t)(len - got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) { repl_fail("cannot read /dev/urandom"); close(fd); return REPL_FAILED; }
    got += (int)n;
  }
  close(fd);
  return got;
}

/* mkdir with mode 0700; an existing entry is left for repl_private_dir to
 * judge. */
static int repl_make_dir(const char *path) {
  if (mkdir(path, 0700) == 0 || errno == EEXIST) return 0;
  return repl_fail("cannot create the directory");
}

/* The directory, opened without following a link, when it is this user's
 * and no one else's: a descriptor for repl_write_secret. */
static int repl_private_dir(const char *path) {
  struct stat st;
  int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return repl_fail("cannot open the directory (it must be a directory, not a link)");
  if (fstat(fd, &st) < 0) { repl_fail("cannot inspect the directory"); close(fd); return REPL_FAILED; }
  errno = 0;
  if (!S_ISDIR(st.st_mode)) { repl_fail("it is not a directory"); close(fd); return REPL_FAILED; }
  if (st.st_uid != geteuid()) { repl_fail("it belongs to another user"); close(fd); return REPL_FAILED; }
  if (st.st_mode & 077) {
    repl_fail("other users can open it (it must be mode 0700)");
    close(fd);
    return REPL_FAILED;
  }
  return fd;
}

/* Writes text to a new file name in the directory dfd, readable and
 * writable by this user only. A leftover file of that name (from a game
 * that ended without closing its REPL) is removed first: the directory is
 * private, so nothing in it was put there by anyone else. */
static int repl_write_secret(int dfd, const char *name, const char *text, int len) {
  int fd, done = 0;
  if (unlinkat(dfd, name, 0) < 0 && errno != ENOENT) return repl_fail("cannot remove the old secret file");
  fd = openat(dfd, name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return repl_fail("cannot create the secret file");
  while (done < len) {
    ssize_t n = write(fd, text + done, (size_t)(len - done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      repl_fail("cannot write the secret file");
      close(fd);
      unlinkat(dfd, name, 0);
      return REPL_FAILED;
    }
    done += (int)n;
  }
  if (close(fd) < 0) { repl_fail("cannot write the secret file"); unlinkat(dfd, name, 0); return REPL_FAILED; }
  return 0;
}

static void repl_remove_secret(int dfd, const char *name) {
  if (dfd >= 0) { if (name) unlinkat(dfd, name, 0); close(dfd); }
}

/* The client side, which may block: it is a program of its own. */

static int repl_connect(int port) {
  struct sockaddr_in a;
  int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return repl_fail("cannot make a socket");
  memset(&a, 0, sizeof a);
  a.sin_family = AF_INET;
  a.sin_port = htons((unsigned short)port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, (struct sockaddr *)&a, sizeof a) < 0) {
    repl_fail("cannot connect to 127.0.0.1");
    close(fd);
    return REPL_FAILED;
  }
#ifdef SO_NOSIGPIPE
  { int one = 1; setsockopt(fd, SOL_SOCKET, SO_NOSIGPIPE, &one, sizeof one); }
#endif
  return fd;
}

static int repl_write_all(int fd, const char *buf, int len, int socket) {
  int done = 0;
  while (done < len) {
    ssize_t n = socket ? send(fd, buf + done, (size_t)(len - done), MSG_NOSIGNAL)
                       : write(fd, buf + done, (size_t)(len - done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return -1;
    done += (int)n;
  }
  return done;
}

static int repl_send_all(int fd, const char *buf, int len) {
  return repl_write_all(fd, buf, len, 1) < 0 ? repl_fail("cannot write to the game") : len;
}

/* Copies standard input to the socket and the socket to standard output
 * until the game closes the connection. At the end of standard input the
 * socket's sending side is shut, and the game's last answers still come. */
static int repl_relay(int fd) {
  char buf[16384];
  int stdin_open = 1;
  for (;;) {
    struct pollfd p[2];
    p[0].fd = fd; p[0].events = POLLIN; p[0].revents = 0;
    if (stdin_open) { p[1].fd = 0; p[1].events = POLLIN; p[1].revents = 0; }
    if (poll(p, stdin_open ? 2 : 1, -1) < 0) {
      if (errno == EINTR) continue;
      return repl_fail("cannot wait for input");
    }
    if (p[0].revents) {
      ssize_t got = recv(fd, buf, sizeof buf, 0);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) return repl_fail("cannot read from the game");
      if (got == 0) return 0;
      if (repl_write_all(1, buf, (int)got, 0) < 0) return repl_fail("cannot write to standard output");
    }
    if (stdin_open && p[1].revents) {
      ssize_t got = read(0, buf, sizeof buf);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) { stdin_open = 0; shutdown(fd, SHUT_WR); }
      else if (repl_write_all(fd, buf, (int)got, 1) < 0) return repl_fail("cannot write to the game");
    }
  }
}

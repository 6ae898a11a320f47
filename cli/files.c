#define _DEFAULT_SOURCE /* realpath */
#include "files.h"

#include <glint.h>

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

int same_file(const char *a, const char *b) {
  struct stat sa, sb;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

char *written_file(const char *path) {
  /* (a loop of links: the name itself, which the writers then refuse) */
  char *at = glint_output_file(path);
  if (!at && !(at = strdup(path)))
    return NULL;
  char *slash = strrchr(at, '/');
  const char *base = slash ? slash + 1 : at;
  if (slash)
    *slash = '\0';
  char *folder = realpath(slash ? (at[0] ? at : "/") : ".", NULL);
  const char *shown = folder ? folder : at;
  size_t size = strlen(shown) + strlen(base) + 2;
  char *file = malloc(size);
  if (file) /* (the root folder is "/" itself) */
    snprintf(file, size, "%s%s%s", shown,
             shown[0] && shown[strlen(shown) - 1] == '/' ? "" : "/", base);
  free(folder);
  glint_free(at);
  return file;
}

int named_as_input(const char *path) {
  static const char *const kinds[] = {".nff", ".json", ".obj", ".ply"};
  const char *slash = strrchr(path, '/');
  const char *base = slash ? slash + 1 : path;
  size_t n = strlen(base);
  if (n > 3 && strcasecmp(base + n - 3, ".gz") == 0)
    n -= 3;
  for (size_t i = 0; i < sizeof kinds / sizeof *kinds; i++) {
    size_t e = strlen(kinds[i]);
    if (n > e && strncasecmp(base + n - e, kinds[i], e) == 0)
      return 1;
  }
  return 0;
}

int links_to_input(const char *path, char *target) {
  /* Every link of the chain: a mesh may itself be a link to a file of
   * another name (mesh.obj -> store/blob), which the image written
   * through out.png -> mesh.obj would replace. */
  char at[PATH_MAX];
  if (snprintf(at, sizeof at, "%s", path) >= (int)sizeof at)
    return 0;
  for (int hop = 0; hop < 40; hop++) { /* (a loop fails to open anyway) */
    struct stat sb;
    if (lstat(at, &sb) != 0 || !S_ISLNK(sb.st_mode))
      return 0;
    char to[PATH_MAX];
    ssize_t n = readlink(at, to, sizeof to - 1);
    if (n <= 0)
      return 0;
    to[n] = '\0';
    /* a relative target is relative to the link's folder */
    char *slash = strrchr(at, '/');
    if (to[0] != '/' && slash) {
      slash[1] = '\0';
      if (strlen(at) + strlen(to) >= sizeof at)
        return 0;
      strcat(at, to);
    } else {
      strcpy(at, to);
    }
    if (named_as_input(at)) {
      snprintf(target, PATH_MAX, "%s", at);
      return 1;
    }
  }
  return 0;
}

int create_beside(const char *path, char *temp, size_t size) {
  /* NAME.PID-k.tmp, or .glint-PID-k.tmp in NAME's folder where the file
   * system finds that too long (a legal name of 250 bytes was refused) */
  const char *slash = strrchr(path, '/');
  int folder = slash ? (int)(slash - path + 1) : 0;
  for (int whole = 1; whole >= 0; whole--)
    for (int k = 0; k < 100; k++) {
      int n =
          whole ? snprintf(temp, size, "%s.%ld-%d.tmp", path, (long)getpid(), k)
                : snprintf(temp, size, "%.*s.glint-%ld-%d.tmp", folder, path,
                           (long)getpid(), k);
      int fd = -1;
      if (n >= (int)size)
        errno = ENAMETOOLONG;
      else
        fd = open(temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd >= 0 || (errno != EEXIST && (errno != ENAMETOOLONG || !whole)))
        return fd;
      if (errno == ENAMETOOLONG)
        break; /* the shorter name */
    }
  if (errno != ENAMETOOLONG)
    errno = EEXIST;
  return -1;
}

int replace_begin(file_replacement *r, const char *path) {
  struct stat sb;
  if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode)) {
    if (!realpath(path, r->path))
      return errno;
  } else if (snprintf(r->path, sizeof r->path, "%s", path) >=
             (int)sizeof r->path) {
    return ENAMETOOLONG;
  }
  sigset_t stops;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  sigaddset(&stops, SIGHUP);
  sigprocmask(SIG_BLOCK, &stops, &r->signals);
  r->fd = create_beside(r->path, r->temp, sizeof r->temp);
  if (r->fd < 0) {
    int saved = errno;
    sigprocmask(SIG_SETMASK, &r->signals, NULL);
    return saved;
  }
  /* A file replaced keeps its permissions, as the images' writer keeps
   * them (a new one has 0666 less the umask). */
  if (stat(r->path, &sb) == 0 && S_ISREG(sb.st_mode))
    (void)fchmod(r->fd, sb.st_mode & 07777);
  return 0;
}

int replace_write(file_replacement *r, const void *data, size_t size) {
  for (size_t done = 0; done < size;) {
    ssize_t n = write(r->fd, (const char *)data + done, size - done);
    if (n < 0 && errno != EINTR)
      return errno;
    if (n > 0)
      done += (size_t)n;
  }
  return 0;
}

int replace_end(file_replacement *r, int keep) {
  int saved = 0;
  if (keep && fsync(r->fd) != 0 && errno != EINVAL)
    saved = errno;
  if (close(r->fd) != 0 && !saved)
    saved = errno;
  if (keep && !saved && rename(r->temp, r->path) != 0)
    saved = errno;
  if (!keep || saved)
    unlink(r->temp);
  sigprocmask(SIG_SETMASK, &r->signals, NULL);
  return saved;
}

int replace_whole(const char *path, const void *data, size_t size) {
  file_replacement r;
  int saved = replace_begin(&r, path);
  if (!saved) {
    saved = replace_write(&r, data, size);
    int ended = replace_end(&r, !saved);
    saved = saved ? saved : ended;
  }
  return saved;
}

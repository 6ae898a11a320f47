/* Files the commands write that are not images (the images' own writer is
 * the library's, glint_image_writer): a benchmark's CSV, a file a viewer
 * script copies. Each is written beside its destination and renamed over
 * it when complete, so that a failure or a stop signal leaves an existing
 * file as it was and no half-written one. */
#ifndef GLINT_CLI_FILES_H
#define GLINT_CLI_FILES_H

#include <limits.h>
#include <signal.h>
#include <stddef.h>

/* Whether paths a and b name one existing file (through links or not). */
int same_file(const char *a, const char *b);

/* The file that writing `path` replaces, named without links (a malloc'd
 * string; NULL out of memory): glint_output_file's, its folder resolved
 * by realpath, so that two names of one file (a link to a file, or in a
 * folder that is a link) compare equal. */
char *written_file(const char *path);

/* Whether `path` is named as glint's inputs are: a scene or a mesh (.nff,
 * .json, .obj, .ply, each optionally .gz), compared without case as the
 * readers compare them. */
int named_as_input(const char *path);

/* Whether `path` is a symbolic link (or a chain of them) any link of
 * which names a file named as an input, which a file written through the
 * link would replace; that link's target then in target (PATH_MAX
 * bytes), as the links name it. */
int links_to_input(const char *path, char *target);

/* A new file beside `path` (its name in `temp`), mode 0666 less the umask;
 * returns its descriptor, or -1 with errno set. */
int create_beside(const char *path, char *temp, size_t size);

/* A file being written in the place of `path`. */
typedef struct file_replacement {
  char path[PATH_MAX];      /* the destination (a link's target) */
  char temp[PATH_MAX + 32]; /* the file written */
  int fd;
  sigset_t signals; /* the signal mask before replace_begin */
} file_replacement;

/* Starts replacing `path` (through a link, the file it names: renamed over,
 * the link itself would be replaced), keeping an existing file's
 * permissions. Stop signals (SIGINT, SIGTERM, SIGHUP) wait from here until
 * replace_end. Returns 0, or an errno value (with nothing to end). */
int replace_begin(file_replacement *r, const char *path);
/* Appends `size` bytes; returns 0 or an errno value. */
int replace_write(file_replacement *r, const void *data, size_t size);
/* keep = 1: the file (flushed to disk) takes the destination's place;
 * keep = 0: it is removed. Returns 0, or an errno value (the file then
 * removed and the destination as it was). */
int replace_end(file_replacement *r, int keep);
/* Replaces `path` with the `size` bytes of `data` whole, or leaves it as
 * it was: replace_begin, replace_write and replace_end. Returns 0, or an
 * errno value. */
int replace_whole(const char *path, const void *data, size_t size);

#endif

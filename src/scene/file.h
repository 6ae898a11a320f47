/* Reading a whole scene or mesh file into memory, the one way every reader
 * does it: gzip-compressed files (known by their magic, whatever their
 * name) are decompressed transparently, whole members only and nothing
 * after the last, plain files read as they are, only regular files are
 * read (a FIFO or a device could block or never end), and every failure is
 * one message that starts with the path. */
#ifndef GLINT_SCENE_FILE_H
#define GLINT_SCENE_FILE_H

#include "glint.h"

#include <stddef.h>

/* The whole of `path` in *data (malloc'ed, to be freed by the caller), with
 * a NUL one past the last of its *size bytes. Files of more than max_bytes
 * (after decompression) are refused, naming the limit. A `text` file is
 * refused at its first NUL byte, as gli_file_check_text says, as soon as
 * that part is read (its first 64 KiB are read alone first): a large
 * binary file named as a text one is refused unread, not read whole first
 * (a sparse file of 3 GB took 18 s). Otherwise NUL bytes are kept.
 * GLINT_E_IO when the system cannot read the file, GLINT_E_PARSE for a
 * damaged or truncated compressed stream. Thread-safe. */
glint_status gli_file_read_all(const char *path, size_t max_bytes, int text,
                               char **data, size_t *size, glint_error *error);

/* Where a loader gets the files it reads: the scene file and the files it
 * refers to (a JSON scene's meshes). NULL is the file system
 * (gli_file_read_all); scene/pack.c records what a load reads
 * (glint_scene_pack) and serves packed bytes instead of files
 * (glint_scene_load_packed), so that ranks of an MPI job parse the very
 * bytes rank 0 read. `read` keeps gli_file_read_all's contract. */
typedef struct gli_file_source {
  glint_status (*read)(void *context, const char *path, size_t max_bytes,
                       int text, char **data, size_t *size, glint_error *error);
  void *context;
} gli_file_source;

glint_status gli_file_source_read(const gli_file_source *source,
                                  const char *path, size_t max_bytes, int text,
                                  char **data, size_t *size,
                                  glint_error *error);

/* Steps over a UTF-8 byte-order mark at the start of a text file, if any. */
void gli_file_skip_bom(const char **data, size_t *size);

/* Line (from first_line) and column (UTF-8 characters, from 1) of `at` in
 * text starting at `data`. A line ends in LF, CR LF or a lone CR (old Mac
 * files). */
void gli_text_line_column(const char *data, const char *at, size_t first_line,
                          size_t *line, size_t *column);

/* GLINT_E_PARSE "PATH:LINE:COLUMN: a NUL byte: binary data where text was
 * expected" if data holds a NUL byte (it would end a number early and hide
 * the rest of the line), as gli_text_line_column counts them; "PATH: UTF-16
 * text" if data from a file's first line (first_line 1) starts with a
 * UTF-16 byte-order mark. */
glint_status gli_file_check_text(const char *path, const char *data,
                                 size_t size, size_t first_line,
                                 glint_error *error);

#endif

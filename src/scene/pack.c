/* A scene and the files it refers to, packed into one block of bytes
 * (glint_scene_pack) and loaded from it (glint_scene_load_packed).
 *
 * Packing loads the scene once with a file source that reads each file from
 * the file system and keeps a copy of its bytes; loading a block runs the
 * same loader with a source that serves those bytes by the path the loader
 * asks for. Both loads ask for the same paths in the same order, since they
 * parse the same bytes, so every rank of an MPI job builds the scene rank 0
 * read, whatever its own file system holds.
 *
 * The block, all numbers little-endian:
 *   "GLINTPK2"                   8 bytes, the magic and version
 *   count                        u32, files (the scene file first)
 *   count x { path_len u32, path bytes, data_len u64, data bytes }
 *   crc                          u32, zlib's CRC-32 of every byte before it
 * The CRC makes a changed byte inside a file's text a damaged block, not
 * a different scene loaded without a word (version 1 had none). */
#include "core/error.h"
#include "scene/file.h"
#include "scene/scene.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static const char magic[8] = {'G', 'L', 'I', 'N', 'T', 'P', 'K', '2'};
#define CRC_BYTES 4

typedef struct packed_file {
  char *path;
  char *data; /* size bytes, then a NUL */
  size_t size;
  int owned; /* path and data allocated here (packing), else in the block */
} packed_file;

typedef struct file_list {
  packed_file *files;
  size_t count, capacity;
} file_list;

static void file_list_free(file_list *l) {
  for (size_t i = 0; i < l->count; i++)
    if (l->files[i].owned) {
      free(l->files[i].path);
      free(l->files[i].data);
    }
  free(l->files);
}

static const packed_file *find(const file_list *l, const char *path) {
  for (size_t i = 0; i < l->count; i++)
    if (strcmp(l->files[i].path, path) == 0)
      return &l->files[i];
  return NULL;
}

/* A copy of f's bytes, NUL-terminated, as gli_file_read_all returns them. */
static glint_status copy_out(const packed_file *f, const char *path,
                             size_t max_bytes, char **data, size_t *size,
                             glint_error *error) {
  if (f->size > max_bytes)
    return gli_fail(error, GLINT_E_IO, "%s: larger than %zu bytes", path,
                    max_bytes);
  char *copy = malloc(f->size + 1);
  if (!copy)
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
  memcpy(copy, f->data, f->size);
  copy[f->size] = '\0';
  *data = copy;
  *size = f->size;
  return GLINT_OK;
}

/* Packing's source: the file system, each file kept once (a mesh used
 * twice is read once). */
static glint_status read_and_keep(void *context, const char *path,
                                  size_t max_bytes, int text, char **data,
                                  size_t *size, glint_error *error) {
  file_list *l = context;
  const packed_file *kept = find(l, path);
  if (kept)
    return copy_out(kept, path, max_bytes, data, size, error);
  if (l->count == l->capacity) {
    size_t capacity = l->capacity ? 2 * l->capacity : 8;
    packed_file *grown = realloc(l->files, capacity * sizeof *grown);
    if (!grown)
      return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
    l->files = grown;
    l->capacity = capacity;
  }
  glint_status st = gli_file_read_all(path, max_bytes, text, data, size, error);
  if (st)
    return st;
  packed_file f = {strdup(path), malloc(*size + 1), *size, 1};
  if (!f.path || !f.data) {
    free(f.path);
    free(f.data);
    free(*data);
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
  }
  memcpy(f.data, *data, *size + 1);
  l->files[l->count++] = f;
  return GLINT_OK;
}

/* Loading's source: the block's files only (their text the readers check
 * as they parse). */
static glint_status serve_packed(void *context, const char *path,
                                 size_t max_bytes, int text, char **data,
                                 size_t *size, glint_error *error) {
  (void)text;
  const packed_file *f = find(context, path);
  if (!f)
    return gli_fail(error, GLINT_E_IO,
                    "%s: not in the packed scene (packed by another "
                    "version of glint?)",
                    path);
  return copy_out(f, path, max_bytes, data, size, error);
}

static void put_u32(unsigned char *p, uint32_t v) {
  for (int i = 0; i < 4; i++)
    p[i] = (unsigned char)(v >> (8 * i));
}

static void put_u64(unsigned char *p, uint64_t v) {
  for (int i = 0; i < 8; i++)
    p[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t get_le(const unsigned char *p, int bytes) {
  uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; i--)
    v = v << 8 | p[i];
  return v;
}

glint_status glint_scene_pack(const char *path, void **packed, size_t *size,
                              glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(packed, "packed", error);
  GLI_NOT_NULL(size, "size", error);
  file_list files = {NULL, 0, 0};
  gli_file_source source = {read_and_keep, &files};
  glint_scene *scene;
  glint_status st = gli_scene_load_from(&source, path, &scene, error);
  if (st) {
    file_list_free(&files);
    return st;
  }
  glint_scene_destroy(scene); /* loaded to learn which files it reads */
  size_t total = sizeof magic + 4 + CRC_BYTES;
  for (size_t i = 0; i < files.count; i++)
    total += 4 + strlen(files.files[i].path) + 8 + files.files[i].size;
  unsigned char *block = malloc(total);
  if (!block || files.count > UINT32_MAX) {
    free(block);
    file_list_free(&files);
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
  }
  unsigned char *p = block;
  memcpy(p, magic, sizeof magic);
  p += sizeof magic;
  put_u32(p, (uint32_t)files.count);
  p += 4;
  for (size_t i = 0; i < files.count; i++) {
    const packed_file *f = &files.files[i];
    size_t n = strlen(f->path);
    put_u32(p, (uint32_t)n); /* a path is far shorter than 4 GiB */
    memcpy(p + 4, f->path, n);
    p += 4 + n;
    put_u64(p, f->size);
    memcpy(p + 8, f->data, f->size);
    p += 8 + f->size;
  }
  put_u32(p, (uint32_t)crc32_z(0, block, total - CRC_BYTES));
  file_list_free(&files);
  *packed = block;
  *size = total;
  return GLINT_OK;
}

static glint_status damaged(glint_error *error, const char *what) {
  return gli_fail(error, GLINT_E_PARSE, "packed scene: damaged (%s)", what);
}

glint_status glint_scene_load_packed(const void *packed, size_t size,
                                     glint_scene **scene, glint_error *error) {
  GLI_NOT_NULL(packed, "packed", error);
  GLI_NOT_NULL(scene, "scene", error);
  if (size > PTRDIFF_MAX) /* no block is that large: a wrong size */
    return damaged(error, "size");
  const unsigned char *p = packed;
  if (size < sizeof magic + 4 + CRC_BYTES ||
      memcmp(p, magic, sizeof magic) != 0)
    return damaged(error, "not a packed glint scene");
  const unsigned char *end = p + size - CRC_BYTES;
  if (crc32_z(0, p, size - CRC_BYTES) != get_le(end, CRC_BYTES))
    return damaged(error, "its checksum does not match its bytes");
  uint64_t count = get_le(p + sizeof magic, 4);
  p += sizeof magic + 4;
  if (count == 0 || count > size / 12) /* 12: an empty file's overhead */
    return damaged(error, "file count");
  file_list files = {calloc(count, sizeof(packed_file)), 0, count};
  if (!files.files)
    return gli_fail(error, GLINT_E_MEMORY, "packed scene: out of memory");
  /* The paths and bytes stay in the block: paths need a NUL, and the
   * readers' copies get one (copy_out), so each path is copied alone. */
  glint_status st = GLINT_OK;
  for (uint64_t i = 0; i < count && !st; i++) {
    uint64_t n = (size_t)(end - p) >= 4 ? get_le(p, 4) : UINT64_MAX;
    if (n == 0 || n > (uint64_t)(end - p) - 4 ||
        (uint64_t)(end - p) - 4 - n < 8) {
      st = damaged(error, "file name");
      break;
    }
    char *path = malloc(n + 1);
    if (!path) {
      st = gli_fail(error, GLINT_E_MEMORY, "packed scene: out of memory");
      break;
    }
    memcpy(path, p + 4, n);
    path[n] = '\0';
    p += 4 + n;
    uint64_t bytes = get_le(p, 8);
    p += 8;
    if (memchr(path, '\0', n) || bytes > (uint64_t)(end - p)) {
      free(path);
      st = damaged(error, "file size");
      break;
    }
    files.files[files.count++] = (packed_file){path, (char *)p, bytes, 0};
    p += bytes;
  }
  if (!st && p != end)
    st = damaged(error, "bytes after the last file");
  if (!st) {
    gli_file_source source = {serve_packed, &files};
    st = gli_scene_load_from(&source, files.files[0].path, scene, error);
    /* The block was packed from a scene that loaded: one that does not
     * load now is damaged (a file's name or bytes changed), whatever the
     * loader calls it (a name that is no scene file, a file not there). */
    if (st && st != GLINT_E_MEMORY) {
      glint_error loaded = {0};
      if (error)
        loaded = *error;
      st = gli_fail(error, GLINT_E_PARSE, "packed scene: damaged: %s",
                    loaded.message);
    }
  }
  for (size_t i = 0; i < files.count; i++)
    free(files.files[i].path);
  free(files.files);
  return st;
}

void glint_free(void *memory) { free(memory); }

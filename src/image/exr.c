/* OpenEXR output through OpenEXR's C library (OpenEXRCore): 32-bit float
 * R, G and B channels, scanline storage with ZIP compression, written into
 * the caller's stream (the atomic write of image/image.c). */
#include "image/image.h"

#include <errno.h>
#include <openexr.h>
#include <string.h>
#include <unistd.h>

/* Where the encoder writes, and why a write failed (an errno; 0: none). */
typedef struct exr_sink {
  FILE *f;
  int error;
} exr_sink;

static int64_t write_at(exr_const_context_t ctxt, void *user,
                        const void *buffer, uint64_t size, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb) {
  (void)ctxt;
  (void)error_cb;
  exr_sink *sink = user;
  /* All of it, or the reason it could not be: a short write (a disk
   * filling, a file-size limit reached) is followed by one that says
   * why. */
  const char *bytes = buffer;
  uint64_t done = 0;
  while (done < size) {
    ssize_t n = pwrite(fileno(sink->f), bytes + done, size - done,
                       (off_t)(offset + done));
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0) {
      sink->error = n < 0 ? errno : ENOSPC;
      return -1;
    }
    done += (uint64_t)n;
  }
  return (int64_t)done;
}

/* Library messages stay out of stderr: the caller reports the failure. */
static void quiet(exr_const_context_t ctxt, exr_result_t code,
                  const char *msg) {
  (void)ctxt;
  (void)code;
  (void)msg;
}

static exr_result_t write_chunks(exr_context_t ctx, const glint_film *film) {
  int lines = 0;
  exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
  exr_encode_pipeline_t enc;
  int started = 0;
  for (int y = 0; rv == EXR_ERR_SUCCESS && y < film->height; y += lines) {
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(ctx, 0, y, &chunk);
    if (rv != EXR_ERR_SUCCESS)
      break;
    rv = started ? exr_encoding_update(ctx, 0, &chunk, &enc)
                 : exr_encoding_initialize(ctx, 0, &chunk, &enc);
    if (rv != EXR_ERR_SUCCESS)
      break;
    const uint8_t *row =
        (const uint8_t *)(film->rgb + (size_t)y * film->width * 3);
    for (int c = 0; c < enc.channel_count; c++) {
      exr_coding_channel_info_t *ch = &enc.channels[c];
      int k = ch->channel_name[0] == 'R'   ? 0
              : ch->channel_name[0] == 'G' ? 1
                                           : 2;
      ch->encode_from_ptr = row + (size_t)k * sizeof(float);
      ch->user_pixel_stride = 3 * sizeof(float);
      ch->user_line_stride = film->width * 3 * (int32_t)sizeof(float);
      ch->user_bytes_per_element = sizeof(float);
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (!started) {
      rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
      started = 1;
      if (rv != EXR_ERR_SUCCESS)
        break;
    }
    rv = exr_encoding_run(ctx, 0, &enc);
  }
  if (started)
    exr_encoding_destroy(ctx, &enc);
  return rv;
}

int gli_exr_encode(const glint_film *film, FILE *f) {
  if (fflush(f) != 0)
    return -1;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  exr_sink sink = {f, 0};
  init.user_data = &sink;
  init.write_fn = write_at;
  init.error_handler_fn = quiet;
  exr_context_t ctx = NULL;
  exr_result_t rv =
      exr_start_write(&ctx, "film.exr", EXR_WRITE_FILE_DIRECTLY, &init);
  int part = 0;
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_add_part(ctx, "glint", EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_initialize_required_attr_simple(ctx, part, film->width,
                                             film->height, EXR_COMPRESSION_ZIP);
  static const char *const names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3 && rv == EXR_ERR_SUCCESS; c++)
    rv = exr_add_channel(ctx, part, names[c], EXR_PIXEL_FLOAT,
                         EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_write_header(ctx);
  if (rv == EXR_ERR_SUCCESS)
    rv = write_chunks(ctx, film);
  exr_result_t done = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
  if (rv == EXR_ERR_SUCCESS)
    rv = done;
  if (rv != EXR_ERR_SUCCESS) {
    /* 0 when the encoder itself failed, unless for memory */
    errno = sink.error ? sink.error : rv == EXR_ERR_OUT_OF_MEMORY ? ENOMEM : 0;
    return -1;
  }
  /* The stream's own position never moved: put it at the end, so the
   * caller's flush and sync see a complete file. */
  return fseeko(f, 0, SEEK_END) != 0 ? -1 : 0;
}

/* The viewer's on-screen text (cli/view_font.c). */
#ifndef GLINT_CLI_VIEW_FONT_H
#define GLINT_CLI_VIEW_FONT_H

#include <stdint.h>

enum { VIEW_GLYPH_W = 5, VIEW_GLYPH_H = 7 };

/* Pixels that `text` spans at `scale` (one column of space per glyph). */
int view_text_width(const char *text, int scale);

/* Draws `text` with its top-left corner at (x, y) into a width x height RGB
 * buffer, each font pixel `scale` x `scale` pixels; clipped to the buffer. */
void view_draw_text(uint8_t *rgb, int width, int height, int x, int y,
                    const char *text, int scale, const uint8_t colour[3]);

/* Darkens [x0, x1) x [y0, y1) to a third, behind text. */
void view_shade_box(uint8_t *rgb, int width, int height, int x0, int y0, int x1,
                    int y1);

#endif

/* The viewer's on-screen text: a 5x7 bitmap font, drawn in glint's own
 * hand (each glyph below is its picture), scaled by whole pixels. Letters
 * are drawn as capitals; a character without a glyph is drawn as '?'. */
#include "view_font.h"

#include <ctype.h>
#include <stddef.h>

typedef struct glyph {
  char c;
  const char *rows; /* 7 rows of 5 columns, '#' for ink */
} glyph;

static const glyph glyphs[] = {
    {' ', "                                   "},
    {'A', " ### "
          "#   #"
          "#   #"
          "#####"
          "#   #"
          "#   #"
          "#   #"},
    {'B', "#### "
          "#   #"
          "#   #"
          "#### "
          "#   #"
          "#   #"
          "#### "},
    {'C', " ### "
          "#   #"
          "#    "
          "#    "
          "#    "
          "#   #"
          " ### "},
    {'D', "#### "
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#### "},
    {'E', "#####"
          "#    "
          "#    "
          "#### "
          "#    "
          "#    "
          "#####"},
    {'F', "#####"
          "#    "
          "#    "
          "#### "
          "#    "
          "#    "
          "#    "},
    {'G', " ### "
          "#   #"
          "#    "
          "# ###"
          "#   #"
          "#   #"
          " ####"},
    {'H', "#   #"
          "#   #"
          "#   #"
          "#####"
          "#   #"
          "#   #"
          "#   #"},
    {'I', " ### "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          " ### "},
    {'J', "  ###"
          "   # "
          "   # "
          "   # "
          "   # "
          "#  # "
          " ##  "},
    {'K', "#   #"
          "#  # "
          "# #  "
          "##   "
          "# #  "
          "#  # "
          "#   #"},
    {'L', "#    "
          "#    "
          "#    "
          "#    "
          "#    "
          "#    "
          "#####"},
    {'M', "#   #"
          "## ##"
          "# # #"
          "# # #"
          "#   #"
          "#   #"
          "#   #"},
    {'N', "#   #"
          "#   #"
          "##  #"
          "# # #"
          "#  ##"
          "#   #"
          "#   #"},
    {'O', " ### "
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          " ### "},
    {'P', "#### "
          "#   #"
          "#   #"
          "#### "
          "#    "
          "#    "
          "#    "},
    {'Q', " ### "
          "#   #"
          "#   #"
          "#   #"
          "# # #"
          "#  # "
          " ## #"},
    {'R', "#### "
          "#   #"
          "#   #"
          "#### "
          "# #  "
          "#  # "
          "#   #"},
    {'S', " ####"
          "#    "
          "#    "
          " ### "
          "    #"
          "    #"
          "#### "},
    {'T', "#####"
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "},
    {'U', "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          " ### "},
    {'V', "#   #"
          "#   #"
          "#   #"
          "#   #"
          "#   #"
          " # # "
          "  #  "},
    {'W', "#   #"
          "#   #"
          "#   #"
          "# # #"
          "# # #"
          "# # #"
          " # # "},
    {'X', "#   #"
          "#   #"
          " # # "
          "  #  "
          " # # "
          "#   #"
          "#   #"},
    {'Y', "#   #"
          "#   #"
          " # # "
          "  #  "
          "  #  "
          "  #  "
          "  #  "},
    {'Z', "#####"
          "    #"
          "   # "
          "  #  "
          " #   "
          "#    "
          "#####"},
    {'0', " ### "
          "#   #"
          "#  ##"
          "# # #"
          "##  #"
          "#   #"
          " ### "},
    {'1', "  #  "
          " ##  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          " ### "},
    {'2', " ### "
          "#   #"
          "    #"
          "   # "
          "  #  "
          " #   "
          "#####"},
    {'3', "#####"
          "   # "
          "  #  "
          "   # "
          "    #"
          "#   #"
          " ### "},
    {'4', "   # "
          "  ## "
          " # # "
          "#  # "
          "#####"
          "   # "
          "   # "},
    {'5', "#####"
          "#    "
          "#### "
          "    #"
          "    #"
          "#   #"
          " ### "},
    {'6', "  ## "
          " #   "
          "#    "
          "#### "
          "#   #"
          "#   #"
          " ### "},
    {'7', "#####"
          "    #"
          "   # "
          "  #  "
          " #   "
          " #   "
          " #   "},
    {'8', " ### "
          "#   #"
          "#   #"
          " ### "
          "#   #"
          "#   #"
          " ### "},
    {'9', " ### "
          "#   #"
          "#   #"
          " ####"
          "    #"
          "   # "
          " ##  "},
    {'.', "     "
          "     "
          "     "
          "     "
          "     "
          " ##  "
          " ##  "},
    {',', "     "
          "     "
          "     "
          "     "
          " ##  "
          "  #  "
          " #   "},
    {':', "     "
          " ##  "
          " ##  "
          "     "
          " ##  "
          " ##  "
          "     "},
    {';', "     "
          " ##  "
          " ##  "
          "     "
          " ##  "
          "  #  "
          " #   "},
    {'-', "     "
          "     "
          "     "
          "#####"
          "     "
          "     "
          "     "},
    {'+', "     "
          "  #  "
          "  #  "
          "#####"
          "  #  "
          "  #  "
          "     "},
    {'=', "     "
          "     "
          "#####"
          "     "
          "#####"
          "     "
          "     "},
    {'/', "     "
          "    #"
          "   # "
          "  #  "
          " #   "
          "#    "
          "     "},
    {'_', "     "
          "     "
          "     "
          "     "
          "     "
          "     "
          "#####"},
    {'%', "##   "
          "##  #"
          "   # "
          "  #  "
          " #   "
          "#  ##"
          "   ##"},
    {'(', "   # "
          "  #  "
          " #   "
          " #   "
          " #   "
          "  #  "
          "   # "},
    {')', " #   "
          "  #  "
          "   # "
          "   # "
          "   # "
          "  #  "
          " #   "},
    {'[', " ### "
          " #   "
          " #   "
          " #   "
          " #   "
          " #   "
          " ### "},
    {']', " ### "
          "   # "
          "   # "
          "   # "
          "   # "
          "   # "
          " ### "},
    {'<', "   # "
          "  #  "
          " #   "
          "#    "
          " #   "
          "  #  "
          "   # "},
    {'>', " #   "
          "  #  "
          "   # "
          "    #"
          "   # "
          "  #  "
          " #   "},
    {'!', "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "     "
          "  #  "},
    {'?', " ### "
          "#   #"
          "    #"
          "   # "
          "  #  "
          "     "
          "  #  "},
    {'\'', "  #  "
           "  #  "
           " #   "
           "     "
           "     "
           "     "
           "     "},
    {'"', " # # "
          " # # "
          "     "
          "     "
          "     "
          "     "
          "     "},
    {'*', "     "
          "  #  "
          "# # #"
          " ### "
          "# # #"
          "  #  "
          "     "},
    {'#', " # # "
          " # # "
          "#####"
          " # # "
          "#####"
          " # # "
          " # # "},
    {'|', "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "
          "  #  "},
    {'@', " ### "
          "#   #"
          "# ###"
          "# # #"
          "# ###"
          "#    "
          " ####"},
};

static const char *glyph_rows(int c) {
  c = toupper((unsigned char)c);
  const char *fallback = NULL;
  for (size_t i = 0; i < sizeof glyphs / sizeof glyphs[0]; i++) {
    if (glyphs[i].c == c)
      return glyphs[i].rows;
    if (glyphs[i].c == '?')
      fallback = glyphs[i].rows;
  }
  return fallback;
}

int view_text_width(const char *text, int scale) {
  int n = 0;
  for (const char *p = text; *p; p++)
    n++;
  return n * (VIEW_GLYPH_W + 1) * scale;
}

void view_draw_text(uint8_t *rgb, int width, int height, int x, int y,
                    const char *text, int scale, const uint8_t colour[3]) {
  for (const char *p = text; *p; p++, x += (VIEW_GLYPH_W + 1) * scale) {
    const char *rows = glyph_rows(*p);
    for (int gy = 0; gy < VIEW_GLYPH_H; gy++)
      for (int gx = 0; gx < VIEW_GLYPH_W; gx++) {
        if (rows[gy * VIEW_GLYPH_W + gx] != '#')
          continue;
        for (int sy = 0; sy < scale; sy++)
          for (int sx = 0; sx < scale; sx++) {
            int px = x + gx * scale + sx, py = y + gy * scale + sy;
            if (px < 0 || py < 0 || px >= width || py >= height)
              continue;
            uint8_t *d = rgb + ((size_t)py * (size_t)width + (size_t)px) * 3;
            d[0] = colour[0];
            d[1] = colour[1];
            d[2] = colour[2];
          }
      }
  }
}

void view_shade_box(uint8_t *rgb, int width, int height, int x0, int y0, int x1,
                    int y1) {
  for (int y = y0 < 0 ? 0 : y0; y < y1 && y < height; y++)
    for (int x = x0 < 0 ? 0 : x0; x < x1 && x < width; x++) {
      uint8_t *d = rgb + ((size_t)y * (size_t)width + (size_t)x) * 3;
      d[0] = (uint8_t)(d[0] / 3);
      d[1] = (uint8_t)(d[1] / 3);
      d[2] = (uint8_t)(d[2] / 3);
    }
}

/* x11_capture WINDOW FILE.ppm: a window's pixels as the X server holds them
 * (XGetImage), written as an 8-bit binary PPM, for tests/view.sh to compare
 * the screen with glint render's image. The colour channels come from the
 * window's visual's masks, whatever its byte order. */
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <stdio.h>
#include <stdlib.h>

/* The channel `mask` selects from `pixel`, scaled to 0..255. */
static int channel(unsigned long pixel, unsigned long mask) {
  if (!mask)
    return 0;
  int shift = 0;
  while (!((mask >> shift) & 1))
    shift++;
  unsigned long max = mask >> shift;
  return (int)(((pixel & mask) >> shift) * 255 / max);
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: x11_capture WINDOW FILE.ppm\n");
    return 2;
  }
  Display *d = XOpenDisplay(NULL);
  if (!d) {
    fprintf(stderr, "x11_capture: cannot open the display\n");
    return 1;
  }
  Window w = (Window)strtoul(argv[1], NULL, 0);
  XWindowAttributes a;
  if (!XGetWindowAttributes(d, w, &a)) {
    fprintf(stderr, "x11_capture: no window %s\n", argv[1]);
    return 1;
  }
  XImage *im = XGetImage(d, w, 0, 0, (unsigned)a.width, (unsigned)a.height,
                         AllPlanes, ZPixmap);
  FILE *f = fopen(argv[2], "wb");
  if (!im || !f) {
    fprintf(stderr, "x11_capture: cannot capture %s into %s\n", argv[1],
            argv[2]);
    return 1;
  }
  fprintf(f, "P6\n%d %d\n255\n", a.width, a.height);
  for (int y = 0; y < a.height; y++)
    for (int x = 0; x < a.width; x++) {
      unsigned long p = XGetPixel(im, x, y);
      fputc(channel(p, a.visual->red_mask), f);
      fputc(channel(p, a.visual->green_mask), f);
      fputc(channel(p, a.visual->blue_mask), f);
    }
  XDestroyImage(im);
  XCloseDisplay(d);
  return fclose(f) == 0 ? 0 : 1;
}

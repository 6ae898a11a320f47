/* Numbers in scene and mesh files: decimal text to double, correctly
 * rounded, always with '.' as the decimal point. */
#ifndef GLINT_SCENE_NUMBER_H
#define GLINT_SCENE_NUMBER_H

#include <locale.h>
#include <stddef.h>

enum { NUMBER_OK = 0, NUMBER_BAD = -1, NUMBER_NOT_FINITE = -2 };

/* The len characters at t, all of them, as a finite number: NUMBER_OK,
 * NUMBER_BAD if they are not a number as strtod reads one, or
 * NUMBER_NOT_FINITE (inf, nan, or too large for a double). The character at
 * t[len] must not continue a number (a blank, a newline, '#' or NUL). */
int gli_number_parse(const char *t, size_t len, double *out);

/* Makes strtod read '.' on this thread whatever LC_NUMERIC the host program
 * chose, until gli_number_locale_end; loaders bracket their parsing with it. */
typedef struct number_locale {
  locale_t c, old;
} number_locale;
number_locale gli_number_locale_begin(void);
void gli_number_locale_end(number_locale l);

#endif

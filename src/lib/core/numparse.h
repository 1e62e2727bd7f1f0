/* numparse.h - exact, fast parsing of decimal numbers in text formats.
 *
 * fct_parse_double gives exactly the value strtod gives (in the C locale) for
 * every input: the common short decimals take a fast exact path (Clinger:
 * a mantissa below 2^53 scaled by an exact power of ten below 10^23 is one
 * correctly rounded IEEE operation); everything else is handed to strtod. */
#ifndef FCT_NUMPARSE_H
#define FCT_NUMPARSE_H

#include <stddef.h>
#include <stdint.h>

/* Parse a number at s (leading blanks are not skipped).  Returns the first
 * character after it, or NULL when s does not start with a number. */
const char *fct_parse_double(const char *s, double *out);

/* Parse an optionally signed decimal integer in [INT64_MIN, INT64_MAX];
 * NULL when there is no integer or it overflows. */
const char *fct_parse_int64(const char *s, int64_t *out);

/* The shortest "%g" form of v (6 to 9 significant digits for a float, 15 to
 * 17 for a double) that fct_parse_double reads back to the same value, so
 * text output keeps what was read ("0.5", not "0.500000000").  Writes at
 * most n bytes (n >= 32 is enough) and returns the length. */
int fct_format_float(char *buf, size_t n, float v);
int fct_format_double(char *buf, size_t n, double v);

#endif

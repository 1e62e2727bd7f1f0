/* numparse.h - exact, fast parsing of decimal numbers in text formats.
 *
 * fct_parse_double gives exactly the value strtod gives (in the C locale) for
 * every input: the common short decimals take a fast exact path (Clinger:
 * a mantissa below 2^53 scaled by an exact power of ten below 10^23 is one
 * correctly rounded IEEE operation); everything else is handed to strtod. */
#ifndef FCT_NUMPARSE_H
#define FCT_NUMPARSE_H

#include <stdint.h>

/* Parse a number at s (leading blanks are not skipped).  Returns the first
 * character after it, or NULL when s does not start with a number. */
const char *fct_parse_double(const char *s, double *out);

/* Parse an optionally signed decimal integer in [INT64_MIN, INT64_MAX];
 * NULL when there is no integer or it overflows. */
const char *fct_parse_int64(const char *s, int64_t *out);

#endif

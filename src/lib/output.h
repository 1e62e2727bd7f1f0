/* output.h - atomic output files.
 *
 * A named output is written to a temporary file in the same folder and
 * renamed over the name only when everything was written, so a failed run
 * never leaves a half-written file.  "-" or NULL means stdout.  A name that
 * is not a regular file (/dev/null, a FIFO, a terminal) is written directly:
 * renaming over it would replace the device with a file. */
#ifndef FCT_OUTPUT_H
#define FCT_OUTPUT_H

#include <stdio.h>

#include "err.h"

struct fct_out {
	FILE *f;
	char *path;   /* NULL for stdout */
	char *tmp;    /* the temporary file; NULL when writing path directly */
};

int fct_out_open(struct fct_out *o, const char *path, struct fct_err *err);
/* Flush, check and move into place; closes o in all cases. */
int fct_out_commit(struct fct_out *o, struct fct_err *err);
/* Discard a named output's temporary file; closes o.  Safe after commit. */
void fct_out_abort(struct fct_out *o);

#endif

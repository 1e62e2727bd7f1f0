/* output.h - atomic output files.
 *
 * A named output is written to a temporary file in the same folder and
 * renamed over the name only when everything was written, so a failed run
 * never leaves a half-written file.  "-" or NULL means stdout.  A name that
 * is not a regular file (/dev/null, a FIFO, a terminal) is written directly:
 * renaming over it would replace the device with a file.
 *
 * The temporary file is hidden beside the output, ".NAME.XXXXXX" (NAME cut
 * to 247 bytes, so that a legal 255-byte name works), and removed by
 * fct_out_remove_temporaries if the program is killed (cli.c calls it from
 * its handler of SIGINT, SIGTERM, SIGHUP, SIGPIPE and SIGXFSZ). */
#ifndef FCT_OUTPUT_H
#define FCT_OUTPUT_H

#include <stdio.h>

#include "core/err.h"

struct fct_out {
	FILE *f;
	char *path;   /* NULL for stdout */
	char *tmp;    /* the temporary file; NULL when writing path directly */
};

int fct_out_open(struct fct_out *o, const char *path, struct fct_err *err);
/* Flush, check and move into place; closes o in all cases.  Every failure
 * sets err ("<stdout>: write error: Broken pipe" for a closed pipe). */
int fct_out_commit(struct fct_out *o, struct fct_err *err);
/* Discard a named output's temporary file; closes o.  Safe after commit. */
void fct_out_abort(struct fct_out *o);
/* Unlink the temporary file of every output open now (not closed by
 * commit or abort).  Async-signal-safe: for a handler of a fatal signal. */
void fct_out_remove_temporaries(void);

#endif

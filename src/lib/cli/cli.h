/* cli.h - what every facet program does the same way: its name in messages,
 * the exit convention, numeric options, progress and the -v figures.
 *
 * This is the one part of the library that prints and exits; only mains
 * (src/cmd, tools) use it.  Exit status: 0 success, 1 bad data or I/O,
 * 2 usage. */
#ifndef FCT_CLI_H
#define FCT_CLI_H

#include "core/clock.h"   /* fct_now, fct_cpu_time: every -v figure reads them */

#include "io/camera.h"
#include "io/image.h"

#include "core/err.h"

#define FCT_VERSION "0.1.0"

extern const char *fct_prog;

/* Record the program name (for messages), set up stdout buffering, and
 * catch SIGINT, SIGTERM, SIGHUP, SIGXFSZ (unless ignored) and SIGPIPE: the
 * program dies of them, quietly, after removing its outputs' temporary
 * files (output.h). */
void fct_cli_init(const char *prog);

/* Every message below is one line: control characters in it (a file name
 * with a newline) are escaped as \n, \r, \t or \xHH.
 *
 * "prog: message" on stderr, for a program that goes on (or exits itself). */
void fct_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* "prog: message" on stderr and exit with status. */
_Noreturn void fct_die(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* "prog: err->msg" and exit 1. */
_Noreturn void fct_die_err(const struct fct_err *err);
/* "prog: WHERE: err->msg" and exit 1, WHERE made of fmt: the library's
 * error reported with the file or stage it happened in. */
_Noreturn void fct_die_err_at(struct fct_err *err, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));
/* "prog: warning: message" (suppressed by fct_quiet). */
void fct_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* "prog: usage message", exit 2. */
_Noreturn void fct_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* After getopt/getopt_long returned '?': "prog: -x: unknown option" or
 * "prog: -x: option requires an argument", exit 2. */
_Noreturn void fct_bad_option(const char *optstring, char **argv);
/* The one operand a filter takes after its options: argv[optind], or
 * absent when there is none; more than one is "too many operands", exit 2. */
const char *fct_one_operand(int argc, char **argv, int optind, const char *absent);

extern int fct_quiet;    /* -q: no warnings, no progress */
extern int fct_verbose;  /* -v: progress and figures */

/* Numeric option arguments, checked: "prog: -t: "0,01" is not a number",
 * or "... must be in [lo, hi]"; exit 2 on error. */
double fct_opt_double(const char *opt, const char *arg, double lo, double hi);
long fct_opt_long(const char *opt, const char *arg, long lo, long hi);
/* A comma-separated list of exactly n numbers ("-K fx,fy,cx,cy"). */
void fct_opt_doubles(const char *opt, const char *arg, double *v, int n);

/* --cylindrical "f,cy,theta0" (f and cy may be empty) for an image of
 * width x height: sets cam's kind, f (default width / 2 pi), cy (default
 * (height - 1) / 2) and theta0; exit 2 when malformed or f is not
 * positive. */
void fct_opt_cylindrical(const char *arg, int width, int height, struct fct_camera *cam);

/* The camera of -K arg (fx,fy,cx,cy, or a dataset name of
 * fct_camera_named) or of --camera file (fct_camera_read_stereo): cam (kind
 * NONE when both are NULL), *named_scale (may be NULL) the named dataset's
 * depth units per metre or 0, stereo (may be NULL) a stereo calibration's
 * baseline and doffs.  Exit 2 when both are given or -K is malformed (a -K
 * that names a file says to give it with --camera); exit 1 on a bad file. */
void fct_opt_camera(struct fct_camera *cam, double *named_scale, struct fct_stereo *stereo,
                    const char *K, const char *file);

/* Write img to path atomically (output.h): PFM when it holds floats, else
 * PNG; exit 1 with the path in the message on failure. */
void fct_write_image_or_die(const struct fct_image *img, const char *path);

/* Write text to path atomically (output.h); exit 1 on failure. */
void fct_write_text_or_die(const char *text, const char *path);


/* Progress on stderr for long work, with -v or when stderr is a terminal
 * (never with -q); redrawn at most a few times a second. */
struct fct_progress {
	const char *what;
	double start, last;
	int on, drawn;
};
void fct_progress_start(struct fct_progress *p, const char *what);
void fct_progress_update(struct fct_progress *p, double done, double total);
void fct_progress_end(struct fct_progress *p);

/* With -v: one figure as "prog: key=value" on stderr. */
void fct_report(const char *key, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* With -v: a figure of one stage of several, "prog: STAGE: key=value". */
void fct_report_stage(const char *stage, const char *key, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* The folder dir, made when missing; exit 1 with "opt: dir: why" ("dir:
 * why" when opt is NULL) when it cannot be. */
void fct_make_folder(const char *opt, const char *dir);

#endif

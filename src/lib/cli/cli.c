/* cli.c - messages, exits, numeric options, progress (see cli.h). */
#include "cli/cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "core/numparse.h"
#include "io/output.h"
#include "io/reader.h"

const char *fct_prog = "facet";
int fct_quiet, fct_verbose;

/* Killed while writing: remove the hidden temporary files of -o (so that
 * an interrupted run leaves nothing behind), then die of the same signal
 * (SA_RESETHAND restored its default action; it is delivered on return). */
static void on_fatal_signal(int sig)
{
	fct_out_remove_temporaries();
	raise(sig);
}

/* SIGINT, SIGTERM, SIGHUP and SIGXFSZ clean up before the program dies,
 * unless the parent ignores them (nohup, background jobs), which stays so.
 * SIGPIPE is caught whatever the parent did with it: a closed pipe ends the
 * program quietly, the Unix way, never with a write error on every stage of
 * a pipeline whose reader went away. */
static void catch_fatal_signals(void)
{
	static const int sigs[] = { SIGINT, SIGTERM, SIGHUP, SIGXFSZ, SIGPIPE };
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_fatal_signal;
	sa.sa_flags = SA_RESETHAND;
	sigemptyset(&sa.sa_mask);
	for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
		struct sigaction old;
		if (sigs[i] != SIGPIPE && sigaction(sigs[i], NULL, &old) == 0 &&
		    old.sa_handler == SIG_IGN)
			continue;
		sigaction(sigs[i], &sa, NULL);
	}
	sigset_t pipe;
	sigemptyset(&pipe);
	sigaddset(&pipe, SIGPIPE);
	sigprocmask(SIG_UNBLOCK, &pipe, NULL);
}

/* The stages allocate and free arrays the size of the mesh again and again
 * (an adjacency, a face list, a copy of the positions).  By default glibc
 * hands such blocks back to the kernel when freed (each from a mapping of
 * its own, or the top of the heap trimmed), and the next array's every
 * page is faulted and zeroed anew: a tenth of planedecim's time on a
 * 640x480 frame.  A command runs once and exits, so it keeps what it freed
 * for its next array.  The peak rises a little with the blocks the heap
 * keeps apart (planarize on a 7-Scenes frame 154 -> 163 MB, segplanes on
 * 1M faces 232 -> 236 bytes a face). */
static void keep_freed_memory(void)
{
#ifdef __GLIBC__
	mallopt(M_MMAP_THRESHOLD, 32 << 20);  /* glibc's largest */
	mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

void fct_cli_init(const char *prog)
{
	fct_prog = prog;
	opterr = 0;  /* fct_bad_option says it in one line */
	/* A large buffer makes stdout writes block-sized even on pipes. */
	static char outbuf[1 << 16];
	setvbuf(stdout, outbuf, _IOFBF, sizeof outbuf);
	fct_pipe_widen(STDOUT_FILENO);
	catch_fatal_signals();
	keep_freed_memory();
}

/* "prog: TAG TEXT" and a newline on stderr in one write, with the control
 * characters of text escaped (\n, \r, \t, \xHH): a file name holding a
 * newline must not make a message two lines. */
static void put_message(const char *tag, const char *text)
{
	char line[4 * 2048 + 256];
	int n = snprintf(line, sizeof line - 8, "%s: %s", fct_prog, tag);
	size_t at = n < 0 ? 0 : (size_t)n < sizeof line - 8 ? (size_t)n : sizeof line - 8;
	for (const unsigned char *p = (const unsigned char *)text; *p && at < sizeof line - 8; p++) {
		if (*p >= 0x20 && *p != 0x7f)
			line[at++] = (char)*p;
		else if (*p == '\n' || *p == '\r' || *p == '\t')
			line[at++] = '\\', line[at++] = *p == '\n' ? 'n' : *p == '\r' ? 'r' : 't';
		else
			at += (size_t)snprintf(line + at, 5, "\\x%02x", *p);
	}
	line[at++] = '\n';
	fwrite(line, 1, at, stderr);
}

static void vmessage(const char *tag, const char *fmt, va_list ap)
{
	char buf[2048];
	vsnprintf(buf, sizeof buf, fmt, ap);
	put_message(tag, buf);
}

void fct_error(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vmessage("", fmt, ap);
	va_end(ap);
}

void fct_die(int status, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vmessage("", fmt, ap);
	va_end(ap);
	exit(status);
}

void fct_die_err(const struct fct_err *err)
{
	put_message("", err->msg);
	exit(1);
}

void fct_die_err_at(struct fct_err *err, const char *fmt, ...)
{
	char where[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(where, sizeof where, fmt, ap);
	va_end(ap);
	fct_err_prefix(err, "%s", where);
	fct_die_err(err);
}

void fct_warn(const char *fmt, ...)
{
	if (fct_quiet)
		return;
	va_list ap;
	va_start(ap, fmt);
	vmessage("warning: ", fmt, ap);
	va_end(ap);
}

void fct_usage_error(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vmessage("", fmt, ap);
	va_end(ap);
	exit(2);
}

void fct_bad_option(const char *optstring, char **argv)
{
	const char *word = argv[optind - 1];
	if (!strncmp(word, "--", 2)) {  /* a long option: name it as given */
		const char *eq = strchr(word, '=');
		if (eq)
			fct_usage_error("%.*s: unknown option, or it takes no argument", (int)(eq - word), word);
		fct_usage_error("%s: unknown option, or it needs an argument", word);
	}
	const char *at = strchr(optstring, optopt);
	if (at && at[1] == ':')
		fct_usage_error("-%c: option requires an argument", optopt);
	fct_usage_error("-%c: unknown option", optopt);
}

double fct_opt_double(const char *opt, const char *arg, double lo, double hi)
{
	double v;
	const char *end = fct_parse_double(arg, &v);
	if (!end || *end || !isfinite(v))
		fct_usage_error("%s: \"%s\" is not a number", opt, arg);
	if (v < lo || v > hi)
		fct_usage_error("%s: %s must be in [%g, %g]", opt, arg, lo, hi);
	return v;
}

long fct_opt_long(const char *opt, const char *arg, long lo, long hi)
{
	int64_t v;
	const char *end = fct_parse_int64(arg, &v);
	if (!end || *end)
		fct_usage_error("%s: \"%s\" is not an integer", opt, arg);
	if (v < lo || v > hi)
		fct_usage_error("%s: %s must be in [%ld, %ld]", opt, arg, lo, hi);
	return (long)v;
}

void fct_opt_doubles(const char *opt, const char *arg, double *v, int n)
{
	const char *s = arg;
	for (int i = 0; i < n; i++) {
		const char *end = fct_parse_double(s, &v[i]);
		if (!end || !isfinite(v[i]) || (i < n - 1 ? *end != ',' : *end != 0))
			fct_usage_error("%s: \"%s\" is not %d comma-separated numbers", opt, arg, n);
		s = end + 1;
	}
}

void fct_opt_cylindrical(const char *arg, int width, int height, struct fct_camera *cam)
{
	double v[3];
	const char *s = arg;
	for (int k = 0; k < 3; k++) {
		const char *e = strchr(s, ',');
		size_t n = e ? (size_t)(e - s) : strlen(s);
		if ((k < 2 && !e) || (k == 2 && e))
			fct_usage_error("--cylindrical: expected f,cy,theta0");
		char buf[64];
		if (n >= sizeof buf)
			fct_usage_error("--cylindrical: \"%s\" is not a number", s);
		memcpy(buf, s, n);
		buf[n] = 0;
		v[k] = n == 0 && k < 2 ? NAN : fct_opt_double("--cylindrical", buf, -1e300, 1e300);
		s = e ? e + 1 : s;
	}
	if (!isnan(v[0]) && !(v[0] > 0))
		fct_usage_error("--cylindrical: f must be positive");
	cam->kind = FCT_CAMERA_CYLINDRICAL;
	cam->f = isnan(v[0]) ? width / (2 * M_PI) : v[0];
	cam->cy = isnan(v[1]) ? (height - 1) / 2.0 : v[1];
	cam->theta0 = v[2];
}

void fct_opt_camera(struct fct_camera *cam, double *named_scale, struct fct_stereo *stereo,
                    const char *K, const char *file)
{
	struct fct_err err;
	struct stat sb;
	double k[4], scale = 0;
	memset(cam, 0, sizeof *cam);
	if (stereo)
		stereo->baseline = stereo->doffs = 0;
	if (K && file)
		fct_usage_error("-K and --camera exclude each other");
	if (file && fct_camera_read_stereo(cam, stereo, file, &err))
		fct_die_err(&err);
	if (K && fct_camera_named(K, cam, &scale)) {
		if (!strchr(K, ',') && stat(K, &sb) == 0 && S_ISREG(sb.st_mode))
			fct_usage_error("-K: \"%s\" is a file: give an intrinsics file with --camera "
			                "(Open3D JSON, a 3x3 K, a camera line, Middlebury calib.txt)", K);
		if (!strchr(K, ','))
			fct_usage_error("-K: \"%s\" is neither fx,fy,cx,cy nor a camera name (%s)", K,
			                fct_camera_names());
		fct_opt_doubles("-K", K, k, 4);
		if (!(k[0] > 0 && k[1] > 0))
			fct_usage_error("-K: focal lengths must be positive");
		cam->kind = FCT_CAMERA_PINHOLE;
		cam->fx = k[0], cam->fy = k[1], cam->cx = k[2], cam->cy = k[3];
	}
	if (named_scale)
		*named_scale = scale;
}

void fct_write_image_or_die(const struct fct_image *img, const char *path)
{
	struct fct_out o;
	struct fct_err err;
	if (fct_out_open(&o, path, &err))
		fct_die_err(&err);
	int rc = img->type == FCT_PIX_F32 ? fct_pfm_write(img, o.f, &err) : fct_png_write(img, o.f, &err);
	if (rc) {
		fct_out_abort(&o);
		fct_err_prefix(&err, "%s", path);
		fct_die_err(&err);
	}
	if (fct_out_commit(&o, &err))
		fct_die_err(&err);
}

void fct_write_text_or_die(const char *text, const char *path)
{
	struct fct_out o;
	struct fct_err err;
	if (fct_out_open(&o, path, &err))
		fct_die_err(&err);
	fputs(text, o.f);
	if (fct_out_commit(&o, &err))
		fct_die_err(&err);
}

void fct_progress_start(struct fct_progress *p, const char *what)
{
	p->what = what;
	p->start = p->last = fct_now();
	p->on = !fct_quiet && (fct_verbose || isatty(STDERR_FILENO));
	p->drawn = 0;
}

void fct_progress_update(struct fct_progress *p, double done, double total)
{
	if (!p->on)
		return;
	double t = fct_now();
	/* Quiet for the first second, then a few redraws a second. */
	if (t - p->start < 1.0 || t - p->last < 0.25)
		return;
	p->last = t;
	p->drawn = 1;
	if (total > 0)
		fprintf(stderr, "\r%s: %s %3.0f%%", fct_prog, p->what, 100.0 * done / total);
	else
		fprintf(stderr, "\r%s: %s %.0f", fct_prog, p->what, done);
}

void fct_progress_end(struct fct_progress *p)
{
	if (p->on && p->drawn)
		fprintf(stderr, "\r%s: %s done in %.1f s\n", fct_prog, p->what, fct_now() - p->start);
	p->drawn = 0;
}

void fct_report(const char *key, const char *fmt, ...)
{
	if (!fct_verbose)
		return;
	char buf[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(buf, sizeof buf, fmt, ap);
	va_end(ap);
	fprintf(stderr, "%s: %s=%s\n", fct_prog, key, buf);
}

void fct_report_stage(const char *stage, const char *key, const char *fmt, ...)
{
	if (!fct_verbose)
		return;
	char k[64], v[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(v, sizeof v, fmt, ap);
	va_end(ap);
	snprintf(k, sizeof k, "%s: %s", stage, key);
	fct_report(k, "%s", v);
}

void fct_make_folder(const char *opt, const char *dir)
{
	struct stat sb;
	if (mkdir(dir, 0777) == 0)
		return;
	if (errno == EEXIST && stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode))
		return;
	const char *why = errno == EEXIST ? "exists and is not a folder" : strerror(errno);
	if (opt)
		fct_die(1, "%s: %s: %s", opt, dir, why);
	fct_die(1, "%s: %s", dir, why);
}

const char *fct_one_operand(int argc, char **argv, int optind, const char *absent)
{
	if (argc - optind > 1)
		fct_usage_error("too many operands");
	return optind < argc ? argv[optind] : absent;
}

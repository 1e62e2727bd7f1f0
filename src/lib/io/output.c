/* output.c - write to a temporary file and rename on success (see output.h). */
#include "io/output.h"

#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/path.h"

/* The longest file name most file systems take (NAME_MAX on Linux). */
enum { NAME_BYTES = 255, MAX_TEMPORARIES = 64 };

/* The temporary files of the outputs open now, for
 * fct_out_remove_temporaries, which a signal handler calls: a slot is set
 * once its file exists and cleared before its path is freed, by lock-free
 * atomic stores, the only writes a handler may see half done. */
static _Atomic(char *) temporaries[MAX_TEMPORARIES];

static void remember_temporary(char *path)
{
	for (int i = 0; i < MAX_TEMPORARIES; i++) {
		char *none = NULL;
		if (atomic_compare_exchange_strong(&temporaries[i], &none, path))
			return;
	}
	/* More outputs open at once than slots: this one is not cleaned up
	 * on a signal (no program opens more than a few). */
}

static void forget_temporary(const char *path)
{
	for (int i = 0; i < MAX_TEMPORARIES; i++)
		if (atomic_load(&temporaries[i]) == path)
			atomic_store(&temporaries[i], NULL);
}

void fct_out_remove_temporaries(void)
{
	for (int i = 0; i < MAX_TEMPORARIES; i++) {
		char *p = atomic_load(&temporaries[i]);
		if (p)
			unlink(p);
	}
}

int fct_out_open(struct fct_out *o, const char *path, struct fct_err *err)
{
	memset(o, 0, sizeof *o);
	if (fct_path_is_std(path)) {
		o->f = stdout;
		return 0;
	}
	struct stat st;
	if (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
		if (!(o->path = fct_strdup(path, err)))
			return -1;
		if (!(o->f = fopen(path, "wb"))) {
			int e = errno;
			fct_out_abort(o);
			return fct_fail(err, "%s: %s", path, strerror(e));
		}
		return 0;
	}
	char *dir = fct_path_dir(path, err);
	if (!dir)
		return -1;
	const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
	/* ".NAME.XXXXXX" adds 8 bytes: a legal name of over 247 bytes is cut
	 * short in its temporary name (mkstemp keeps that one unique). */
	int keep = strlen(base) > NAME_BYTES - 8 ? NAME_BYTES - 8 : (int)strlen(base);
	size_t n = strlen(dir) + strlen(base) + 16;
	o->tmp = malloc(n);
	o->path = fct_strdup(path, err);
	if (!o->tmp || !o->path) {
		free(dir);
		fct_out_abort(o);
		return fct_fail(err, "out of memory");
	}
	snprintf(o->tmp, n, "%s/.%.*s.XXXXXX", dir, keep, base);
	free(dir);
	/* Signals wait while the file is made and remembered: killed between
	 * the two, a program left its temporary behind (a test that kills as
	 * soon as the file shows caught it there under load). */
	sigset_t all, before;
	sigfillset(&all);
	sigprocmask(SIG_BLOCK, &all, &before);
	int fd = mkstemp(o->tmp);
	int e = errno;
	if (fd >= 0)
		remember_temporary(o->tmp);
	sigprocmask(SIG_SETMASK, &before, NULL);
	if (fd < 0) {
		free(o->tmp);
		o->tmp = NULL;
		fct_out_abort(o);
		return fct_fail(err, "%s: %s", path, strerror(e));
	}
	/* mkstemp makes 0600; give the file the permissions a plain create would. */
	mode_t mask = umask(0);
	umask(mask);
	fchmod(fd, 0666 & ~mask);
	if (!(o->f = fdopen(fd, "wb"))) {
		close(fd);
		fct_out_abort(o);
		return fct_fail(err, "%s: %s", path, strerror(errno));
	}
	return 0;
}

int fct_out_commit(struct fct_out *o, struct fct_err *err)
{
	if (!o->f)
		return fct_fail(err, "output already closed");
	if (!o->path) {
		errno = 0;
		int bad = fflush(stdout) != 0 || ferror(stdout);
		int e = errno;
		o->f = NULL;
		/* EPIPE included: a closed pipe ends a program by SIGPIPE (cli.c), so
		 * this is seen only by a caller that blocks or ignores it. */
		if (bad)
			return fct_fail(err, "<stdout>: write error: %s", strerror(e ? e : EIO));
		return 0;
	}
	int bad = fflush(o->f) != 0 || ferror(o->f);
	int e = errno;
	if (fclose(o->f) != 0 && !bad)
		bad = 1, e = errno;
	o->f = NULL;
	if (bad) {
		fct_fail(err, "%s: write error: %s", o->path, strerror(e ? e : EIO));
		fct_out_abort(o);
		return -1;
	}
	if (o->tmp && rename(o->tmp, o->path) != 0) {
		fct_fail(err, "%s: %s", o->path, strerror(errno));
		fct_out_abort(o);
		return -1;
	}
	forget_temporary(o->tmp);
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
	return 0;
}

void fct_out_abort(struct fct_out *o)
{
	if (o->f && o->f != stdout)
		fclose(o->f);
	o->f = NULL;
	if (o->tmp) {
		unlink(o->tmp);
		forget_temporary(o->tmp);
	}
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
}

/* reader.c - forward-only buffered input (see reader.h). */
#include "io/reader.h"

#define _GNU_SOURCE 1  /* F_SETPIPE_SZ */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { BLOCK = 1 << 20, MAX_LINE = 16 << 20 };

void fct_pipe_widen(int fd)
{
#ifdef F_SETPIPE_SZ
	struct stat st;
	/* A 64 KiB pipe makes both ends switch for every 64 KiB; 1 MiB halves the cost
	 * of a pass-through.  Refusal (over the user's limit) is harmless. */
	if (fd >= 0 && fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode))
		fcntl(fd, F_SETPIPE_SZ, 1 << 20);
#else
	(void)fd;
#endif
}

int fct_reader_open(struct fct_reader *r, const char *path, struct fct_err *err)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return fct_fail(err, "%s: %s", path, strerror(errno));
	if (fct_reader_init(r, f, path, err)) {
		fclose(f);
		return -1;
	}
	return 0;
}

void fct_reader_close(struct fct_reader *r)
{
	FILE *f = r->f;
	fct_reader_free(r);
	if (f)
		fclose(f);
}

int fct_reader_init(struct fct_reader *r, FILE *f, const char *name, struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	r->f = f;
	r->name = name;
	r->cap = BLOCK;
	if (!(r->buf = malloc(r->cap + 1)))
		return fct_fail(err, "%s: out of memory", name);
	struct stat st;
	if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)) {
		long at = ftell(f);
		r->size_hint = (uint64_t)st.st_size - (uint64_t)(at > 0 ? at : 0);
	}
	fct_pipe_widen(fileno(f));
	return 0;
}

void fct_reader_free(struct fct_reader *r)
{
	free(r->buf);
	r->buf = NULL;
}

uint64_t fct_reader_remaining(const struct fct_reader *r)
{
	if (!r->size_hint)
		return UINT64_MAX;
	uint64_t at = fct_reader_offset(r);
	return at < r->size_hint ? r->size_hint - at : 0;
}

/* Move unread bytes to the front and read more, growing the buffer to hold n. */
static size_t refill(struct fct_reader *r, size_t n)
{
	if (r->pos) {
		memmove(r->buf, r->buf + r->pos, r->len - r->pos);
		r->base += r->pos;
		r->len -= r->pos;
		r->pos = 0;
	}
	if (n > r->cap) {
		size_t ncap = r->cap;
		while (ncap < n)
			ncap *= 2;
		unsigned char *nb = realloc(r->buf, ncap + 1);
		if (!nb)
			return r->len;
		r->buf = nb;
		r->cap = ncap;
	}
	while (r->len < n && !r->eof && !r->ioerr) {
		size_t got = fread(r->buf + r->len, 1, r->cap - r->len, r->f);
		r->len += got;
		if (got == 0) {
			if (ferror(r->f))
				r->ioerr = errno ? errno : EIO;
			else
				r->eof = 1;
		}
	}
	return r->len;
}

size_t fct_reader_fill(struct fct_reader *r, size_t n)
{
	if (r->len - r->pos >= n)
		return n;
	refill(r, n);
	return r->len - r->pos;
}

char *fct_reader_line(struct fct_reader *r, size_t *len, struct fct_err *err)
{
	err->msg[0] = 0;
	size_t scanned = 0;
	for (;;) {
		unsigned char *start = r->buf + r->pos;
		size_t avail = r->len - r->pos;
		unsigned char *nl = memchr(start + scanned, '\n', avail - scanned);
		if (nl || (r->eof && avail) || r->ioerr) {
			if (r->ioerr && !nl) {
				fct_reader_fail_short(r, err, "reading");
				return NULL;
			}
			size_t n = nl ? (size_t)(nl - start) : avail;
			r->pos += nl ? n + 1 : n;
			if (n && start[n - 1] == '\r')
				n--;
			start[n] = 0;  /* the buffer has one spare byte past cap */
			*len = n;
			r->line++;
			return (char *)start;
		}
		if (r->eof)
			return NULL;
		scanned = avail;
		if (avail >= MAX_LINE) {
			fct_fail(err, "%s:%llu: line longer than %d bytes", r->name,
			         (unsigned long long)r->line + 1, MAX_LINE);
			return NULL;
		}
		size_t want = avail + BLOCK;
		if (want > r->cap && want < 2 * r->cap)
			want = 2 * r->cap;
		refill(r, want);
		if (r->len - r->pos == avail && !r->eof && !r->ioerr) {
			fct_fail(err, "%s:%llu: out of memory for a long line", r->name,
			         (unsigned long long)r->line + 1);
			return NULL;
		}
	}
}

int fct_reader_fail_short(struct fct_reader *r, struct fct_err *err, const char *what)
{
	if (r->ioerr)
		return fct_fail(err, "%s: byte %llu: %s: %s", r->name,
		                (unsigned long long)fct_reader_offset(r), what, strerror(r->ioerr));
	return fct_fail(err, "%s: byte %llu: %s: unexpected end of file", r->name,
	                (unsigned long long)r->len + r->base, what);
}

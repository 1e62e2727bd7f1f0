/* reader.h - buffered, forward-only input shared by the text and binary readers.
 *
 * Never seeks, so pipes work; reads in large blocks; lets a format be detected
 * by peeking at the first bytes.  Tracks the byte offset and, for text, the
 * line number, so that errors say where they are. */
#ifndef FCT_READER_H
#define FCT_READER_H

#include <stdint.h>
#include <stdio.h>

#include "core/err.h"

struct fct_reader {
	FILE *f;
	const char *name;     /* for messages: a path or "<stdin>" */
	unsigned char *buf;
	size_t cap, pos, len;
	uint64_t base;        /* input offset of buf[0] */
	uint64_t line;        /* number of the line last returned by fct_reader_line */
	uint64_t size_hint;   /* bytes in a regular file from its start, 0 if unknown */
	int eof;              /* the FILE reported end of file */
	int ioerr;            /* the FILE reported an error */
};

/* Give a pipe on fd a larger buffer where the system allows (Linux). */
void fct_pipe_widen(int fd);

/* Set up r on f (which stays open and owned by the caller). */
int fct_reader_init(struct fct_reader *r, FILE *f, const char *name, struct fct_err *err);
void fct_reader_free(struct fct_reader *r);
/* Open path and set up r on it ("path: reason" when it cannot be opened);
 * fct_reader_close frees r and closes the file. */
int fct_reader_open(struct fct_reader *r, const char *path, struct fct_err *err);
void fct_reader_close(struct fct_reader *r);

/* Make n bytes available at r->buf + r->pos (n <= the reader's maximum block);
 * returns the number available, which is less than n only at end of input. */
size_t fct_reader_fill(struct fct_reader *r, size_t n);

/* Input offset of the next unread byte. */
static inline uint64_t fct_reader_offset(const struct fct_reader *r)
{
	return r->base + r->pos;
}

/* Bytes of input left after the next unread one, when the input is a regular
 * file; UINT64_MAX when unknown (a pipe). */
uint64_t fct_reader_remaining(const struct fct_reader *r);

/* The next line, NUL-terminated in place, without its LF or CRLF; *len gets
 * its length.  Returns NULL at end of input (err->msg empty) or on a line
 * longer than the reader's maximum or an I/O error (message set). */
char *fct_reader_line(struct fct_reader *r, size_t *len, struct fct_err *err);

/* Message for a failed read: I/O error or truncation, with the byte offset. */
int fct_reader_fail_short(struct fct_reader *r, struct fct_err *err, const char *what);

#endif

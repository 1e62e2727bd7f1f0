/* err.h - the one error convention of the library.
 *
 * Library functions never print and never exit.  A function that can fail
 * takes a `struct fct_err *` last, returns -1 (or NULL) on failure and leaves
 * one line in err->msg of the form "where: what" (no program name, no newline);
 * the program prefixes its own name and exits 1.  Internal inconsistencies
 * abort(). */
#ifndef FCT_ERR_H
#define FCT_ERR_H

#include <stddef.h>

struct fct_err {
	char msg[1024];
};

/* Format a message into err (err may be NULL) and return -1. */
int fct_fail(struct fct_err *err, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* Put "prefix: " before the message already in err (when err is not NULL). */
void fct_err_prefix(struct fct_err *err, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* Up to len bytes of s (stopping at a NUL) made fit to quote in a one-line
 * message: printable ASCII kept, every other byte as \xNN (so a binary
 * file's bytes never reach the terminal raw), cut with "..." to fit size
 * (at least 8) bytes with the terminator.  Returns buf. */
char *fct_escape(char *buf, size_t size, const char *s, size_t len);

/* Overflow-checked a*b and a+b for sizes: return 0 and store, or -1. */
int fct_mul_size(size_t a, size_t b, size_t *out);
int fct_add_size(size_t a, size_t b, size_t *out);

/* Grow *ptr (of *cap elements of size elem) to hold at least need elements,
 * doubling; returns 0, or -1 on overflow or out of memory (with a message). */
int fct_grow(void **ptr, size_t *cap, size_t need, size_t elem, struct fct_err *err);

/* fct_grow to exactly need elements, for storage whose size is known: a
 * doubled capacity would leave up to half of it never written (and its
 * pages never faulted in, so that later arrays placed there fault again). */
int fct_reserve(void **ptr, size_t *cap, size_t need, size_t elem, struct fct_err *err);

/* malloc of n elements of size elem, overflow-checked; n == 0 allocates one
 * element so that NULL always means failure (message set). */
void *fct_alloc_array(size_t n, size_t elem, struct fct_err *err);

/* fct_alloc_array for an array that is written whole once (voxgrid's
 * slabs, a depth map's per-pixel arrays and grid mesh): from 1 MB up, in
 * whole 2 MB pages aligned to them and advised for huge pages where the
 * system has them, freed with free().  The kernel faults fresh memory in
 * 4 KB at a time otherwise, about 1.3 us a page on a 2-vCPU VM: 18 MB in
 * a fresh process took 6.1 ms so and 0.8 ms in huge pages (medians of 40;
 * after 3 s idle, 2 runs of 10 each way came cold from the host, huge
 * 5.6-10 ms, 4 KB 10.8-16.9 ms).  Below 1 MB plain malloc: clearing a
 * huge page would cost more than the faults it saves.  Not for every
 * large array: with every fct_alloc_array of 4 MB or more from here,
 * marching cubes in a one-shot tsdfuse ran 10% slower (the room at 1 cm:
 * 0.118 -> 0.130 s) and fusion at 1 cm no faster. */
void *fct_alloc_big(size_t n, size_t elem, struct fct_err *err);

/* strdup that reports failure through err. */
char *fct_strdup(const char *s, struct fct_err *err);

#endif

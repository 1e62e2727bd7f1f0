/* test_par.c - par.h: every item is done once, in the chunk
 * fct_par_chunk_of names, with the same chunks for any thread count. */
#include <stdatomic.h>
#include <stdlib.h>

#include "check.h"
#include "core/par.h"

struct seen {
	size_t n, nchunk;
	int *count;          /* per item: times done */
	size_t *chunk;       /* per item: the chunk that did it */
	size_t *first;       /* per item: the first item of its chunk's call */
	atomic_int bad;      /* a chunk whose items disagree with fct_par_chunk_of */
};

static void mark(void *ctx, size_t lo, size_t hi, int worker)
{
	struct seen *s = ctx;
	(void)worker;
	size_t c = fct_par_chunk_of(s->n, s->nchunk, lo);
	for (size_t i = lo; i < hi; i++) {
		s->count[i]++;
		s->chunk[i] = c;
		s->first[i] = lo;
		if (fct_par_chunk_of(s->n, s->nchunk, i) != c)
			atomic_fetch_add(&s->bad, 1);
	}
}

static void check_case(size_t n, size_t nchunk, int nthreads)
{
	struct seen s = { n, nchunk, calloc(n + 1, sizeof(int)), calloc(n + 1, sizeof(size_t)),
	                  calloc(n + 1, sizeof(size_t)), 0 };
	fct_par_run(nthreads, n, nchunk, mark, &s);
	int once = 1, ordered = 1;
	for (size_t i = 0; i < n; i++) {
		once &= s.count[i] == 1;
		if (i > 0)   /* chunks are consecutive runs, indices ascending */
			ordered &= s.chunk[i] == s.chunk[i - 1] ? s.first[i] == s.first[i - 1]
			                                        : s.chunk[i] == s.chunk[i - 1] + 1 && s.first[i] == i;
	}
	size_t used = nchunk == 0 ? 256 : nchunk;
	if (used > n)
		used = n;
	CHECK_MSG(once, "n %zu nchunk %zu threads %d: every item once", n, nchunk, nthreads);
	CHECK_MSG(ordered, "n %zu nchunk %zu threads %d: chunks in order", n, nchunk, nthreads);
	CHECK_MSG(atomic_load(&s.bad) == 0, "n %zu nchunk %zu: fct_par_chunk_of agrees", n, nchunk);
	if (n > 0) {
		CHECK_INT(s.chunk[0], 0);
		CHECK_INT(s.chunk[n - 1], used - 1);
	}
	free(s.count);
	free(s.chunk);
	free(s.first);
}

int main(void)
{
	size_t ns[] = { 1, 2, 7, 255, 256, 257, 1000, 100003 };
	size_t cs[] = { 0, 1, 3, 256, 5000 };
	for (size_t a = 0; a < sizeof ns / sizeof *ns; a++)
		for (size_t b = 0; b < sizeof cs / sizeof *cs; b++)
			for (int t = 1; t <= 3; t++)
				check_case(ns[a], cs[b], t);
	/* by hand: 10 items in 4 chunks are 0-1, 2-4, 5-6, 7-9 */
	CHECK_INT(fct_par_chunk_of(10, 4, 1), 0);
	CHECK_INT(fct_par_chunk_of(10, 4, 2), 1);
	CHECK_INT(fct_par_chunk_of(10, 4, 4), 1);
	CHECK_INT(fct_par_chunk_of(10, 4, 5), 2);
	CHECK_INT(fct_par_chunk_of(10, 4, 7), 3);
	CHECK_INT(fct_par_chunk_of(10, 4, 9), 3);
	CHECK_DONE();
}

/* par.h - a parallel loop: a range cut into a fixed number of chunks that
 * threads take in turn.  Every chunk is the same whatever the thread count,
 * so a function that writes only its own items' results gives the same bytes
 * on 1 thread or 64. */
#ifndef FCT_PAR_H
#define FCT_PAR_H

#include <stddef.h>

#define FCT_PAR_MAX 64          /* threads at most */

/* Work on items [lo, hi) of the range, as thread `worker` (0 .. nthreads-1:
 * an index into per-thread scratch space, never used for the result). */
typedef void fct_par_fn(void *ctx, size_t lo, size_t hi, int worker);

/* Threads to use for a request: want <= 0 means one per online processor;
 * the answer is in 1 .. FCT_PAR_MAX. */
int fct_par_threads(int want);

/* Run fn over [0, n) cut into nchunk chunks (0: 256) on nthreads threads
 * (the caller's thread is worker 0).  When a thread cannot be started the
 * others do its share.  Returns after every chunk is done. */
void fct_par_run(int nthreads, size_t n, size_t nchunk, fct_par_fn *fn, void *ctx);

/* The index of the chunk that holds item i < n in fct_par_run(..., n,
 * nchunk, ...): per-chunk results (partial sums added in chunk order, a
 * chunk's own buffer) can be kept by it whatever the thread count. */
size_t fct_par_chunk_of(size_t n, size_t nchunk, size_t i);

#endif

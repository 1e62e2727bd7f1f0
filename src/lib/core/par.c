/* par.c - the parallel loop of par.h on POSIX threads. */
#include "core/par.h"

#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>

struct job {
	fct_par_fn *fn;
	void *ctx;
	size_t n, nchunk;
	atomic_size_t next;
};

struct arg {
	struct job *j;
	int worker;
};

/* The first item of chunk c of n items cut into nchunk chunks: n c / nchunk
 * without overflow for any n. */
static size_t chunk_lo(size_t n, size_t nchunk, size_t c)
{
	size_t q = n / nchunk, r = n % nchunk;
	return q * c + r * c / nchunk;
}

/* nchunk as fct_par_run uses it. */
static size_t chunk_count(size_t n, size_t nchunk)
{
	if (nchunk == 0)
		nchunk = 256;
	return nchunk > n ? n : nchunk;
}

static void *work(void *p)
{
	struct arg *a = p;
	struct job *j = a->j;
	for (;;) {
		size_t c = atomic_fetch_add(&j->next, 1);
		if (c >= j->nchunk)
			break;
		size_t lo = chunk_lo(j->n, j->nchunk, c), hi = chunk_lo(j->n, j->nchunk, c + 1);
		if (lo < hi)
			j->fn(j->ctx, lo, hi, a->worker);
	}
	return NULL;
}

int fct_par_threads(int want)
{
	if (want <= 0) {
		long n = sysconf(_SC_NPROCESSORS_ONLN);
		want = n > 0 ? (int)(n < FCT_PAR_MAX ? n : FCT_PAR_MAX) : 1;
	}
	return want < FCT_PAR_MAX ? want : FCT_PAR_MAX;
}

void fct_par_run(int nthreads, size_t n, size_t nchunk, fct_par_fn *fn, void *ctx)
{
	if (n == 0)
		return;
	nchunk = chunk_count(n, nchunk);
	if (nthreads < 1)
		nthreads = 1;
	if (nthreads > FCT_PAR_MAX)
		nthreads = FCT_PAR_MAX;
	if ((size_t)nthreads > nchunk)
		nthreads = (int)nchunk;
	struct job j = { fn, ctx, n, nchunk, 0 };
	struct arg args[FCT_PAR_MAX];
	pthread_t th[FCT_PAR_MAX];
	int started = 0;
	for (int t = 1; t < nthreads; t++) {
		args[t] = (struct arg){ &j, t };
		if (pthread_create(&th[t], NULL, work, &args[t]))
			break;   /* fewer threads: those running do the rest */
		started = t;
	}
	args[0] = (struct arg){ &j, 0 };
	work(&args[0]);
	for (int t = 1; t <= started; t++)
		pthread_join(th[t], NULL);
}

size_t fct_par_chunk_of(size_t n, size_t nchunk, size_t i)
{
	nchunk = chunk_count(n, nchunk);
	size_t lo = 0, hi = nchunk;   /* the last c < nchunk with chunk_lo(c) <= i */
	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;
		if (chunk_lo(n, nchunk, mid) <= i)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

/* par.c - the parallel loop of par.h on POSIX threads. */
#include "par.h"

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

static void *work(void *p)
{
	struct arg *a = p;
	struct job *j = a->j;
	for (;;) {
		size_t c = atomic_fetch_add(&j->next, 1);
		if (c >= j->nchunk)
			break;
		/* n * c / nchunk without overflow for any n */
		size_t q = j->n / j->nchunk, r = j->n % j->nchunk;
		size_t lo = q * c + r * c / j->nchunk, hi = q * (c + 1) + r * (c + 1) / j->nchunk;
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
	if (nchunk == 0)
		nchunk = 256;
	if (nchunk > n)
		nchunk = n;
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

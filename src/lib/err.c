/* err.c - error messages and checked memory growth. */
#include "err.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

int fct_fail(struct fct_err *err, const char *fmt, ...)
{
	if (err) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(err->msg, sizeof err->msg, fmt, ap);
		va_end(ap);
	}
	return -1;
}

void fct_err_prefix(struct fct_err *err, const char *fmt, ...)
{
	if (!err)
		return;
	char head[512], old[sizeof err->msg];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(head, sizeof head, fmt, ap);
	va_end(ap);
	memcpy(old, err->msg, sizeof old);
	snprintf(err->msg, sizeof err->msg, "%s: %s", head, old);
}

int fct_mul_size(size_t a, size_t b, size_t *out)
{
	if (b && a > SIZE_MAX / b)
		return -1;
	*out = a * b;
	return 0;
}

int fct_add_size(size_t a, size_t b, size_t *out)
{
	if (a > SIZE_MAX - b)
		return -1;
	*out = a + b;
	return 0;
}

enum { HUGE_PAGE = (size_t)2 << 20 };

void fct_advise_large(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
	/* Big arrays are filled once, front to back: on Linux with transparent
	 * huge pages in "madvise" mode, asking for them saves most of the page
	 * faults, which otherwise cost as much as the work (a third of dm2mesh's
	 * time on a 640x480 map). */
	if (bytes < HUGE_PAGE)
		return;
	uintptr_t a = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
	uintptr_t e = ((uintptr_t)p + bytes) & ~(uintptr_t)(HUGE_PAGE - 1);
	if (e > a)
		madvise((void *)a, e - a, MADV_HUGEPAGE);
#else
	(void)p, (void)bytes;
#endif
}

void *fct_malloc_large(size_t bytes)
{
	if (bytes < HUGE_PAGE)
		return malloc(bytes ? bytes : 1);
	/* Aligned, so that every whole huge page of it can be one. */
	void *p;
	if (posix_memalign(&p, HUGE_PAGE, bytes))
		return NULL;
	fct_advise_large(p, bytes);
	return p;
}

int fct_grow(void **ptr, size_t *cap, size_t need, size_t elem, struct fct_err *err)
{
	if (need <= *cap)
		return 0;
	size_t ncap = *cap ? *cap : 16;
	while (ncap < need) {
		if (ncap > SIZE_MAX / 2)
			return fct_fail(err, "size overflow");
		ncap *= 2;
	}
	size_t bytes;
	if (fct_mul_size(ncap, elem, &bytes))
		return fct_fail(err, "size overflow");
	void *p = realloc(*ptr, bytes);
	if (!p)
		return fct_fail(err, "out of memory (%zu bytes)", bytes);
	fct_advise_large(p, bytes);
	*ptr = p;
	*cap = ncap;
	return 0;
}

void *fct_alloc_array(size_t n, size_t elem, struct fct_err *err)
{
	size_t bytes;
	if (fct_mul_size(n ? n : 1, elem, &bytes)) {
		fct_fail(err, "size overflow");
		return NULL;
	}
	void *p = fct_malloc_large(bytes);
	if (!p)
		fct_fail(err, "out of memory (%zu bytes)", bytes);
	return p;
}

char *fct_strdup(const char *s, struct fct_err *err)
{
	size_t n = strlen(s) + 1;
	char *d = malloc(n);
	if (!d) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	memcpy(d, s, n);
	return d;
}

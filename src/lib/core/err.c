/* err.c - error messages and checked memory growth. */
#include "core/err.h"

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

/* Bytes kept as they are in fct_escape. */
static int plain(unsigned char c)
{
	return c >= ' ' && c < 0x7f && c != '\\';
}

char *fct_escape(char *buf, size_t size, const char *s, size_t len)
{
	size_t need = 0, o = 0;
	for (size_t i = 0; i < len && s[i]; i++)
		need += plain((unsigned char)s[i]) ? 1 : 4;
	int cut = need >= size;
	for (size_t i = 0; i < len && s[i]; i++) {
		unsigned char c = (unsigned char)s[i];
		size_t w = plain(c) ? 1 : 4;
		if (cut && o + w + 3 >= size) {
			memcpy(buf + o, "...", 3);
			o += 3;
			break;
		}
		if (w == 1)
			buf[o++] = (char)c;
		else
			o += (size_t)snprintf(buf + o, size - o, "\\x%02x", c);
	}
	buf[o] = 0;
	return buf;
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

int fct_reserve(void **ptr, size_t *cap, size_t need, size_t elem, struct fct_err *err)
{
	size_t bytes;
	if (need <= *cap)
		return 0;
	if (fct_mul_size(need, elem, &bytes))
		return fct_fail(err, "size overflow");
	void *p = realloc(*ptr, bytes);
	if (!p)
		return fct_fail(err, "out of memory (%zu bytes)", bytes);
	*ptr = p;
	*cap = need;
	return 0;
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
	return fct_reserve(ptr, cap, ncap, elem, err);
}

void *fct_alloc_array(size_t n, size_t elem, struct fct_err *err)
{
	size_t bytes;
	if (fct_mul_size(n ? n : 1, elem, &bytes)) {
		fct_fail(err, "size overflow");
		return NULL;
	}
	void *p = malloc(bytes);
	if (!p)
		fct_fail(err, "out of memory (%zu bytes)", bytes);
	return p;
}

void *fct_alloc_big(size_t n, size_t elem, struct fct_err *err)
{
#ifdef MADV_HUGEPAGE
	const size_t huge = (size_t)2 << 20;
	size_t bytes;
	if (fct_mul_size(n, elem, &bytes) || bytes > SIZE_MAX - huge) {
		fct_fail(err, "size overflow");
		return NULL;
	}
	if (bytes < huge / 2)
		return fct_alloc_array(n, elem, err);
	bytes = (bytes + huge - 1) / huge * huge;
	void *p;
	if (posix_memalign(&p, huge, bytes)) {
		fct_fail(err, "out of memory (%zu bytes)", bytes);
		return NULL;
	}
	madvise(p, bytes, MADV_HUGEPAGE);
	return p;
#else
	return fct_alloc_array(n, elem, err);
#endif
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

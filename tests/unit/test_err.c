/* test_err.c - messages: bytes escaped for one line, growth checks, big
 * allocations. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/err.h"

static void test_escape(void)
{
	char b[64];
	CHECK_STR(fct_escape(b, sizeof b, "bmesh", 5), "bmesh");
	/* a line end, a terminal escape, a backslash and a high byte */
	CHECK_STR(fct_escape(b, sizeof b, "a\nb\x1b[2J\\\xff", 9), "a\\x0ab\\x1b[2J\\x5c\\xff");
	/* stops at len and at a NUL */
	CHECK_STR(fct_escape(b, sizeof b, "abcdef", 3), "abc");
	CHECK_STR(fct_escape(b, sizeof b, "ab\0cd", 5), "ab");
	/* cut to the buffer with "..." (8 bytes: 7 characters) */
	CHECK_STR(fct_escape(b, 8, "abcdefghij", 10), "abcd...");
	CHECK_STR(fct_escape(b, 8, "abcdefg", 7), "abcdefg");
	CHECK_STR(fct_escape(b, 8, "\x01\x02\x03", 3), "\\x01...");
	CHECK(strlen(fct_escape(b, 8, "\x01\x02", 2)) == 7);
}

static void test_sizes(void)
{
	size_t r;
	CHECK(fct_mul_size(SIZE_MAX / 2 + 1, 2, &r) == -1);
	CHECK(fct_add_size(SIZE_MAX, 1, &r) == -1);
	CHECK(fct_mul_size(3, 4, &r) == 0 && r == 12);
}

/* fct_alloc_big: plain below 1 MB, whole aligned 2 MB pages from there;
 * an overflowing size fails with a message. */
static void test_alloc_big(void)
{
	struct fct_err err;
	const size_t huge = (size_t)2 << 20;
	unsigned char *small = fct_alloc_big(1000, 1, &err);
	CHECK(small != NULL);
	memset(small, 1, 1000);
	free(small);
	size_t n = huge + huge / 2 + 8;   /* 3 MB and a little, rounded to 4 MB */
	unsigned char *big = fct_alloc_big(n, 1, &err);
	CHECK(big != NULL && (uintptr_t)big % huge == 0);
	memset(big, 7, 2 * huge);
	CHECK(big[n - 1] == 7 && big[2 * huge - 1] == 7);
	free(big);
	CHECK(fct_alloc_big(SIZE_MAX / 2 + 1, 2, &err) == NULL);
	CHECK_STR(err.msg, "size overflow");
	CHECK(fct_alloc_big(SIZE_MAX - 1, 1, &err) == NULL);
	CHECK_STR(err.msg, "size overflow");
}

int main(void)
{
	test_escape();
	test_sizes();
	test_alloc_big();
	CHECK_DONE();
}

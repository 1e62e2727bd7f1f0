/* test_err.c - messages: bytes escaped for one line, growth checks. */
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

int main(void)
{
	test_escape();
	test_sizes();
	CHECK_DONE();
}

/* test_reader - the forward-only buffered reader, by hand: lines (LF, CRLF,
 * a last line without its newline, empty lines, their numbers), a line
 * longer than a block, a line past the 16 MiB limit refused with its
 * number, fill and offsets, the bytes left in a regular file opened part
 * way and "unknown" for a pipe, the messages for a short read and for an
 * I/O error (a folder read as a file), and opening a missing file. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "io/reader.h"

static FILE *mem(const char *s)
{
	FILE *f = fmemopen((void *)s, strlen(s), "rb");
	if (!f)
		abort();
	return f;
}

static void test_lines(void)
{
	struct fct_reader r;
	struct fct_err err;
	size_t len;
	char *l;
	FILE *f = mem("a\r\nbb\n\nccc\r\nlast");
	CHECK_INT(fct_reader_init(&r, f, "t.txt", &err), 0);
	static const char *want[] = { "a", "bb", "", "ccc", "last" };
	for (int k = 0; k < 5; k++) {
		l = fct_reader_line(&r, &len, &err);
		CHECK(l != NULL);
		if (!l)
			break;
		CHECK_STR(l, want[k]);
		CHECK_INT(len, strlen(want[k]));
		CHECK_INT(r.line, k + 1);
	}
	CHECK(fct_reader_line(&r, &len, &err) == NULL);
	CHECK_STR(err.msg, "");   /* end of input, not an error */
	CHECK_INT(fct_reader_offset(&r), 16);   /* 3 + 3 + 1 + 5 + 4 bytes */
	fct_reader_free(&r);
	fclose(f);

	/* no input at all; one newline alone */
	f = mem("");
	fct_reader_init(&r, f, "t.txt", &err);
	CHECK(fct_reader_line(&r, &len, &err) == NULL);
	CHECK_INT(r.line, 0);
	fct_reader_free(&r);
	fclose(f);
	f = mem("\n");
	fct_reader_init(&r, f, "t.txt", &err);
	l = fct_reader_line(&r, &len, &err);
	CHECK(l && len == 0 && *l == 0);
	CHECK(fct_reader_line(&r, &len, &err) == NULL);
	fct_reader_free(&r);
	fclose(f);
}

/* A line of 1.5 MiB (longer than one 1 MiB block), then a short one; a
 * line of 16 MiB + 1 byte refused. */
static void test_long_lines(void)
{
	struct fct_reader r;
	struct fct_err err;
	size_t len, n = 3 << 19;
	FILE *f = tmpfile();
	for (size_t i = 0; i < n; i++)
		fputc('a' + (int)(i % 26), f);
	fputs("\nok\n", f);
	rewind(f);
	CHECK_INT(fct_reader_init(&r, f, "long.txt", &err), 0);
	char *l = fct_reader_line(&r, &len, &err);
	CHECK(l != NULL);
	CHECK_INT(len, n);
	if (l)
		CHECK(l[0] == 'a' && l[n - 1] == 'a' + (int)((n - 1) % 26) && l[n] == 0);
	l = fct_reader_line(&r, &len, &err);
	CHECK(l && !strcmp(l, "ok"));
	CHECK_INT(r.line, 2);
	fct_reader_close(&r);

	f = tmpfile();
	fputs("first\n", f);
	char *block = malloc(1 << 20);
	memset(block, 'x', 1 << 20);
	for (int k = 0; k < 16; k++)
		fwrite(block, 1, 1 << 20, f);
	fputs("x\n", f);
	free(block);
	rewind(f);
	fct_reader_init(&r, f, "huge.txt", &err);
	CHECK(fct_reader_line(&r, &len, &err) != NULL);
	CHECK(fct_reader_line(&r, &len, &err) == NULL);
	CHECK_STR(err.msg, "huge.txt:2: line longer than 16777216 bytes");
	fct_reader_close(&r);
}

static void test_fill(void)
{
	struct fct_reader r;
	struct fct_err err;
	FILE *f = mem("0123456789");
	fct_reader_init(&r, f, "m", &err);
	CHECK_INT(fct_reader_remaining(&r), UINT64_MAX);   /* not a regular file */
	/* at least n bytes unless the input ends (after a refill it says all
	 * it holds, 10 here; with n already held it says n) */
	CHECK(fct_reader_fill(&r, 4) >= 4);
	CHECK(!memcmp(r.buf + r.pos, "0123", 4));
	r.pos += 4;
	CHECK_INT(fct_reader_offset(&r), 4);
	CHECK(fct_reader_fill(&r, 4) >= 4);
	CHECK_INT(fct_reader_fill(&r, 100), 6);   /* short only at the end */
	CHECK(!memcmp(r.buf + r.pos, "456789", 6));
	r.pos += 6;
	CHECK_INT(fct_reader_fill(&r, 1), 0);
	CHECK_INT(fct_reader_fail_short(&r, &err, "header"), -1);
	CHECK_STR(err.msg, "m: byte 10: header: unexpected end of file");
	fct_reader_free(&r);
	fclose(f);

	/* a regular file of 100 bytes opened at byte 10: 90 left, then 85 */
	f = tmpfile();
	for (int i = 0; i < 100; i++)
		fputc('z', f);
	fseek(f, 10, SEEK_SET);
	fct_reader_init(&r, f, "reg", &err);
	CHECK_INT(r.size_hint, 90);
	CHECK_INT(fct_reader_remaining(&r), 90);
	fct_reader_fill(&r, 5);
	r.pos += 5;
	CHECK_INT(fct_reader_remaining(&r), 85);
	fct_reader_close(&r);

	/* a pipe: unknown */
	int fd[2];
	if (pipe(fd) == 0) {
		if (write(fd[1], "ab\n", 3) != 3)
			abort();
		close(fd[1]);
		f = fdopen(fd[0], "rb");
		fct_reader_init(&r, f, "<stdin>", &err);
		CHECK_INT(fct_reader_remaining(&r), UINT64_MAX);
		size_t len;
		char *l = fct_reader_line(&r, &len, &err);
		CHECK(l && !strcmp(l, "ab"));
		fct_reader_close(&r);
	}
}

static void test_errors(void)
{
	struct fct_reader r;
	struct fct_err err;
	size_t len;
	CHECK_INT(fct_reader_open(&r, "/nonexistent/x.ply", &err), -1);
	CHECK_STR(err.msg, "/nonexistent/x.ply: No such file or directory");
	/* a folder opens but cannot be read */
	CHECK_INT(fct_reader_open(&r, "/tmp", &err), 0);
	CHECK(fct_reader_line(&r, &len, &err) == NULL);
	CHECK_STR(err.msg, "/tmp: byte 0: reading: Is a directory");
	CHECK_INT(fct_reader_fail_short(&r, &err, "header"), -1);
	CHECK_STR(err.msg, "/tmp: byte 0: header: Is a directory");
	fct_reader_close(&r);
}

int main(void)
{
	test_lines();
	test_long_lines();
	test_fill();
	test_errors();
	CHECK_DONE();
}

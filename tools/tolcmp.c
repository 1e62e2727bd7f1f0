/* tolcmp - compare two text files token by token, numbers with a tolerance,
 * so that golden-file tests survive another compiler, libm or BLAS (in the
 * spirit of Radiance's radcompare).
 *
 * Both files are read line by line; a line's tokens are its runs of
 * non-blank characters.  Two tokens match when they are the same text, or
 * both integers of equal value, or both numbers, at least one of them
 * floating-point, within |a-b| <= abs + rel*max(|a|,|b|).  Exit status
 * follows cmp(1): 0 same, 1 different, 2 trouble. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "core/numparse.h"
#include "io/reader.h"

static const char usage[] =
	"usage: tolcmp [-s] [-a abs] [-r rel] file1 file2\n"
	"Compare two text files token by token; numbers that are not both integers\n"
	"are equal when |a-b| <= abs + rel*max(|a|,|b|).\n"
	"  -a abs        absolute tolerance (default 1e-9)\n"
	"  -r rel        relative tolerance (default 1e-6)\n"
	"  -s            silent: report only through the exit status\n"
	"  -h, --help    this help\n"
	"      --version print the version\n"
	"Exit status: 0 equal within tolerance, 1 different, 2 usage or I/O error.\n";

/* What a token is, for comparison. */
enum kind { WORD, INTEGER, REAL };

struct token {
	enum kind kind;
	int64_t i;
	double d;
};

static int is_blank(char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/* Classify the NUL-terminated token s: an integer when all of it is one,
 * a real when all of it is a number and it has a '.', an exponent, or is
 * nan or inf; anything else is a word. */
static struct token classify(const char *s)
{
	struct token t = {WORD, 0, 0};
	const char *end = fct_parse_int64(s, &t.i);
	if (end && !*end) {
		t.kind = INTEGER;
		t.d = (double)t.i;
		return t;
	}
	end = fct_parse_double(s, &t.d);
	if (!end || *end)
		return t;
	const char *p = s + (*s == '+' || *s == '-');
	int hex = p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
	if (strchr(s, '.') || (!hex && strpbrk(s, "eE")) || (hex && strpbrk(s, "pP")) ||
	    !strncasecmp(p, "nan", 3) || !strncasecmp(p, "inf", 3))
		t.kind = REAL;
	return t;
}

static double tol_abs = 1e-9, tol_rel = 1e-6;

/* Do two tokens match?  *diff gets |a-b| for two numbers (-1 otherwise). */
static int tokens_match(const char *a, const char *b, double *diff)
{
	*diff = -1;
	if (!strcmp(a, b))
		return 1;
	struct token x = classify(a), y = classify(b);
	if (x.kind == WORD || y.kind == WORD)
		return 0;
	if (x.kind == INTEGER && y.kind == INTEGER) {
		*diff = fabs((double)x.i - (double)y.i);
		return x.i == y.i;
	}
	if (isnan(x.d) || isnan(y.d)) {
		*diff = NAN;
		return isnan(x.d) && isnan(y.d);
	}
	if (x.d == y.d) {   /* equal infinities included */
		*diff = 0;
		return 1;
	}
	*diff = fabs(x.d - y.d);
	if (isinf(x.d) || isinf(y.d))
		return 0;   /* rel * inf would let anything match an infinity */
	double big = fmax(fabs(x.d), fabs(y.d));
	return *diff <= tol_abs + tol_rel * big;
}

struct input {
	const char *name;
	FILE *f;
	struct fct_reader r;
	char *line;
	ssize_t len;
	long lineno;
};

/* Next line of in (at most the reader's 16 MB, without its line end); 0 at
 * end of file; exits 2 on a read error, an overlong line or a NUL byte
 * (binary input: /dev/zero would otherwise be read until memory ran out). */
static int next_line(struct input *in)
{
	struct fct_err err;
	size_t n;
	in->line = fct_reader_line(&in->r, &n, &err);
	if (!in->line) {
		if (err.msg[0])
			fct_die(2, "%s", err.msg);
		return 0;
	}
	in->lineno++;
	if (memchr(in->line, 0, n))
		fct_die(2, "%s:%ld: NUL byte: not a text file", in->name, in->lineno);
	in->len = (ssize_t)n;
	return 1;
}

/* The next token in line[*pos..len), NUL-terminated in place (the blank
 * after it is overwritten); NULL at the end of the line. */
static char *next_token(struct input *in, ssize_t *pos)
{
	ssize_t p = *pos;
	while (p < in->len && is_blank(in->line[p]))
		p++;
	if (p >= in->len)
		return NULL;
	char *t = in->line + p;
	while (p < in->len && !is_blank(in->line[p]))
		p++;
	in->line[p] = 0;   /* line has a NUL at len, so p <= len is writable */
	*pos = p + (p < in->len);
	return t;
}

static int count_tokens(struct input *in)
{
	int n = 0;
	for (ssize_t p = 0;;) {
		while (p < in->len && is_blank(in->line[p]))
			p++;
		if (p >= in->len)
			return n;
		n++;
		while (p < in->len && !is_blank(in->line[p]))
			p++;
	}
}

static int silent;

/* Compare the current lines of a and b; 1 when they match. */
static int compare_lines(struct input *a, struct input *b)
{
	int na = count_tokens(a), nb = count_tokens(b);
	if (na != nb) {
		if (!silent)
			fct_error("%s:%ld: %d tokens vs %d", a->name, a->lineno, na, nb);
		return 0;
	}
	ssize_t pa = 0, pb = 0;
	for (int i = 0; i < na; i++) {
		const char *ta = next_token(a, &pa), *tb = next_token(b, &pb);
		double d;
		if (tokens_match(ta, tb, &d))
			continue;
		if (!silent) {
			if (d >= 0 || isnan(d))
				fct_error("%s:%ld: \"%s\" vs \"%s\" (difference %.3g)",
				        a->name, a->lineno, ta, tb, d);
			else
				fct_error("%s:%ld: \"%s\" vs \"%s\"", a->name, a->lineno, ta, tb);
		}
		return 0;
	}
	return 1;
}

static void start_input(struct input *in)
{
	struct fct_err err;
	if (fct_reader_init(&in->r, in->f, in->name, &err))
		fct_die(2, "%s", err.msg);
}

static void open_input(struct input *in, const char *path)
{
	memset(in, 0, sizeof *in);
	if (!strcmp(path, "-")) {
		in->name = "<stdin>";
		in->f = stdin;
		start_input(in);
		return;
	}
	in->name = path;
	if (!(in->f = fopen(path, "r")))
		fct_die(2, "%s: %s", path, strerror(errno));
	start_input(in);
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("tolcmp");
	static const char optstring[] = "a:hr:s";
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'a': tol_abs = fct_opt_double("-a", optarg, 0, INFINITY); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'r': tol_rel = fct_opt_double("-r", optarg, 0, INFINITY); break;
		case 's': silent = 1; break;
		case 'V': puts("tolcmp (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	if (argc - optind != 2)
		fct_usage_error("expected two files");
	if (!strcmp(argv[optind], "-") && !strcmp(argv[optind + 1], "-"))
		fct_usage_error("only one file can be stdin");
	struct input a, b;
	open_input(&a, argv[optind]);
	open_input(&b, argv[optind + 1]);
	int same = 1;
	for (;;) {
		int ga = next_line(&a), gb = next_line(&b);
		if (!ga || !gb) {
			if (ga != gb) {
				same = 0;
				/* Count the rest of the longer file for the message. */
				struct input *lon = ga ? &a : &b;
				while (next_line(lon))
					;
				if (!silent)
					fct_error("%s: %ld lines vs %ld in %s",
					        a.name, a.lineno, b.lineno, b.name);
			}
			break;
		}
		if (!compare_lines(&a, &b)) {
			same = 0;
			break;
		}
	}
	fct_reader_free(&a.r);
	fct_reader_free(&b.r);
	if (a.f != stdin)
		fclose(a.f);
	if (b.f != stdin)
		fclose(b.f);
	return same ? 0 : 1;
}

/* check.h - the unit-test harness: checks record file:line and go on; the
 * test's main ends with CHECK_DONE(), which prints "N passed, N failed" and
 * returns non-zero on any failure.
 *
 *   int main(void) { test_something(); CHECK_DONE(); }
 */
#ifndef FCT_CHECK_H
#define FCT_CHECK_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int check_passed, check_failed;

#define CHECK(cond) check_report(!!(cond), __FILE__, __LINE__, "%s", #cond)
#define CHECK_MSG(cond, ...) check_report(!!(cond), __FILE__, __LINE__, __VA_ARGS__)
#define CHECK_INT(a, b) do { long long a_ = (long long)(a), b_ = (long long)(b); \
	check_report(a_ == b_, __FILE__, __LINE__, "%s == %s (%lld vs %lld)", #a, #b, a_, b_); } while (0)
#define CHECK_NEAR(a, b, tol) do { double a_ = (a), b_ = (b); \
	check_report(fabs(a_ - b_) <= (tol), __FILE__, __LINE__, "%s ~ %s (%.17g vs %.17g, tol %g)", \
	             #a, #b, a_, b_, (double)(tol)); } while (0)
#define CHECK_STR(a, b) do { const char *a_ = (a), *b_ = (b); \
	check_report(a_ && b_ && !strcmp(a_, b_), __FILE__, __LINE__, "%s == %s (\"%s\" vs \"%s\")", \
	             #a, #b, a_ ? a_ : "(null)", b_ ? b_ : "(null)"); } while (0)
#define CHECK_DONE() do { printf("%s: %d passed, %d failed\n", __FILE__, check_passed, check_failed); \
	return check_failed != 0; } while (0)

__attribute__((format(printf, 4, 5)))
static void check_report(int ok, const char *file, int line, const char *fmt, ...)
{
	if (ok) {
		check_passed++;
		return;
	}
	check_failed++;
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "%s:%d: check failed: ", file, line);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
}

#endif

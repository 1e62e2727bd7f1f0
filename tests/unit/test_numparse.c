/* Exactness of the fast decimal parser: it must give strtod's value, bit for
 * bit, on every input, including the cases that leave its fast path. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/numparse.h"

static uint64_t rng_state = 88172645463325252ull;

static uint64_t next(void)
{
	rng_state ^= rng_state << 13;
	rng_state ^= rng_state >> 7;
	rng_state ^= rng_state << 17;
	return rng_state;
}

/* Both parsers agree on value (bitwise) and on where the number ends. */
static int same_as_strtod(const char *s)
{
	double a, b;
	char *e;
	b = strtod(s, &e);
	const char *end = fct_parse_double(s, &a);
	if (!end)
		return e == s;
	return end == e && memcmp(&a, &b, sizeof a) == 0;
}

static void test_fixed_cases(void)
{
	static const char *cases[] = {
		"0", "-0", "+0", "1", "-1", "0.5", "0.1", "0.2", "0.3", "1e10", "1E-10", "-2.5e+3",
		"0.000123", "123456789012345678", "1234567890123456789", "12345678901234567890",
		"9007199254740992", "9007199254740993", "0.1e23", "1e22", "1e23", "1e-22", "1e-23",
		"4.9e-324", "2.2250738585072014e-308", "1.7976931348623157e308", "1e309", "-1e400",
		"0.0378297", "-0.0120482", "3.14159265358979323846", "1.", ".5", "-.5", "5e",
		"5e+", "0x1p3", "inf", "-inf", "nan", "infinity", "00000000000000000000001.5",
		"0.00000000000000000000000000000001", "123.456e-7", "1e-300", "7e22", "8e22",
	};
	for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
		CHECK_MSG(same_as_strtod(cases[i]), "\"%s\" differs from strtod", cases[i]);
	double v;
	CHECK(fct_parse_double("abc", &v) == NULL);
	CHECK(fct_parse_double("-", &v) == NULL);
	CHECK(fct_parse_double("", &v) == NULL);
	const char *s = "1.25 rest";
	CHECK(fct_parse_double(s, &v) == s + 4 && v == 1.25);
}

static void test_random_decimals(void)
{
	char buf[64];
	int bad = 0;
	for (int i = 0; i < 200000; i++) {
		uint64_t r = next();
		int digits = 1 + (int)(r % 19), point = (int)((r >> 8) % (digits + 1));
		char *p = buf;
		if (r & (1ull << 40))
			*p++ = '-';
		for (int d = 0; d < digits; d++) {
			if (d == point && d)
				*p++ = '.';
			*p++ = (char)('0' + next() % 10);
		}
		if (r & (1ull << 41))
			p += sprintf(p, "e%d", (int)((r >> 16) % 61) - 30);
		*p = 0;
		bad += !same_as_strtod(buf);
	}
	CHECK_INT(bad, 0);
	/* Round trips of printed floats and doubles. */
	bad = 0;
	for (int i = 0; i < 100000; i++) {
		uint64_t bits = next();
		double d;
		memcpy(&d, &bits, sizeof d);
		if (!(d == d) || d - d != 0)
			continue;
		sprintf(buf, i & 1 ? "%.17g" : "%.9g", i & 1 ? d : (double)(float)d);
		bad += !same_as_strtod(buf);
	}
	CHECK_INT(bad, 0);
}

static void test_int64(void)
{
	int64_t v;
	CHECK(fct_parse_int64("9223372036854775807", &v) && v == INT64_MAX);
	CHECK(fct_parse_int64("-9223372036854775808", &v) && v == INT64_MIN);
	CHECK(fct_parse_int64("9223372036854775808", &v) == NULL);
	CHECK(fct_parse_int64("99999999999999999999", &v) == NULL);
	CHECK(fct_parse_int64("-", &v) == NULL);
	CHECK(fct_parse_int64("12x", &v) && v == 12);
	CHECK(fct_parse_int64("+7", &v) && v == 7);
}

int main(void)
{
	test_fixed_cases();
	test_random_decimals();
	test_int64();
	CHECK_DONE();
}

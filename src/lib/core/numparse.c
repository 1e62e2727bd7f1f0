/* numparse.c - exact fast decimal parsing (see numparse.h). */
#include "core/numparse.h"

#include <stdio.h>
#include <stdlib.h>

static const double pow10_exact[23] = {
	1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
	1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

static int is_digit(char c)
{
	return (unsigned)(c - '0') < 10;
}

/* strtod for the cases the fast path does not decide; also accepts inf/nan. */
static const char *slow_path(const char *s, double *out)
{
	char *end;
	double v = strtod(s, &end);
	if (end == s)
		return NULL;
	*out = v;
	return end;
}

const char *fct_parse_double(const char *s, double *out)
{
	const char *p = s;
	int neg = 0;
	if (*p == '-' || *p == '+')
		neg = *p++ == '-';
	if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
		return slow_path(s, out);  /* hexadecimal floats */
	uint64_t mant = 0;
	int digits = 0, frac = 0, any = 0;
	while (*p == '0')  /* leading zeros carry no precision */
		p++, any = 1;
	for (; is_digit(*p); p++, any = 1) {
		if (digits < 19)
			mant = mant * 10 + (uint64_t)(*p - '0');
		else
			return slow_path(s, out);
		digits += mant != 0;
	}
	if (*p == '.') {
		p++;
		for (; is_digit(*p); p++, any = 1) {
			if (digits >= 19)
				return slow_path(s, out);
			mant = mant * 10 + (uint64_t)(*p - '0');
			digits += mant != 0;
			frac++;
		}
	}
	if (!any)
		return slow_path(s, out);  /* "inf", "nan", ".e" and friends */
	int exp10 = 0;
	if (*p == 'e' || *p == 'E') {
		const char *q = p + 1;
		int eneg = 0;
		if (*q == '-' || *q == '+')
			eneg = *q++ == '-';
		if (!is_digit(*q))
			goto done;  /* "1e" is the number 1 followed by "e", as strtod reads it */
		int e = 0;
		for (; is_digit(*q); q++)
			if (e < 100000)
				e = e * 10 + (*q - '0');
		exp10 = eneg ? -e : e;
		p = q;
	}
done:;
	int scale = exp10 - frac;
	if (mant > (UINT64_C(1) << 53) || scale < -22 || scale > 22)
		return slow_path(s, out);
	double v = (double)mant;
	if (mant != 0)
		v = scale < 0 ? v / pow10_exact[-scale] : v * pow10_exact[scale];
	*out = neg ? -v : v;
	return p;
}

const char *fct_parse_int64(const char *s, int64_t *out)
{
	const char *p = s;
	int neg = 0;
	if (*p == '-' || *p == '+')
		neg = *p++ == '-';
	if (!is_digit(*p))
		return NULL;
	uint64_t v = 0;
	for (; is_digit(*p); p++) {
		uint64_t d = (uint64_t)(*p - '0');
		if (v > (UINT64_MAX - d) / 10)
			return NULL;
		v = v * 10 + d;
	}
	if (neg ? v > (uint64_t)INT64_MAX + 1 : v > (uint64_t)INT64_MAX)
		return NULL;
	*out = neg ? (int64_t)(0 - v) : (int64_t)v;
	return p;
}

int fct_format_float(char *buf, size_t n, float v)
{
	for (int prec = 6; prec < 9; prec++) {
		int k = snprintf(buf, n, "%.*g", prec, v);
		double d;
		if (fct_parse_double(buf, &d) && (float)d == v)
			return k;
	}
	return snprintf(buf, n, "%.9g", v);
}

int fct_format_double(char *buf, size_t n, double v)
{
	for (int prec = 15; prec < 17; prec++) {
		int k = snprintf(buf, n, "%.*g", prec, v);
		double d;
		if (fct_parse_double(buf, &d) && d == v)
			return k;
	}
	return snprintf(buf, n, "%.17g", v);
}

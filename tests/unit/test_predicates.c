/* test_predicates - exact signs of orient2d and incircle on inputs where
 * plain double evaluation is wrong: the near-collinear grid around (0.5,
 * 0.5) (exact answer 12 (ay - ax) by hand), integer configurations checked
 * against 128-bit integer arithmetic after exact scaling by powers of two
 * and dyadic translation, exactly cocircular Pythagorean points, tiny,
 * subnormal, huge and mixed-magnitude coordinates (the big-integer stage,
 * cross-checked with the expansion stage through exact scaling), and sign
 * identities under permutation. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "geom/predicates.h"
#include "core/rng.h"

static int sgn(double x)
{
	return (x > 0) - (x < 0);
}

static int sgn128(__int128 x)
{
	return (x > 0) - (x < 0);
}

/* Plain double evaluation, to show that the cases are hard. */
static double naive_orient(const double a[2], const double b[2], const double c[2])
{
	return (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
}

static double naive_incircle(const double a[2], const double b[2], const double c[2], const double d[2])
{
	double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
	double cdx = c[0] - d[0], cdy = c[1] - d[1];
	return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
	       (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
	       (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

/* Exact signs for integer coordinates below 2^25 in magnitude. */
static int exact_orient(const int64_t a[2], const int64_t b[2], const int64_t c[2])
{
	__int128 l = (__int128)(a[0] - c[0]) * (b[1] - c[1]);
	__int128 r = (__int128)(a[1] - c[1]) * (b[0] - c[0]);
	return sgn128(l - r);
}

static int exact_incircle(const int64_t a[2], const int64_t b[2], const int64_t c[2], const int64_t d[2])
{
	__int128 adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
	__int128 cdx = c[0] - d[0], cdy = c[1] - d[1];
	__int128 det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
	               (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
	               (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
	return sgn128(det);
}

static void test_simple(void)
{
	double a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1}, m[2] = {0.5, 0}, far[2] = {3, 3};
	CHECK(fct_orient2d(a, b, c) > 0);
	CHECK(fct_orient2d(a, c, b) < 0);
	CHECK(fct_orient2d(a, b, m) == 0);
	CHECK_NEAR(fct_orient2d(a, b, c), 1.0, 0);
	double in[2] = {0.25, 0.25}, on[2] = {1, 1};
	CHECK(fct_incircle(a, b, c, in) > 0);
	CHECK(fct_incircle(a, b, c, on) == 0);
	CHECK(fct_incircle(a, b, c, far) < 0);
	CHECK(fct_incircle(a, c, b, in) < 0);   /* clockwise: sign reversed */
	/* Collinear a, b, m: the sign is that of the determinant (here the side
	 * of the line, as the circle degenerates). */
	CHECK(fct_incircle(a, b, m, c) == -fct_incircle(a, m, b, c));
}

/* The classic: a = (0.5 + i u, 0.5 + j u), u = 2^-53, i, j < 256, against
 * b = (12, 12) and c = (24, 24).  By hand, orient2d(a, b, c) = 12 (ay - ax),
 * so the sign is that of j - i. */
static void test_near_collinear_grid(void)
{
	const double u = 0x1p-53;
	double b[2] = {12, 12}, c[2] = {24, 24};
	int wrong = 0, naive_wrong = 0, cases = 0;
	for (int i = 0; i < 256; i++)
		for (int j = 0; j < 256; j++) {
			double a[2] = {0.5 + i * u, 0.5 + j * u};
			int want = (j > i) - (j < i);
			cases++;
			wrong += sgn(fct_orient2d(a, b, c)) != want;
			wrong += sgn(fct_orient2d(b, c, a)) != want;
			wrong += sgn(fct_orient2d(c, a, b)) != want;
			wrong += sgn(fct_orient2d(b, a, c)) != -want;
			naive_wrong += sgn(naive_orient(a, b, c)) != want;
		}
	CHECK_INT(cases, 65536);
	CHECK_INT(wrong, 0);
	/* The plain formula gets a large share wrong: the test is a real one. */
	CHECK_MSG(naive_wrong > 1000, "naive wrong on %d of 65536", naive_wrong);
}

/* Random near-collinear and near-cocircular integer configurations (below
 * 2^23), moved by a dyadic offset and scaled by 2^k: both exact, so the
 * 128-bit integer sign is the answer for every k. */
static void test_integer_configurations(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	static const int scales[] = {0, -30, 40, -200, 170, -1000, -1070, 700, 900};
	int wrong = 0, zeros = 0, total = 0;
	for (int it = 0; it < 3000; it++) {
		int64_t p[4][2];
		for (int k = 0; k < 3; k++)
			for (int q = 0; q < 2; q++)
				p[k][q] = (int64_t)fct_rng_below(&r, 1u << 23) - (1 << 22);
		/* p1 = p0 + M (dx, dy); near_line = p0 + j (dx, dy) + (e0, e1), e
		 * in {-1, 0, 1}: exactly on the line p0 p1 one time in nine */
		int64_t dir[2], near_line[2];
		for (int q = 0; q < 2; q++)
			dir[q] = (int64_t)fct_rng_below(&r, 2049) - 1024;
		int64_t M = 1 + (int64_t)fct_rng_below(&r, 4096), j = (int64_t)fct_rng_below(&r, 12288) - 4096;
		for (int q = 0; q < 2; q++) {
			p[1][q] = p[0][q] + M * dir[q];
			near_line[q] = p[0][q] + j * dir[q] + (int64_t)fct_rng_below(&r, 3) - 1;
		}
		double ax = (double)p[0][0], ay = (double)p[0][1], bx = (double)p[1][0], by = (double)p[1][1];
		double cx = (double)p[2][0], cy = (double)p[2][1];
		double den = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
		if (fabs(den) < 1) {
			it--;
			continue;
		}
		double ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / den;
		double uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / den;
		double rad = hypot(ax - ux, ay - uy), th = fct_rng_uniform(&r) * 2 * M_PI;
		p[3][0] = (int64_t)llround(ux + rad * cos(th));
		p[3][1] = (int64_t)llround(uy + rad * sin(th));
		if (llabs(p[3][0]) >= 1 << 24 || llabs(p[3][1]) >= 1 << 24) {
			it--;
			continue;
		}
		int want_o = exact_orient(p[0], p[1], near_line);
		int want_i = exact_incircle(p[0], p[1], p[2], p[3]);
		zeros += want_o == 0;
		for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
			double off = scales[s] == 0 ? 1048576.5 : 0;   /* dyadic: exact */
			double d[5][2];
			for (int k = 0; k < 4; k++)
				for (int q = 0; q < 2; q++)
					d[k][q] = ldexp((double)p[k][q] + off, scales[s]);
			for (int q = 0; q < 2; q++)
				d[4][q] = ldexp((double)near_line[q] + off, scales[s]);
			total++;
			wrong += sgn(fct_orient2d(d[0], d[1], d[4])) != want_o;
			wrong += sgn(fct_orient2d(d[1], d[4], d[0])) != want_o;
			wrong += sgn(fct_incircle(d[0], d[1], d[2], d[3])) != want_i;
			wrong += sgn(fct_incircle(d[1], d[2], d[0], d[3])) != want_i;
			wrong += sgn(fct_incircle(d[0], d[1], d[3], d[2])) != -want_i;
		}
	}
	CHECK_INT(wrong, 0);
	CHECK_MSG(zeros > 100, "only %d exactly collinear cases", zeros);
	CHECK(total > 0);
}

/* The integer points on x^2 + y^2 = R^2, all exactly cocircular. */
static int circle_points(int64_t R, int64_t (*p)[2], int max)
{
	int n = 0;
	for (int64_t x = -R; x <= R; x++) {
		int64_t y2 = R * R - x * x;
		int64_t y = (int64_t)llround(sqrt((double)y2));
		if (y * y != y2)
			continue;
		if (n < max) {
			p[n][0] = x;
			p[n][1] = y;
			n++;
		}
		if (y != 0 && n < max) {
			p[n][0] = x;
			p[n][1] = -y;
			n++;
		}
	}
	return n;
}

static void test_cocircular(void)
{
	/* 1185665 = 5 * 13 * 17 * 29 * 37, five primes 1 mod 4: 4 * 3^5 = 972
	 * points, coordinates of 21 bits, so that plain products round; then
	 * one point moved by one unit in or out. */
	static int64_t p[1000][2];
	int n = circle_points(1185665, p, 1000);
	CHECK_INT(n, 972);
	static const int scales[] = {0, 30, -40, -1060, 960};
	const double off[2] = {3.0 * 1048576 + 0.25, -0.75};   /* dyadic, exact */
	int wrong = 0, naive_nonzero = 0;
	for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
		for (int it = 0; it < 400; it++) {
			int i = (it * 7) % n, j = (it * 13 + 5) % n, k = (it * 31 + 11) % n, l = (it * 3 + 50) % n;
			if (i == j || j == k || i == k || l == i || l == j || l == k)
				continue;
			double a[2], b[2], c[2], d[2], dn[2], dout[2];
			const int64_t *pp[4] = {p[i], p[j], p[k], p[l]};
			double *dd[4] = {a, b, c, d};
			for (int m = 0; m < 4; m++)
				for (int q = 0; q < 2; q++)
					dd[m][q] = ldexp((double)pp[m][q] + (scales[s] == 0 ? off[q] : 0), scales[s]);
			/* moved toward the centre / away from it along the larger axis */
			int ax = llabs(p[l][0]) > llabs(p[l][1]) ? 0 : 1;
			int64_t in[2] = {p[l][0], p[l][1]}, out[2] = {p[l][0], p[l][1]};
			in[ax] -= p[l][ax] > 0 ? 1 : -1;
			out[ax] += p[l][ax] > 0 ? 1 : -1;
			for (int q = 0; q < 2; q++) {
				dn[q] = ldexp((double)in[q] + (scales[s] == 0 ? off[q] : 0), scales[s]);
				dout[q] = ldexp((double)out[q] + (scales[s] == 0 ? off[q] : 0), scales[s]);
			}
			int o = exact_orient(p[i], p[j], p[k]);
			wrong += fct_incircle(a, b, c, d) != 0;
			wrong += sgn(fct_incircle(a, b, c, dn)) != o;      /* inside: + for ccw */
			wrong += sgn(fct_incircle(a, b, c, dout)) != -o;
			naive_nonzero += scales[s] == 0 && naive_incircle(a, b, c, d) != 0;
		}
	}
	CHECK_INT(wrong, 0);
	/* The plain formula often misses the exact zero. */
	CHECK_MSG(naive_nonzero > 100, "naive nonzero on %d", naive_nonzero);
}

/* Hand-made cases at the ends of the double range (big-integer stage). */
static void test_extreme(void)
{
	const double t = 0x1p-1074;   /* the smallest subnormal */
	/* c just above the line through a and b: positive, though every
	 * product of the plain formula is at the bottom of the range */
	double a[2] = {-1, 0}, b[2] = {1, 0}, c[2] = {0, t}, c0[2] = {0, 0}, c1[2] = {0, -t};
	CHECK(fct_orient2d(a, b, c) > 0);
	CHECK(fct_orient2d(a, b, c0) == 0);
	CHECK(fct_orient2d(a, b, c1) < 0);
	/* products that underflow: (2^-600, 0), (0, 2^-600), and a point off
	 * their line x + y = 2^-600 by 2^-653, on its right */
	double e[2] = {0x1p-600, 0}, f[2] = {0, 0x1p-600}, g[2] = {0x1p-601 + 0x1p-653, 0x1p-601}, g0[2] = {0x1p-601, 0x1p-601};
	CHECK(fct_orient2d(e, f, g) < 0);
	CHECK(fct_orient2d(e, f, g0) == 0);
	CHECK(naive_orient(e, f, g) == 0);   /* and the plain formula misses it */
	/* mixed magnitudes: 2^601 (2^-600 - 2^-599 - 2^-651) + (2^-599 + 2^-651) 2^600 = -2^-51 */
	double h1[2] = {0x1p600, 0}, h2[2] = {0, 0x1p-600}, h3[2] = {-0x1p600, 0x1p-599 + 0x1p-651};
	double h4[2] = {-0x1p600, 0x1p-599};
	CHECK(fct_orient2d(h1, h2, h3) < 0);
	CHECK(fct_orient2d(h1, h2, h4) == 0);
	/* huge: products overflow in the filter */
	double k1[2] = {0x1p1000, 0x1p1000}, k2[2] = {-0x1p1000, 0x1p1000}, k3[2] = {0, 0x1p1000};
	double k4[2] = {0, 0x1p1000 - 0x1p948};
	CHECK(fct_orient2d(k1, k2, k3) == 0);
	CHECK(fct_orient2d(k1, k2, k4) > 0);   /* below the line from right to left: ccw */
	CHECK(fct_orient2d(k2, k1, k4) < 0);
	/* the unit circle and d = (2^-1074, -1): |d|^2 = 1 + 2^-2148, outside */
	double u1[2] = {1, 0}, u2[2] = {0, 1}, u3[2] = {-1, 0}, ud[2] = {t, -1}, uon[2] = {0, -1};
	CHECK(fct_incircle(u1, u2, u3, ud) < 0);
	CHECK(fct_incircle(u1, u2, u3, uon) == 0);
	CHECK(naive_incircle(u1, u2, u3, ud) == 0);
	/* a circle of radius 2^500 (beyond the expansion range), d inside by 2^448 */
	double r1[2] = {0x1p500, 0}, r2[2] = {0, 0x1p500}, r3[2] = {-0x1p500, 0};
	double rin[2] = {0, -0x1p500 + 0x1p448}, ron[2] = {0, -0x1p500}, rout[2] = {0, -0x1p500 - 0x1p448};
	CHECK(fct_incircle(r1, r2, r3, rin) > 0);
	CHECK(fct_incircle(r1, r2, r3, ron) == 0);
	CHECK(fct_incircle(r1, r2, r3, rout) < 0);
	/* subnormal unit circle: radius 2^-1070, d inside by 2^-1074 */
	double s1[2] = {0x1p-1070, 0}, s2[2] = {0, 0x1p-1070}, s3[2] = {-0x1p-1070, 0};
	double sin_[2] = {0, -0x1p-1070 + t}, son[2] = {0, -0x1p-1070};
	CHECK(fct_incircle(s1, s2, s3, sin_) > 0);
	CHECK(fct_incircle(s1, s2, s3, son) == 0);
	CHECK(fct_orient2d(s1, s2, s3) > 0);
	/* largest finite coordinates: the differences themselves overflow */
	double m1[2] = {DBL_MAX, -DBL_MAX}, m2[2] = {-DBL_MAX, DBL_MAX}, m3[2] = {0, 0}, m4[2] = {t, 0};
	CHECK(fct_orient2d(m1, m2, m3) == 0);
	CHECK(fct_orient2d(m1, m2, m4) < 0);   /* right of y = -x walked from m1 to m2 */
	CHECK(fct_orient2d(m2, m1, m4) > 0);
	/* -0 and 0 are the same point */
	double z1[2] = {-0.0, 0}, z2[2] = {1, 0}, z3[2] = {2, -0.0};
	CHECK(fct_orient2d(z1, z2, z3) == 0);
}

/* Random near-degenerate doubles (full 53-bit mantissas, differences that
 * round): the expansion stage's answers must agree with the big-integer
 * stage's (reached by exact scaling by 2^-900 or 2^900) and obey the
 * permutation identities. */
static void test_random_near_degenerate(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 99);
	int bad = 0, naive_bad = 0, zero = 0;
	for (int it = 0; it < 20000; it++) {
		double a[2], b[2], c[2], d[2];
		for (int q = 0; q < 2; q++) {
			a[q] = fct_rng_uniform(&r) * 2 - 1;
			b[q] = fct_rng_uniform(&r) * 2 - 1;
		}
		double tt = fct_rng_uniform(&r) * 4 - 2;
		for (int q = 0; q < 2; q++)
			c[q] = a[q] + tt * (b[q] - a[q]);   /* collinear up to rounding */
		if (it % 4 == 0)
			c[1] = c[0] * 0.5;    /* with a and b on the same line: exact zeros */
		if (it % 4 == 0) {
			a[1] = a[0] * 0.5;
			b[1] = b[0] * 0.5;
		}
		/* d on the circumcircle of a, b, e up to rounding */
		double e[2] = {fct_rng_uniform(&r), fct_rng_uniform(&r)};
		double den = 2 * (a[0] * (b[1] - e[1]) + b[0] * (e[1] - a[1]) + e[0] * (a[1] - b[1]));
		double ux = ((a[0] * a[0] + a[1] * a[1]) * (b[1] - e[1]) + (b[0] * b[0] + b[1] * b[1]) * (e[1] - a[1]) +
		             (e[0] * e[0] + e[1] * e[1]) * (a[1] - b[1])) / den;
		double uy = ((a[0] * a[0] + a[1] * a[1]) * (e[0] - b[0]) + (b[0] * b[0] + b[1] * b[1]) * (a[0] - e[0]) +
		             (e[0] * e[0] + e[1] * e[1]) * (b[0] - a[0])) / den;
		double rad = hypot(a[0] - ux, a[1] - uy), th = fct_rng_uniform(&r) * 2 * M_PI;
		d[0] = ux + rad * cos(th);
		d[1] = uy + rad * sin(th);
		if (!isfinite(d[0]) || !isfinite(d[1]) || rad > 100)
			continue;
		int o = sgn(fct_orient2d(a, b, c));
		int ic = sgn(fct_incircle(a, b, e, d));
		zero += o == 0;
		bad += sgn(fct_orient2d(b, c, a)) != o;
		bad += sgn(fct_orient2d(c, a, b)) != o;
		bad += sgn(fct_orient2d(a, c, b)) != -o;
		bad += sgn(fct_incircle(b, e, a, d)) != ic;
		bad += sgn(fct_incircle(a, b, d, e)) != -ic;
		bad += sgn(fct_incircle(d, b, e, a)) != -ic;
		naive_bad += sgn(naive_orient(b, c, a)) != sgn(naive_orient(a, b, c));
		naive_bad += sgn(naive_incircle(a, b, d, e)) != -sgn(naive_incircle(a, b, e, d));
		static const int sc[] = {-900, 900};
		for (int s = 0; s < 2; s++) {
			double A[2], B[2], C[2], D[2], E[2];
			for (int q = 0; q < 2; q++) {
				A[q] = ldexp(a[q], sc[s]);
				B[q] = ldexp(b[q], sc[s]);
				C[q] = ldexp(c[q], sc[s]);
				D[q] = ldexp(d[q], sc[s]);
				E[q] = ldexp(e[q], sc[s]);
			}
			bad += sgn(fct_orient2d(A, B, C)) != o;
			bad += sgn(fct_incircle(A, B, E, D)) != ic;
		}
	}
	CHECK_INT(bad, 0);
	CHECK_MSG(zero > 1000, "exact zeros: %d", zero);
	CHECK_MSG(naive_bad > 100, "naive inconsistencies: %d", naive_bad);
}

int main(void)
{
	test_simple();
	test_near_collinear_grid();
	test_integer_configurations();
	test_cocircular();
	test_extreme();
	test_random_near_degenerate();
	CHECK_DONE();
}

/* predicates.c - exact orient2d and incircle: a floating-point filter with a
 * proven error bound, then exact evaluation.
 *
 * Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
 * Geometric Predicates" (1997): sections 2.3-2.8 (expansions: Two-Sum,
 * Two-Product with Dekker's split, Grow-Expansion, Scale-Expansion) and 4
 * (the predicates).  We keep his first stage (the filter) and then go
 * straight to an exact evaluation; his intermediate stages only make the
 * rare exact case cheaper.
 *
 * Notation: eps = 2^-53, the unit roundoff of round-to-nearest doubles.
 * Every +, -, * of doubles returns (x op y)(1 + d) with |d| <= eps as long
 * as the result is not subnormal; a sum or difference that falls in the
 * subnormal range is exact, a product there may be off by eta <= 2^-1075.
 *
 * Stage 1 (filter).  For orient2d, det = fl(fl(acx*bcy) - fl(acy*bcx)) with
 * acx = fl(ax - cx) etc.; each product carries three roundings (two inputs
 * and itself) and the difference one more, so
 *   |det - exact| <= 3 eps (1 + O(eps)) (|l| + |r|) + eps |det|
 * and the sign is certain once |det| > 4 eps (|l| + |r|) (computed).  For
 * incircle, with lift L = adx^2 + ady^2 (four roundings), D = bdx*cdy -
 * cdx*bdy (error <= 4 eps (|bdx*cdy| + |cdx*bdy|)), T = L*D (one more) and
 * two additions of the three T's, the error is at most
 *   (5 + 4 + 2) eps (1 + O(eps)) * sum_i L_i (|P1_i| + |P2_i|)
 * (the "permanent"); we accept when |det| > 12 eps * permanent.  Underflow
 * adds at most about 2 eta (sum L + sum |P|) + 4 eta, covered by adding
 * DBL_MIN * (sum L + sum |P| + 1) to the bound (DBL_MIN alone for orient2d).
 * Overflow makes det or the bound infinite or NaN, and the strict
 * comparisons below then refuse to decide.
 *
 * Stage 2 (exact, expansions).  Each difference is computed exactly as a
 * two-term expansion (Two-Diff), and the determinant is expanded from them
 * with Scale-Expansion (products) and Grow-Expansion (sums), dropping zero
 * components.  Both keep an expansion nonoverlapping and sorted by
 * increasing magnitude (Shewchuk's theorems 10 and 19 need nothing more),
 * so the last component carries the sign of the exact sum.  Dekker's split
 * and Two-Product are exact when no partial product underflows or
 * overflows.  When every coordinate is 0 or of magnitude in [2^-180, 2^180],
 * every component is an integer multiple of 2^-232 (degree 1), 2^-464
 * (degree 2) or 2^-928 (degree 4), all far above the subnormal range, and
 * below 2^800 in magnitude, so this holds.
 *
 * Stage 3 (exact, big integers).  Any other finite input (subnormal, tiny
 * or huge coordinates, or a mix) is scaled to integers by the smallest
 * power of two among its coordinates and the determinant is evaluated in
 * a fixed-size big-integer arithmetic of 32-bit limbs: coordinates need at
 * most 2098 bits, the incircle determinant at most 8400.  Slow, and meant
 * only for inputs no image coordinate will ever be. */
#include "geom/predicates.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "predicates.c needs doubles evaluated in double precision (FLT_EVAL_METHOD 0: SSE2, not x87)"
#endif

/* A fused a*b - c in Dekker's split (c - (c - a) with c = s*a) would break
 * it.  The Makefile passes -ffp-contract=off (also gcc's default in ISO C
 * mode); clang also honours the standard pragma, gcc warns about it. */
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

#define EPS 0x1p-53
#define O2_BOUND (4 * EPS)
#define IC_BOUND (12 * EPS)

/* ---- error-free transformations ---- */

/* a + b = x + y exactly, x = fl(a + b). */
static inline void two_sum(double a, double b, double *x, double *y)
{
	double s = a + b;
	double bv = s - a;
	double av = s - bv;
	*x = s;
	*y = (a - av) + (b - bv);
}

/* a - b = x + y exactly, x = fl(a - b). */
static inline void two_diff(double a, double b, double *x, double *y)
{
	double s = a - b;
	double bv = a - s;
	double av = s + bv;
	*x = s;
	*y = (a - av) + (bv - b);
}

/* Dekker: a = hi + lo, each with at most 26 significant bits. */
static inline void split(double a, double *hi, double *lo)
{
	double c = 134217729.0 * a; /* 2^27 + 1 */
	double big = c - a;
	*hi = c - big;
	*lo = a - *hi;
}

/* a * b = x + y exactly, x = fl(a * b). */
static inline void two_product(double a, double b, double *x, double *y)
{
	double p = a * b, ah, al, bh, bl;
	split(a, &ah, &al);
	split(b, &bh, &bl);
	double e1 = p - ah * bh;
	double e2 = e1 - al * bh;
	double e3 = e2 - ah * bl;
	*x = p;
	*y = al * bl - e3;
}

/* ---- expansions: nonoverlapping, increasing magnitude, no zeros ---- */

/* h = e + b, in place (h may be e); h has room for n + 1.  Returns length. */
static int exp_grow(double *h, const double *e, int n, double b)
{
	double q = b;
	int k = 0;
	for (int i = 0; i < n; i++) {
		double s, t;
		two_sum(q, e[i], &s, &t);
		if (t != 0)
			h[k++] = t;
		q = s;
	}
	if (q != 0)
		h[k++] = q;
	return k;
}

/* h += f (h holds hn components and has room for hn + fn).  Returns length. */
static int exp_add(double *h, int hn, const double *f, int fn)
{
	for (int j = 0; j < fn; j++)
		hn = exp_grow(h, h, hn, f[j]);
	return hn;
}

/* h = b * e; h has room for 2n.  Returns length. */
static int exp_scale(double *h, const double *e, int n, double b)
{
	if (n == 0 || b == 0)
		return 0;
	double q, t;
	int k = 0;
	two_product(e[0], b, &q, &t);
	if (t != 0)
		h[k++] = t;
	for (int i = 1; i < n; i++) {
		double p1, p0, s, s0;
		two_product(e[i], b, &p1, &p0);
		two_sum(q, p0, &s, &s0);
		if (s0 != 0)
			h[k++] = s0;
		two_sum(p1, s, &q, &s0);
		if (s0 != 0)
			h[k++] = s0;
	}
	if (q != 0)
		h[k++] = q;
	return k;
}

/* h = e * f; h has room for 2 en fn, tmp for 2 en.  Returns length. */
static int exp_mul(double *h, const double *e, int en, const double *f, int fn, double *tmp)
{
	int hn = 0;
	for (int j = 0; j < fn; j++) {
		int tn = exp_scale(tmp, e, en, f[j]);
		hn = exp_add(h, hn, tmp, tn);
	}
	return hn;
}

static void exp_negate(double *e, int n)
{
	for (int i = 0; i < n; i++)
		e[i] = -e[i];
}

/* The exact a - b as an expansion of one or two components (or none). */
static int exp_diff(double *h, double a, double b)
{
	double x, y;
	int k = 0;
	two_diff(a, b, &x, &y);
	if (y != 0)
		h[k++] = y;
	if (x != 0)
		h[k++] = x;
	return k;
}

static double exp_top(const double *e, int n)
{
	return n ? e[n - 1] : 0.0;
}

/* May the expansion stage be used: every coordinate 0 or in [2^-180, 2^180]? */
static int in_range(const double *v, int n)
{
	for (int i = 0; i < n; i++) {
		double a = fabs(v[i]);
		if (a != 0 && !(a >= 0x1p-180 && a <= 0x1p180))
			return 0;
	}
	return 1;
}

/* ---- big integers (stage 3) ---- */

#define BIG_LIMBS 280

struct big {
	int neg;            /* sign of a nonzero value */
	int n;              /* limbs in use; 0 means zero */
	uint32_t d[BIG_LIMBS];   /* magnitude, least significant limb first */
};

static void big_trim(struct big *a)
{
	while (a->n > 0 && a->d[a->n - 1] == 0)
		a->n--;
	if (a->n == 0)
		a->neg = 0;
}

/* a = sign * m * 2^shift. */
static void big_set(struct big *a, uint64_t m, int shift, int neg)
{
	int limb = shift / 32, bit = shift % 32;
	if (limb + 3 > BIG_LIMBS)
		abort();
	memset(a->d, 0, (size_t)(limb + 3) * sizeof a->d[0]);
	uint64_t lo = m << bit;
	uint64_t hi = bit ? m >> (64 - bit) : 0;
	a->d[limb] = (uint32_t)lo;
	a->d[limb + 1] = (uint32_t)(lo >> 32);
	a->d[limb + 2] = (uint32_t)hi;
	a->n = limb + 3;
	a->neg = neg;
	big_trim(a);
}

static int big_cmp_mag(const struct big *a, const struct big *b)
{
	if (a->n != b->n)
		return a->n < b->n ? -1 : 1;
	for (int i = a->n - 1; i >= 0; i--)
		if (a->d[i] != b->d[i])
			return a->d[i] < b->d[i] ? -1 : 1;
	return 0;
}

/* r = a + (negb ? -b : b); r must not alias a or b. */
static void big_add(struct big *r, const struct big *a, const struct big *b, int negb)
{
	int bneg = b->n ? b->neg ^ negb : 0;
	if (a->n == 0 || b->n == 0 || a->neg == bneg) {
		const struct big *x = a->n >= b->n ? a : b, *y = x == a ? b : a;
		int neg = a->n ? a->neg : bneg;
		uint64_t c = 0;
		if (x->n + 1 > BIG_LIMBS)
			abort();
		for (int i = 0; i < x->n; i++) {
			c += (uint64_t)x->d[i] + (i < y->n ? y->d[i] : 0);
			r->d[i] = (uint32_t)c;
			c >>= 32;
		}
		r->d[x->n] = (uint32_t)c;
		r->n = x->n + 1;
		r->neg = neg;
	} else {
		/* Opposite signs: subtract the smaller magnitude from the larger. */
		int c = big_cmp_mag(a, b);
		const struct big *x = c >= 0 ? a : b, *y = c >= 0 ? b : a;
		int neg = c >= 0 ? a->neg : bneg;
		int64_t borrow = 0;
		for (int i = 0; i < x->n; i++) {
			int64_t v = (int64_t)x->d[i] - (i < y->n ? y->d[i] : 0) - borrow;
			borrow = v < 0;
			r->d[i] = (uint32_t)(v + (borrow ? (int64_t)1 << 32 : 0));
		}
		r->n = x->n;
		r->neg = neg;
	}
	big_trim(r);
}

/* r = a * b; r must not alias a or b. */
static void big_mul(struct big *r, const struct big *a, const struct big *b)
{
	if (a->n == 0 || b->n == 0) {
		r->n = 0;
		r->neg = 0;
		return;
	}
	if (a->n + b->n > BIG_LIMBS)
		abort();
	memset(r->d, 0, (size_t)(a->n + b->n) * sizeof r->d[0]);
	for (int i = 0; i < a->n; i++) {
		uint64_t c = 0;
		for (int j = 0; j < b->n; j++) {
			c += (uint64_t)a->d[i] * b->d[j] + r->d[i + j];
			r->d[i + j] = (uint32_t)c;
			c >>= 32;
		}
		r->d[i + b->n] = (uint32_t)c;
	}
	r->n = a->n + b->n;
	r->neg = a->neg ^ b->neg;
	big_trim(r);
}

static double big_sign(const struct big *a)
{
	return a->n == 0 ? 0.0 : a->neg ? -1.0 : 1.0;
}

/* Coordinate v as odd integer m times 2^e (v != 0). */
static uint64_t mant_exp(double v, int *e)
{
	int k;
	double f = frexp(fabs(v), &k);
	uint64_t m = (uint64_t)ldexp(f, 53);
	k -= 53;
	while (!(m & 1)) {
		m >>= 1;
		k++;
	}
	*e = k;
	return m;
}

/* The n coordinates v as integers: v[i] = out[i] * 2^emin for a common emin
 * (emin >= -1074, and every value is below 2^1024, so at most 2098 bits). */
static void big_coords(struct big *out, const double *v, int n)
{
	int emin = INT32_MAX, e;
	for (int i = 0; i < n; i++) {
		if (v[i] != 0) {
			mant_exp(v[i], &e);
			if (e < emin)
				emin = e;
		}
	}
	for (int i = 0; i < n; i++) {
		if (v[i] == 0) {
			out[i].n = 0;
			out[i].neg = 0;
			continue;
		}
		uint64_t m = mant_exp(v[i], &e);
		big_set(&out[i], m, e - emin, v[i] < 0);
	}
}

/* ---- orient2d ---- */

static double orient2d_exact(const double a[2], const double b[2], const double c[2])
{
	double acx[2], acy[2], bcx[2], bcy[2], l[8], r[8], tmp[4], det[16];
	int nacx = exp_diff(acx, a[0], c[0]), nacy = exp_diff(acy, a[1], c[1]);
	int nbcx = exp_diff(bcx, b[0], c[0]), nbcy = exp_diff(bcy, b[1], c[1]);
	int nl = exp_mul(l, acx, nacx, bcy, nbcy, tmp);
	int nr = exp_mul(r, acy, nacy, bcx, nbcx, tmp);
	exp_negate(r, nr);
	memcpy(det, l, (size_t)nl * sizeof det[0]);
	int n = exp_add(det, nl, r, nr);
	return exp_top(det, n);
}

static double orient2d_big(const double a[2], const double b[2], const double c[2])
{
	double v[6] = {a[0], a[1], b[0], b[1], c[0], c[1]};
	struct big x[6], acx, acy, bcx, bcy, l, r, det;
	big_coords(x, v, 6);
	big_add(&acx, &x[0], &x[4], 1);
	big_add(&acy, &x[1], &x[5], 1);
	big_add(&bcx, &x[2], &x[4], 1);
	big_add(&bcy, &x[3], &x[5], 1);
	big_mul(&l, &acx, &bcy);
	big_mul(&r, &acy, &bcx);
	big_add(&det, &l, &r, 1);
	return big_sign(&det);
}

double fct_orient2d(const double a[2], const double b[2], const double c[2])
{
	double acx = a[0] - c[0], bcx = b[0] - c[0];
	double acy = a[1] - c[1], bcy = b[1] - c[1];
	double l = acx * bcy, r = acy * bcx;
	double det = l - r;
	double bound = O2_BOUND * (fabs(l) + fabs(r)) + DBL_MIN;
	if (det > bound || -det > bound)
		return det;
	double v[6] = {a[0], a[1], b[0], b[1], c[0], c[1]};
	if (in_range(v, 6))
		return orient2d_exact(a, b, c);
	return orient2d_big(a, b, c);
}

/* ---- incircle ---- */

/* h = x*y - z*w for two-term expansions (room for 16). */
static int exp_cross(double *h, const double *x, int nx, const double *y, int ny,
                     const double *z, int nz, const double *w, int nw)
{
	double p[8], q[8], tmp[4];
	int np = exp_mul(p, x, nx, y, ny, tmp);
	int nq = exp_mul(q, z, nz, w, nw, tmp);
	exp_negate(q, nq);
	memcpy(h, p, (size_t)np * sizeof h[0]);
	return exp_add(h, np, q, nq);
}

static double incircle_exact(const double a[2], const double b[2], const double c[2], const double d[2])
{
	double dx[3][2], dy[3][2];
	int ndx[3], ndy[3];
	const double *p[3] = {a, b, c};
	for (int i = 0; i < 3; i++) {
		ndx[i] = exp_diff(dx[i], p[i][0], d[0]);
		ndy[i] = exp_diff(dy[i], p[i][1], d[1]);
	}
	static const int nxt[3] = {1, 2, 0}, prv[3] = {2, 0, 1};
	double det[1536], cr[16], lift[16], sq[8], t[512], tmp[32];
	int ndet = 0;
	for (int i = 0; i < 3; i++) {
		int j = nxt[i], k = prv[i];
		/* lift_i * (dx_j dy_k - dx_k dy_j) */
		int ncr = exp_cross(cr, dx[j], ndx[j], dy[k], ndy[k], dx[k], ndx[k], dy[j], ndy[j]);
		int nl = exp_mul(lift, dx[i], ndx[i], dx[i], ndx[i], tmp);
		int nsq = exp_mul(sq, dy[i], ndy[i], dy[i], ndy[i], tmp);
		nl = exp_add(lift, nl, sq, nsq);
		int nt = exp_mul(t, lift, nl, cr, ncr, tmp);
		ndet = exp_add(det, ndet, t, nt);
	}
	return exp_top(det, ndet);
}

static double incircle_big(const double a[2], const double b[2], const double c[2], const double d[2])
{
	double v[8] = {a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]};
	struct big x[8], dx[3], dy[3], p, q, cr, s1, s2, lift, t, acc[2];
	big_coords(x, v, 8);
	for (int i = 0; i < 3; i++) {
		big_add(&dx[i], &x[2 * i], &x[6], 1);
		big_add(&dy[i], &x[2 * i + 1], &x[7], 1);
	}
	static const int nxt[3] = {1, 2, 0}, prv[3] = {2, 0, 1};
	int cur = 0;
	acc[0].n = 0;
	acc[0].neg = 0;
	for (int i = 0; i < 3; i++) {
		int j = nxt[i], k = prv[i];
		big_mul(&p, &dx[j], &dy[k]);
		big_mul(&q, &dx[k], &dy[j]);
		big_add(&cr, &p, &q, 1);
		big_mul(&s1, &dx[i], &dx[i]);
		big_mul(&s2, &dy[i], &dy[i]);
		big_add(&lift, &s1, &s2, 0);
		big_mul(&t, &lift, &cr);
		big_add(&acc[1 - cur], &acc[cur], &t, 0);
		cur = 1 - cur;
	}
	return big_sign(&acc[cur]);
}

double fct_incircle(const double a[2], const double b[2], const double c[2], const double d[2])
{
	double adx = a[0] - d[0], ady = a[1] - d[1];
	double bdx = b[0] - d[0], bdy = b[1] - d[1];
	double cdx = c[0] - d[0], cdy = c[1] - d[1];
	double bc1 = bdx * cdy, bc2 = cdx * bdy;
	double ca1 = cdx * ady, ca2 = adx * cdy;
	double ab1 = adx * bdy, ab2 = bdx * ady;
	double la = adx * adx + ady * ady;
	double lb = bdx * bdx + bdy * bdy;
	double lc = cdx * cdx + cdy * cdy;
	double det = la * (bc1 - bc2) + lb * (ca1 - ca2) + lc * (ab1 - ab2);
	double pa = fabs(bc1) + fabs(bc2), pb = fabs(ca1) + fabs(ca2), pc = fabs(ab1) + fabs(ab2);
	double perm = la * pa + lb * pb + lc * pc;
	double bound = IC_BOUND * perm + DBL_MIN * (la + lb + lc + pa + pb + pc + 1);
	if (det > bound || -det > bound)
		return det;
	double v[8] = {a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]};
	if (in_range(v, 8))
		return incircle_exact(a, b, c, d);
	return incircle_big(a, b, c, d);
}

/* test_areaflow.c - area decreasing flow (Sun et al. sec. 2): eq. (3)
 * against a numerical minimisation of eq. (2) on random umbrellas; eq. (4)
 * on hand-made votes (flat: 0, 90-degree crease: 1, folded sheet: 1);
 * the eigen-solver; whole-mesh runs: a bump flattened, a noisy folded grid
 * whose crease survives (and is rounded by Laplacian and Taubin), a closed
 * sphere that keeps its volume, bad input without NaN, and the same
 * result for any thread count. */
#include <stdlib.h>

#include "areaflow.h"
#include "check.h"
#include "geom.h"
#include "rng.h"

static struct fct_err err __attribute__((unused));

/* Eq. (2) for the umbrella: sum 4 S_i^2 + lambda |v + l n - v0|^2. */
static double energy(const double v[3], const double v0[3], const double n[3], const double *ring,
                     size_t ntri, double lambda, double l)
{
	double x[3], e = 0;
	fct_v3_axpy(x, v, l, n);
	for (size_t i = 0; i < ntri; i++) {
		double a[3], b[3], c[3];
		fct_v3_sub(a, ring + 6 * i, x);
		fct_v3_sub(b, ring + 6 * i + 3, x);
		fct_v3_cross(c, a, b);
		e += fct_v3_dot(c, c);   /* (2 S)^2 */
	}
	return e + lambda * fct_v3_dist2(x, v0);
}

static void test_step_vs_numeric(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	int worse = 0, close = 0;
	for (int t = 0; t < 200; t++) {
		size_t ntri = 3 + fct_rng_below(&r, 6);
		double ring[6 * 8], v[3], v0[3], n[3];
		for (size_t i = 0; i < 6 * ntri; i++)
			ring[i] = 2 * fct_rng_uniform(&r) - 1;
		for (int k = 0; k < 3; k++) {
			v[k] = 0.3 * fct_rng_normal(&r);
			v0[k] = v[k] + 0.2 * fct_rng_normal(&r);
			n[k] = fct_rng_normal(&r);
		}
		double len = sqrt(fct_v3_dot(n, n));
		for (int k = 0; k < 3; k++)
			n[k] /= len;
		double lambda = t % 4 == 0 ? 0 : fct_rng_uniform(&r) * 3;
		double l = fct_areaflow_step(v, v0, n, ring, ntri, lambda);
		/* golden-section search on [-20, 20]: f is a convex quadratic in l */
		double lo = -20, hi = 20, g = (sqrt(5) - 1) / 2;
		double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
		double f1 = energy(v, v0, n, ring, ntri, lambda, x1), f2 = energy(v, v0, n, ring, ntri, lambda, x2);
		for (int it = 0; it < 200; it++) {
			if (f1 < f2) {
				hi = x2, x2 = x1, f2 = f1;
				x1 = hi - g * (hi - lo);
				f1 = energy(v, v0, n, ring, ntri, lambda, x1);
			} else {
				lo = x1, x1 = x2, f1 = f2;
				x2 = lo + g * (hi - lo);
				f2 = energy(v, v0, n, ring, ntri, lambda, x2);
			}
		}
		double ln = (lo + hi) / 2;
		close += fabs(l - ln) <= 1e-6 * (1 + fabs(ln));
		/* and nothing beats it: f(l) <= f(l +- 1e-4) */
		double f = energy(v, v0, n, ring, ntri, lambda, l);
		worse += f > energy(v, v0, n, ring, ntri, lambda, l + 1e-4) ||
		         f > energy(v, v0, n, ring, ntri, lambda, l - 1e-4);
	}
	CHECK_INT(close, 200);
	CHECK_INT(worse, 0);
}

/* Hand cases of eq. (3). */
static void test_step_cases(void)
{
	/* A flat hexagonal ring at z = 0 and the vertex at height h, normal +z:
	 * with lambda = 0 the step is -h exactly (back into the plane); with
	 * v0 at h, l = -B h / (B + lambda), B the sum of squared ring edges. */
	double ring[36], v[3] = { 0, 0, 0.25 }, n[3] = { 0, 0, 1 };
	for (int i = 0; i < 6; i++) {
		double a0 = i * M_PI / 3, a1 = (i + 1) * M_PI / 3;
		ring[6 * i] = cos(a0), ring[6 * i + 1] = sin(a0), ring[6 * i + 2] = 0;
		ring[6 * i + 3] = cos(a1), ring[6 * i + 4] = sin(a1), ring[6 * i + 5] = 0;
	}
	CHECK_NEAR(fct_areaflow_step(v, v, n, ring, 6, 0), -0.25, 1e-15);
	CHECK_NEAR(fct_areaflow_step(v, v, n, ring, 6, 6), -0.25 * 6 / (6 + 6), 1e-15);
	/* Flipping the normal flips l: the move l n is the same. */
	double nm[3] = { 0, 0, -1 };
	CHECK_NEAR(fct_areaflow_step(v, v, nm, ring, 6, 2), 0.25 * 6 / 8, 1e-15);
	/* In the plane already: no move.  Only degenerate triangles (a = b)
	 * and lambda = 0: B = 0, no unique minimum: 0. */
	double flat[3] = { 0, 0, 0 };
	CHECK_NEAR(fct_areaflow_step(flat, flat, n, ring, 6, 1), 0, 1e-15);
	double deg[6] = { 1, 0, 0, 1, 0, 0 };
	CHECK(fct_areaflow_step(v, v, n, deg, 1, 0) == 0);
	CHECK(fct_areaflow_step(v, v, n, ring, 0, 0) == 0);
	/* Overflowing input gives 0, never NaN. */
	double huge[6] = { 1e300, 0, 0, 0, 1e300, 0 }, hv[3] = { 0, 0, 1e300 };
	double l = fct_areaflow_step(hv, v, n, huge, 1, 1);
	CHECK(isfinite(l));
}

static void test_eigen(void)
{
	double nu[3], e1[3];
	double d[6] = { 1, 0, 0, 3, 0, 2 };
	fct_sym3_eigen(d, nu, e1, NULL);
	CHECK_NEAR(nu[0], 3, 1e-12);
	CHECK_NEAR(nu[1], 2, 1e-12);
	CHECK_NEAR(nu[2], 1, 1e-12);
	CHECK_NEAR(fabs(e1[1]), 1, 1e-12);
	/* n n^T for n = (1, 2, 2)/3: eigenvalues 1, 0, 0, e1 = +-n */
	double t[6] = { 1.0 / 9, 2.0 / 9, 2.0 / 9, 4.0 / 9, 4.0 / 9, 4.0 / 9 };
	fct_sym3_eigen(t, nu, e1, NULL);
	/* the closed form keeps half the digits at a repeated eigenvalue */
	CHECK_NEAR(nu[0], 1, 1e-7);
	CHECK_NEAR(nu[1], 0, 1e-7);
	CHECK_NEAR(fabs(e1[0] * 1 + e1[1] * 2 + e1[2] * 2) / 3, 1, 1e-9);
	/* Repeated largest: diag(1, 1, 0); e1 in the xy plane, closest to the hint */
	double r2[6] = { 1, 0, 0, 1, 0, 0 }, hint[3] = { 1, 1, 1 };
	fct_sym3_eigen(r2, nu, e1, hint);
	CHECK_NEAR(nu[0], 1, 1e-7);
	CHECK_NEAR(nu[1], 1, 1e-7);
	CHECK_NEAR(nu[2], 0, 1e-12);
	CHECK_NEAR(e1[2], 0, 1e-12);
	CHECK_NEAR(e1[0], sqrt(0.5), 1e-12);
	/* Zero matrix: all zero, a unit e1 */
	double z[6] = { 0, 0, 0, 0, 0, 0 };
	fct_sym3_eigen(z, nu, e1, NULL);
	CHECK(nu[0] == 0 && nu[2] == 0);
	CHECK_NEAR(fct_v3_dot(e1, e1), 1, 1e-15);
}

/* Eq. (4) on hand-made votes around q = 0. */
static void test_crease_cases(void)
{
	double q[3] = { 0, 0, 0 }, p[3 * 16], n[3 * 16], mu[16];
	/* A flat disc of 8 faces in z = 0, normals +z: T = diag(0, 0, sum mu),
	 * s = 0 (the transported normal of a flat plane is itself). */
	for (int i = 0; i < 8; i++) {
		double a = i * M_PI / 4, r = 0.5 + 0.25 * (i % 3);
		p[3 * i] = r * cos(a), p[3 * i + 1] = r * sin(a), p[3 * i + 2] = 0;
		n[3 * i] = 0, n[3 * i + 1] = 0, n[3 * i + 2] = 1;
		mu[i] = exp(-r * r);
	}
	CHECK_NEAR(fct_crease_strength(q, p, n, mu, 8, 0.3), 0, 1e-12);
	/* A sharp 90-degree crease along the y axis, q on it: faces on the
	 * floor x > 0 (normal +z) and the wall x < 0 (normal +x, the wall is
	 * the plane x = 0... here z > 0 half of x = 0): the normals are
	 * transported unchanged (each face's plane contains q), so T =
	 * diag(w, 0, w), nu = (w, w, 0): s = 1. */
	for (int i = 0; i < 8; i++) {
		double y = -0.75 + 0.5 * (i / 2);
		if (i % 2 == 0) {   /* floor */
			p[3 * i] = 0.5, p[3 * i + 1] = y, p[3 * i + 2] = 0;
			n[3 * i] = 0, n[3 * i + 1] = 0, n[3 * i + 2] = 1;
		} else {            /* wall */
			p[3 * i] = 0, p[3 * i + 1] = y, p[3 * i + 2] = 0.5;
			n[3 * i] = 1, n[3 * i + 1] = 0, n[3 * i + 2] = 0;
		}
		mu[i] = 1;
	}
	CHECK_NEAR(fct_crease_strength(q, p, n, mu, 8, 0.3), 1, 1e-7);
	/* A shallow crease (10 degrees) is weak: s = sin^2(10)/1 ~ 0.03. */
	double c10 = cos(10 * M_PI / 180), s10 = sin(10 * M_PI / 180);
	for (int i = 0; i < 8; i++) {
		double y = -0.75 + 0.5 * (i / 2);
		if (i % 2) {   /* the other side tilted by 10 degrees about y */
			p[3 * i] = -0.5 * c10, p[3 * i + 1] = y, p[3 * i + 2] = 0.5 * s10;
			n[3 * i] = s10, n[3 * i + 1] = 0, n[3 * i + 2] = c10;
		} else {
			p[3 * i] = 0.5, p[3 * i + 1] = y, p[3 * i + 2] = 0;
			n[3 * i] = 0, n[3 * i + 1] = 0, n[3 * i + 2] = 1;
		}
	}
	double s = fct_crease_strength(q, p, n, mu, 8, 0.3);
	/* T = 4 (z z^T + m m^T), m the tilted normal: eigenvalues 4 (1 +- cos 10), 0 */
	CHECK_NEAR(s, (1 - c10) / (1 + c10), 1e-12);
	CHECK(s < 0.01);
	/* A sphere seen from its centre region: q on a unit sphere at the north
	 * pole, faces around it at 20 degrees: the arc transport brings every
	 * normal back to +z, s = 0 (curvature alone is no crease). */
	for (int i = 0; i < 8; i++) {
		double a = i * M_PI / 4, th = 20 * M_PI / 180;
		n[3 * i] = sin(th) * cos(a), n[3 * i + 1] = sin(th) * sin(a), n[3 * i + 2] = cos(th);
		p[3 * i] = n[3 * i], p[3 * i + 1] = n[3 * i + 1], p[3 * i + 2] = n[3 * i + 2] - 1;
		mu[i] = 1;
	}
	CHECK_NEAR(fct_crease_strength(q, p, n, mu, 8, 0.3), 0, 1e-12);
	/* A sheet folded back on itself (normals +z and -z): the mean normal
	 * vanishes, s = 1 by the delta rule. */
	for (int i = 0; i < 8; i++) {
		p[3 * i] = 0.5 * cos(i), p[3 * i + 1] = 0.5 * sin(i), p[3 * i + 2] = 0;
		n[3 * i] = 0, n[3 * i + 1] = 0, n[3 * i + 2] = i % 2 ? 1 : -1;
	}
	CHECK_NEAR(fct_crease_strength(q, p, n, mu, 8, 0.3), 1, 0);
	/* No votes, zero weights: 0. */
	CHECK(fct_crease_strength(q, p, n, mu, 0, 0.3) == 0);
	double zero[8] = { 0 };
	CHECK(fct_crease_strength(q, p, n, zero, 8, 0.3) == 0);
}

int main(void)
{
	test_step_vs_numeric();
	test_step_cases();
	test_eigen();
	test_crease_cases();
	CHECK_DONE();
}

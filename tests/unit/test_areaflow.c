/* test_areaflow.c - area decreasing flow (Sun et al. sec. 2): eq. (3)
 * against a numerical minimisation of eq. (2) on random umbrellas; eq. (4)
 * on hand-made votes (flat: 0, 90-degree crease: 1, folded sheet: 1);
 * the eigen-solver; whole-mesh runs: a bump flattened, a noisy folded grid
 * whose crease survives (and is rounded by Laplacian and Taubin), a closed
 * sphere that keeps its volume, bad input without NaN, and the same
 * result for any thread count. */
#include <stdlib.h>
#include <string.h>

#include "fusion/areaflow.h"
#include "check.h"
#include "geom/geom.h"
#include "core/rng.h"

static struct fct_err err;

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
	/* the closed form keeps half the digits at a repeated eigenvalue; the
	 * two smaller ones come from the plane across e1, to rounding */
	CHECK_NEAR(nu[0], 1, 1e-7);
	CHECK_NEAR(nu[1], 0, 1e-15);
	CHECK_NEAR(nu[2], 0, 1e-15);
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

/* Grid helpers ----------------------------------------------------------- */

/* An n x n grid of unit spacing folded at column n/2 into a floor (z = 0,
 * x >= 0) and a wall (x = 0, z >= 0): a 90-degree crease along y.  With
 * sigma > 0 every vertex moves along its true normal (the bisector on the
 * crease) by a normal deviate of that deviation. */
static void folded_grid(struct fct_mesh *m, int n, double sigma, uint64_t seed)
{
	struct fct_rng r;
	fct_rng_seed(&r, seed);
	fct_mesh_init(m);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			double x = i - n / 2, p[3] = { x >= 0 ? x : 0, j, x >= 0 ? 0 : -x };
			double nn[3] = { x > 0 ? 0 : x < 0 ? 1 : sqrt(0.5), 0, x > 0 ? 1 : x < 0 ? 0 : sqrt(0.5) };
			double e = sigma > 0 ? sigma * fct_rng_normal(&r) : 0;
			if (fct_mesh_add_vertex(m, p[0] + e * nn[0], p[1], p[2] + e * nn[2], &err) < 0)
				abort();
		}
	for (int j = 0; j + 1 < n; j++)
		for (int i = 0; i + 1 < n; i++) {
			uint32_t a = (uint32_t)(j * n + i), b = a + 1, c = a + (uint32_t)n, d = c + 1;
			uint32_t t1[3] = { a, b, d }, t2[3] = { a, d, c };
			if (fct_mesh_add_face(m, t1, 3, &err) < 0 || fct_mesh_add_face(m, t2, 3, &err) < 0)
				abort();
		}
}

/* Distance from p to the folded surface (the two half-planes). */
static double folded_dist(const double *p)
{
	double corner = sqrt(p[0] * p[0] + p[2] * p[2]);
	double df = p[0] >= 0 ? fabs(p[2]) : corner, dw = p[2] >= 0 ? fabs(p[0]) : corner;
	return df < dw ? df : dw;
}

static double mean_folded_dist(const struct fct_mesh *m)
{
	double s = 0;
	for (size_t v = 0; v < m->nv; v++)
		s += folded_dist(m->xyz + 3 * v);
	return s / (double)m->nv;
}

/* Unit normal of the least-squares plane of the vertices of grid columns
 * i0..i1 (all rows but the outer two). */
static void fit_normal(const struct fct_mesh *m, int n, int i0, int i1, double nrm[3])
{
	double c[3] = { 0, 0, 0 }, cov[6] = { 0 };
	int k = 0;
	for (int pass = 0; pass < 2; pass++)
		for (int j = 2; j < n - 2; j++)
			for (int i = i0; i <= i1; i++) {
				const double *p = m->xyz + 3 * (size_t)(j * n + i);
				if (pass == 0) {
					fct_v3_add(c, c, p);
					k++;
					continue;
				}
				double d[3] = { p[0] - c[0] / k, p[1] - c[1] / k, p[2] - c[2] / k };
				/* minus the scatter: its first eigenvector is the normal */
				cov[0] -= d[0] * d[0], cov[1] -= d[0] * d[1], cov[2] -= d[0] * d[2];
				cov[3] -= d[1] * d[1], cov[4] -= d[1] * d[2], cov[5] -= d[2] * d[2];
			}
	double nu[3];
	fct_sym3_eigen(cov, nu, nrm, NULL);
}

/* The angle in degrees between the planes fitted to the 4 columns on each
 * side next to the crease (the crease column left out): 90 for the truth. */
static double crease_angle(const struct fct_mesh *m, int n)
{
	double a[3], b[3];
	fit_normal(m, n, n / 2 + 1, n / 2 + 4, a);
	fit_normal(m, n, n / 2 - 4, n / 2 - 1, b);
	return acos(fabs(fct_v3_dot(a, b))) * 180 / M_PI;
}

static double run_method(const struct fct_mesh *in, enum fct_smooth_method method, int iterations,
                         struct fct_mesh *out)
{
	struct fct_areaflow_params p;
	fct_areaflow_params_default(&p);
	p.method = method;
	p.iterations = iterations;
	if (fct_mesh_copy(out, in, &err) || fct_areaflow(out, &p, NULL, NULL, &err))
		abort();
	return mean_folded_dist(out);
}

/* The noisy crease: areaflow lowers the distance to the true surface by
 * at least 40 percent and keeps the dihedral angle within 5 degrees, and
 * beats Laplacian and Taubin on both at the same iteration count. */
static void test_folded_crease(void)
{
	enum { N = 48 };
	struct fct_mesh noisy, af, lap, tau;
	folded_grid(&noisy, N, 0.2, 3);
	double raw = mean_folded_dist(&noisy);
	double raw_angle = crease_angle(&noisy, N);
	for (int it = 3; it <= 10; it += 7) {
		double d_af = run_method(&noisy, FCT_SMOOTH_AREAFLOW, it, &af);
		double d_lap = run_method(&noisy, FCT_SMOOTH_LAPLACIAN, it, &lap);
		double d_tau = run_method(&noisy, FCT_SMOOTH_TAUBIN, it, &tau);
		double a_af = crease_angle(&af, N), a_lap = crease_angle(&lap, N), a_tau = crease_angle(&tau, N);
		fprintf(stderr, "folded x%d: raw %.4f (%.2f deg) areaflow %.4f (%.2f) laplacian %.4f (%.2f) taubin %.4f (%.2f)\n",
		        it, raw, raw_angle, d_af, a_af, d_lap, a_lap, d_tau, a_tau);
		CHECK_MSG(d_af <= 0.6 * raw, "x%d: areaflow %g vs raw %g", it, d_af, raw);
		CHECK_MSG(fabs(a_af - 90) < 5, "x%d: areaflow angle %g", it, a_af);
		CHECK_MSG(fabs(a_af - 90) < fabs(a_lap - 90), "x%d: angle %g vs laplacian %g", it, a_af, a_lap);
		CHECK_MSG(fabs(a_af - 90) < fabs(a_tau - 90), "x%d: angle %g vs taubin %g", it, a_af, a_tau);
		CHECK_MSG(d_af < d_lap, "x%d: distance %g vs laplacian %g", it, d_af, d_lap);
		CHECK_MSG(d_af < d_tau, "x%d: distance %g vs taubin %g", it, d_af, d_tau);
		fct_mesh_free(&af);
		fct_mesh_free(&lap);
		fct_mesh_free(&tau);
	}
	fct_mesh_free(&noisy);
}

/* A closed UV sphere of radius 1: nlat rings between the poles, nlon
 * vertices per ring, outward faces. */
static void uv_sphere(struct fct_mesh *m, int nlat, int nlon)
{
	fct_mesh_init(m);
	if (fct_mesh_add_vertex(m, 0, 0, 1, &err) < 0)
		abort();
	for (int i = 1; i <= nlat; i++)
		for (int j = 0; j < nlon; j++) {
			double th = M_PI * i / (nlat + 1), ph = 2 * M_PI * j / nlon;
			if (fct_mesh_add_vertex(m, sin(th) * cos(ph), sin(th) * sin(ph), cos(th), &err) < 0)
				abort();
		}
	uint32_t south = (uint32_t)(1 + nlat * nlon);
	if (fct_mesh_add_vertex(m, 0, 0, -1, &err) < 0)
		abort();
	for (int j = 0; j < nlon; j++) {
		uint32_t a = (uint32_t)(1 + j), b = (uint32_t)(1 + (j + 1) % nlon);
		uint32_t t[3] = { 0, a, b };
		uint32_t base = (uint32_t)(1 + (nlat - 1) * nlon);
		uint32_t u[3] = { south, base + (uint32_t)((j + 1) % nlon), base + (uint32_t)j };
		if (fct_mesh_add_face(m, t, 3, &err) < 0 || fct_mesh_add_face(m, u, 3, &err) < 0)
			abort();
	}
	for (int i = 0; i + 1 < nlat; i++)
		for (int j = 0; j < nlon; j++) {
			uint32_t a = (uint32_t)(1 + i * nlon + j), b = (uint32_t)(1 + i * nlon + (j + 1) % nlon);
			uint32_t c = a + (uint32_t)nlon, d = b + (uint32_t)nlon;
			uint32_t t1[3] = { a, c, d }, t2[3] = { a, d, b };
			if (fct_mesh_add_face(m, t1, 3, &err) < 0 || fct_mesh_add_face(m, t2, 3, &err) < 0)
				abort();
		}
}

/* Enclosed volume (divergence theorem) and area of a triangle mesh. */
static void volume_area(const struct fct_mesh *m, double *vol, double *area)
{
	*vol = 0, *area = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *t = m->fvert + m->fstart[f];
		const double *a = m->xyz + 3 * (size_t)t[0], *b = m->xyz + 3 * (size_t)t[1];
		const double *c = m->xyz + 3 * (size_t)t[2];
		double x[3];
		fct_v3_cross(x, b, c);
		*vol += fct_v3_dot(a, x) / 6;
		*area += fct_triangle_area2(a, b, c) / 2;
	}
}

/* A closed noiseless sphere (90 rings of 180 vertices, mean edge 1/30 of
 * the radius) keeps its volume and area within 1 percent after 5
 * iterations: the pull back to the input (lambda) holds what mean
 * curvature flow would shrink.  The shrinkage grows as (edge / radius)^2
 * times 1/lambda: a sphere of 30 rings loses 6 percent of its volume at
 * the default lambda. */
static void test_sphere_shrinkage(void)
{
	struct fct_mesh s, af, lap;
	uv_sphere(&s, 90, 180);
	double v0, a0, v1, a1, v2, a2;
	volume_area(&s, &v0, &a0);
	struct fct_areaflow_params p;
	fct_areaflow_params_default(&p);
	struct fct_areaflow_stats st;
	p.iterations = 5;
	if (fct_mesh_copy(&af, &s, &err) || fct_areaflow(&af, &p, NULL, &st, &err))
		abort();
	volume_area(&af, &v1, &a1);
	p.method = FCT_SMOOTH_LAPLACIAN;
	p.iterations = st.iterations > 0 ? st.iterations : 1;
	if (fct_mesh_copy(&lap, &s, &err) || fct_areaflow(&lap, &p, NULL, NULL, &err))
		abort();
	volume_area(&lap, &v2, &a2);
	fprintf(stderr, "sphere: %d iterations: volume %.5f area %.5f; laplacian volume %.5f area %.5f\n",
	        st.iterations, v1 / v0, a1 / a0, v2 / v0, a2 / a0);
	CHECK_INT(st.iterations, 5);
	CHECK_MSG(fabs(v1 / v0 - 1) < 0.01, "volume ratio %g", v1 / v0);
	CHECK_MSG(fabs(a1 / a0 - 1) < 0.01, "area ratio %g", a1 / a0);
	fct_mesh_free(&s);
	fct_mesh_free(&af);
	fct_mesh_free(&lap);
}

static int all_finite(const struct fct_mesh *m)
{
	for (size_t i = 0; i < 3 * m->nv; i++)
		if (!isfinite(m->xyz[i]))
			return 0;
	return 1;
}

/* Bad input: no faces, isolated vertices, zero-area faces, a non-manifold
 * edge, repeated vertices, a polygon, coincident vertices, non-finite
 * coordinates (refused).  Never NaN; what cannot move does not. */
static void test_bad_input(void)
{
	struct fct_areaflow_params p;
	fct_areaflow_params_default(&p);
	struct fct_areaflow_stats st;
	double crease[17];
	struct fct_mesh m;

	/* No faces: unchanged, crease 0. */
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 1, 2, 3, &err);
	fct_mesh_add_vertex(&m, 4, 5, 6, &err);
	CHECK_INT(fct_areaflow(&m, &p, crease, &st, &err), 0);
	CHECK(m.xyz[0] == 1 && m.xyz[5] == 6);
	CHECK(crease[0] == 0 && crease[1] == 0);
	CHECK_INT(st.isolated, 2);
	CHECK_INT(st.iterations, 0);
	fct_mesh_free(&m);

	/* Empty mesh. */
	fct_mesh_init(&m);
	CHECK_INT(fct_areaflow(&m, &p, NULL, &st, &err), 0);
	fct_mesh_free(&m);

	/* Four triangles on one edge (non-manifold: held), a zero-area face, a
	 * face repeating a vertex, a quad, an isolated vertex, and two
	 * coincident vertices. */
	static const double pos[] = {
		0, 0, 0,  1, 0, 0,  0.5, 1, 0.1,  0.5, -1, 0.2,  0.5, 0, 1,  0.5, 0, -1,  /* 0-5 */
		2, 0, 0,  3, 0, 0,  4, 0, 0,       /* 6-8 collinear */
		5, 5, 5,                           /* 9 isolated */
		0, 3, 0,  1, 3, 0.3,  1, 4, 0,  0, 4, 0.2,   /* 10-13 quad */
		7, 7, 7,  7, 7, 7,  8, 7, 7,       /* 14-16 two coincident */
	};
	fct_mesh_init(&m);
	for (size_t i = 0; i < sizeof pos / sizeof *pos / 3; i++)
		fct_mesh_add_vertex(&m, pos[3 * i], pos[3 * i + 1], pos[3 * i + 2], &err);
	uint32_t f[][4] = { {0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {1, 0, 5}, {6, 7, 8}, {1, 6, 6},
	                    {10, 11, 12, 13}, {14, 15, 16} };
	for (size_t i = 0; i < 8; i++)
		fct_mesh_add_face(&m, f[i], i == 6 ? 4 : 3, &err);
	double before[3 * 17];
	memcpy(before, m.xyz, sizeof before);
	p.iterations = 5;
	CHECK_INT(fct_areaflow(&m, &p, crease, &st, &err), 0);
	CHECK(all_finite(&m));
	for (int v = 0; v < 17; v++)
		CHECK_MSG(isfinite(crease[v]) && crease[v] >= 0 && crease[v] <= 1, "crease %d: %g", v, crease[v]);
	CHECK_INT(st.isolated, 1);
	CHECK_INT(st.held, 2);   /* 0 and 1, on the edge of four faces */
	CHECK(!memcmp(m.xyz, before, 6 * sizeof *before));   /* 0, 1 held */
	CHECK(!memcmp(m.xyz + 27, before + 27, 3 * sizeof *before));   /* isolated */
	CHECK(!memcmp(m.xyz + 18, before + 18, 9 * sizeof *before));   /* collinear: no normal */
	/* the same for the baselines */
	p.method = FCT_SMOOTH_TAUBIN;
	CHECK_INT(fct_areaflow(&m, &p, crease, &st, &err), 0);
	CHECK(all_finite(&m));
	fct_mesh_free(&m);

	/* Non-finite coordinates are refused, the mesh unchanged. */
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0, 0, 0, &err);
	fct_mesh_add_vertex(&m, NAN, 0, 0, &err);
	fct_mesh_add_vertex(&m, 0, 1, 0, &err);
	uint32_t t[3] = { 0, 1, 2 };
	fct_mesh_add_face(&m, t, 3, &err);
	p.method = FCT_SMOOTH_AREAFLOW;
	CHECK_INT(fct_areaflow(&m, &p, NULL, &st, &err), -1);
	CHECK_STR(err.msg, "vertex 1: coordinate is not finite");
	fct_mesh_free(&m);

	/* Huge coordinates: no overflow into NaN. */
	folded_grid(&m, 8, 0.3, 5);
	for (size_t i = 0; i < 3 * m.nv; i++)
		m.xyz[i] *= 1e200;
	CHECK_INT(fct_areaflow(&m, &p, NULL, &st, &err), 0);
	CHECK(all_finite(&m));
	fct_mesh_free(&m);
}

/* The same output, byte for byte, for 1, 2 and 5 threads. */
static void test_threads(void)
{
	struct fct_mesh in, a, b;
	folded_grid(&in, 64, 0.3, 9);
	struct fct_areaflow_params p;
	fct_areaflow_params_default(&p);
	p.iterations = 3;
	double *ca = malloc(sizeof *ca * in.nv), *cb = malloc(sizeof *cb * in.nv);
	p.threads = 1;
	if (!ca || !cb || fct_mesh_copy(&a, &in, &err) || fct_areaflow(&a, &p, ca, NULL, &err))
		abort();
	for (int t = 2; t <= 5; t += 3) {
		p.threads = t;
		if (fct_mesh_copy(&b, &in, &err) || fct_areaflow(&b, &p, cb, NULL, &err))
			abort();
		CHECK(!memcmp(a.xyz, b.xyz, sizeof *a.xyz * 3 * a.nv));
		CHECK(!memcmp(ca, cb, sizeof *ca * a.nv));
		fct_mesh_free(&b);
	}
	free(ca);
	free(cb);
	fct_mesh_free(&a);
	fct_mesh_free(&in);
}

int main(void)
{
	test_sphere_shrinkage();
	test_bad_input();
	test_threads();
	test_folded_crease();
	test_step_vs_numeric();
	test_step_cases();
	test_eigen();
	test_crease_cases();
	CHECK_DONE();
}

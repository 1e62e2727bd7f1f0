/* planes.c - the patch property and plane element (see planes.h). */
#include "geom/planes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

int fct_planes_get(const struct fct_mesh *m, struct fct_plane **planes, size_t *n,
                   struct fct_err *err)
{
	*planes = NULL, *n = 0;
	const struct fct_elem *e = fct_mesh_find_elem(m, "plane");
	if (!e)
		return 0;
	static const char *const names[] = { "nx", "ny", "nz", "d" };
	const struct fct_prop *p[4];
	for (int k = 0; k < 4; k++) {
		p[k] = fct_elem_find(e, names[k]);
		if (!p[k] || p[k]->count_type != FCT_NONE)
			return fct_fail(err, "element plane: no scalar property %s", names[k]);
	}
	const struct fct_prop *count = fct_elem_find(e, "count"), *rms = fct_elem_find(e, "rms");
	if (count && count->count_type != FCT_NONE)
		count = NULL;
	if (rms && rms->count_type != FCT_NONE)
		rms = NULL;
	struct fct_plane *pl = fct_alloc_array(e->count, sizeof *pl, err);
	if (!pl)
		return -1;
	for (size_t i = 0; i < e->count; i++) {
		for (int k = 0; k < 3; k++)
			pl[i].n[k] = fct_prop_get(p[k], i);
		pl[i].d = fct_prop_get(p[3], i);
		/* Checked before the cast: a NaN or 1e300 count is undefined as a long. */
		double c = count ? fct_prop_get(count, i) : 0;
		if (!(c >= 0 && c <= INT32_MAX && c == floor(c))) {
			free(pl);
			return fct_fail(err, "element plane %zu: count %.9g is not a count of points", i, c);
		}
		pl[i].count = (long)c;
		pl[i].rms = rms ? fct_prop_get(rms, i) : 0;
		double len = sqrt(pl[i].n[0] * pl[i].n[0] + pl[i].n[1] * pl[i].n[1] + pl[i].n[2] * pl[i].n[2]);
		if (!(fabs(len - 1) <= 1e-6) || !isfinite(pl[i].d)) {
			free(pl);
			return fct_fail(err, "element plane %zu: the normal is not of unit length, or d is not finite",
			                i);
		}
	}
	*planes = pl, *n = e->count;
	return 0;
}

int fct_planes_set(struct fct_mesh *m, const struct fct_plane *planes, size_t n,
                   struct fct_err *err)
{
	fct_mesh_remove_elem(m, "plane");
	struct fct_elem *e = fct_mesh_add_elem(m, "plane", n, err);
	if (!e)
		return -1;
	static const char *const names[] = { "nx", "ny", "nz", "d", "count", "rms" };
	for (int k = 0; k < 6; k++)
		if (!fct_elem_add_scalar(e, names[k], k == 4 ? FCT_INT32 : FCT_FLOAT64, err))
			return -1;
	/* Adding properties may have moved them: look them up once, now. */
	struct fct_prop *p[6];
	for (int k = 0; k < 6; k++)
		p[k] = fct_elem_find(e, names[k]);
	for (size_t i = 0; i < n; i++) {
		for (int k = 0; k < 3; k++)
			fct_prop_set(p[k], i, planes[i].n[k]);
		fct_prop_set(p[3], i, planes[i].d);
		fct_prop_set(p[4], i, (double)planes[i].count);
		fct_prop_set(p[5], i, planes[i].rms);
	}
	return 0;
}

int fct_patches_get(const struct fct_mesh *m, int32_t **patch, int *present, long nplanes,
                    struct fct_err *err)
{
	*patch = NULL, *present = 0;
	const struct fct_prop *p = fct_elem_find(&m->face, "patch");
	if (!p)
		return 0;
	if (p->count_type != FCT_NONE)
		return fct_fail(err, "face property patch is a list");
	int32_t *out = fct_alloc_array(m->nf, sizeof *out, err);
	if (!out)
		return -1;
	for (size_t f = 0; f < m->nf; f++) {
		double v = fct_prop_get(p, f);
		if (!(v == floor(v) && v >= -1 && (nplanes < 0 || v < nplanes) && v <= INT32_MAX)) {
			free(out);
			return fct_fail(err, "face %zu: patch %.17g is not -1 or a plane (%ld planes)", f, v,
			                nplanes);
		}
		out[f] = (int32_t)v;
	}
	*patch = out, *present = 1;
	return 0;
}

int fct_patches_set(struct fct_mesh *m, const int32_t *patch, struct fct_err *err)
{
	struct fct_prop *p = fct_elem_add_scalar(&m->face, "patch", FCT_INT32, err);
	if (!p)
		return -1;
	if (m->nf)
		memcpy(p->data, patch, m->nf * sizeof *patch);
	return 0;
}

static int integral(double v, double lo, double hi)
{
	return v == floor(v) && v >= lo && v <= hi;
}

int fct_wires_get(const struct fct_mesh *m, long nplanes, struct fct_wire **wires, size_t *n,
                  int *present, struct fct_err *err)
{
	*wires = NULL, *n = 0, *present = 0;
	const struct fct_elem *e = fct_mesh_find_elem(m, "edge");
	if (!e)
		return 0;
	static const char *const names[] = { "vertex1", "vertex2", "patch1", "patch2" };
	const struct fct_prop *ep[4];
	for (int k = 0; k < 4; k++) {
		ep[k] = fct_elem_find(e, names[k]);
		if (!ep[k] || ep[k]->count_type != FCT_NONE)
			return fct_fail(err, "element edge: no scalar property %s", names[k]);
	}
	struct fct_wire *w = fct_alloc_array(e->count, sizeof *w, err);
	if (!w && e->count)
		return -1;
	double maxv = (double)m->nv - 1, maxp = nplanes >= 0 ? (double)nplanes - 1 : (double)INT32_MAX;
	for (size_t i = 0; i < e->count; i++) {
		double v1 = fct_prop_get(ep[0], i), v2 = fct_prop_get(ep[1], i);
		double p1 = fct_prop_get(ep[2], i), p2 = fct_prop_get(ep[3], i);
		if (!integral(v1, 0, maxv) || !integral(v2, 0, maxv)) {
			free(w);
			return fct_fail(err, "edge %zu: vertex %.17g or %.17g is not one of the %zu vertices", i,
			                v1, v2, m->nv);
		}
		if (!integral(p1, -1, maxp) || !integral(p2, -1, maxp)) {
			free(w);
			if (nplanes >= 0)
				return fct_fail(err, "edge %zu: patch %.17g or %.17g is neither -1 nor a plane (%ld planes)",
				                i, p1, p2, nplanes);
			return fct_fail(err, "edge %zu: patch %.17g or %.17g is not -1 or a patch number", i, p1, p2);
		}
		if (v1 == v2) {
			free(w);
			return fct_fail(err, "edge %zu: both ends are vertex %.0f", i, v1);
		}
		if (p1 < 0 && p2 < 0) {
			free(w);
			return fct_fail(err, "edge %zu: no patch on either side", i);
		}
		w[i] = (struct fct_wire){ (uint32_t)v1, (uint32_t)v2, (int32_t)p1, (int32_t)p2 };
	}
	*wires = w, *n = e->count, *present = 1;
	return 0;
}

int fct_wires_set(struct fct_mesh *m, const struct fct_wire *wires, size_t n, struct fct_err *err)
{
	fct_mesh_remove_elem(m, "edge");
	struct fct_elem *e = fct_mesh_add_elem(m, "edge", n, err);
	if (!e)
		return -1;
	static const char *const names[] = { "vertex1", "vertex2", "patch1", "patch2" };
	int32_t *col[4];
	for (int k = 0; k < 4; k++) {
		struct fct_prop *p = fct_elem_add_scalar(e, names[k], FCT_INT32, err);
		if (!p)
			return -1;
		col[k] = (int32_t *)p->data;
	}
	for (size_t i = 0; i < n; i++) {
		col[0][i] = (int32_t)wires[i].v1, col[1][i] = (int32_t)wires[i].v2;
		col[2][i] = wires[i].p1, col[3][i] = wires[i].p2;
	}
	return 0;
}

void fct_plane_frame(const double n[3], double e1[3], double e2[3])
{
	/* Start from the axis least aligned with n, so e1 is well defined. */
	double a[3] = { 0, 0, 0 };
	int k = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
	a[k] = 1;
	fct_v3_cross(e1, a, n);
	double l = sqrt(fct_v3_dot(e1, e1));
	e1[0] /= l, e1[1] /= l, e1[2] /= l;
	fct_v3_cross(e2, n, e1);
}

/* Eigen solvers ----------------------------------------------------------- */

/* The smallest root of the characteristic polynomial by Halley's method
 * from 0, where the polynomial is positive, decreasing and convex up to the
 * root: the iterates rise to it, in two or three steps when the points are
 * nearly planar (the common case here), some 40 ns.  Jacobi rotations take
 * over when the iteration is slow (nearly equal eigenvalues). */
double fct_sym3_min_eigenvalue(const double s[6])
{
	double a = s[0], b = s[1], c = s[2], d = s[3], e = s[4], f = s[5];
	double t = a + b + c;
	double m = a * b - d * d + b * c - e * e + a * c - f * f;
	double det = a * (b * c - e * e) - d * (d * c - e * f) + f * (d * e - b * f);
	if (!(det > 0) || !(m > 0))
		return 0;   /* singular, up to rounding: a point, a line or a plane */
	double x = 0;
	for (int it = 0; it < 12; it++) {
		double px = ((t - x) * x - m) * x + det;
		double dp = (2 * t - 3 * x) * x - m;
		double den = 2 * dp * dp - px * (2 * t - 6 * x);
		if (!(dp < 0) || !(den > 0))
			break;
		double nx = x - 2 * px * dp / den;
		if (!(nx > x))
			return x;
		if (nx - x <= 1e-16 * t)   /* below the rounding of the entries */
			return nx;
		x = nx;
	}
	/* Nearly equal eigenvalues (the polynomial is ill-conditioned there):
	 * Jacobi rotations. */
	double m3[3][3] = { { a, d, f }, { d, b, e }, { f, e, c } }, v[3][3], ev[3];
	fct_sym3_jacobi(v, ev, m3);
	double l = fmin(ev[0], fmin(ev[1], ev[2]));
	return l > 0 ? l : 0;
}

void fct_sym3_jacobi(double v[3][3], double ev[3], double a[3][3])
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			v[i][j] = i == j;
	for (int sweep = 0; sweep < 64; sweep++) {
		double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
		double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
		if (off == 0 || off <= 1e-36 * diag)
			break;
		for (int p = 0; p < 2; p++)
			for (int q = p + 1; q < 3; q++) {
				if (a[p][q] == 0)
					continue;
				double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
				double t = 1 / (fabs(theta) + sqrt(theta * theta + 1));
				if (theta < 0)
					t = -t;
				double c = 1 / sqrt(t * t + 1), s = t * c;
				for (int k = 0; k < 3; k++) {   /* columns p, q */
					double akp = a[k][p], akq = a[k][q];
					a[k][p] = c * akp - s * akq;
					a[k][q] = s * akp + c * akq;
				}
				for (int k = 0; k < 3; k++) {   /* rows p, q */
					double apk = a[p][k], aqk = a[q][k];
					a[p][k] = c * apk - s * aqk;
					a[q][k] = s * apk + c * aqk;
				}
				for (int k = 0; k < 3; k++) {
					double vkp = v[k][p], vkq = v[k][q];
					v[k][p] = c * vkp - s * vkq;
					v[k][q] = s * vkp + c * vkq;
				}
			}
	}
	for (int i = 0; i < 3; i++)
		ev[i] = a[i][i];
}

double fct_plane_fit(struct fct_plane *pl, const double c[3], const double s[6])
{
	double a[3][3] = {
		{ s[0], s[3], s[5] },
		{ s[3], s[1], s[4] },
		{ s[5], s[4], s[2] },
	}, v[3][3], ev[3];
	fct_sym3_jacobi(v, ev, a);
	int k = 0;   /* the smallest; ties to the lower index */
	for (int i = 1; i < 3; i++)
		if (ev[i] < ev[k])
			k = i;
	double n[3] = { v[0][k], v[1][k], v[2][k] };
	double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
	for (int i = 0; i < 3; i++)
		pl->n[i] = n[i] / len;
	pl->d = -(pl->n[0] * c[0] + pl->n[1] * c[1] + pl->n[2] * c[2]);
	return ev[k] > 0 ? ev[k] : 0;
}

/* cylview.c - planar views of a cylindrical panorama (see cylview.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

#include "render/cylview.h"
#include "render/texmap.h"
#include "io/header.h"
#include "io/output.h"
#include "core/path.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void fct_cylview_params_default(struct fct_cylview_params *p)
{
	memset(p, 0, sizeof *p);
	p->count = 8;
	p->fov = 90;
}

/* The panorama's rows in heights h: its top and bottom pixel edges. */
static void pano_heights(const struct fct_camera *c, double *hmin, double *hmax)
{
	*hmin = (-0.5 - c->cy) / c->f;
	*hmax = (c->height - 0.5 - c->cy) / c->f;
}

static int check_pano_camera(const struct fct_camera *c, struct fct_err *err)
{
	if (c->kind != FCT_CAMERA_CYLINDRICAL)
		return fct_fail(err, "the panorama's camera is not cylindrical");
	if (c->width < 1 || c->height < 1)
		return fct_fail(err, "the panorama's camera has no size");
	if (!(c->f > 0 && isfinite(c->f) && isfinite(c->cy) && isfinite(c->theta0)))
		return fct_fail(err, "the panorama's camera has a bad f, cy or theta0");
	return 0;
}

int fct_cylview_plan(const struct fct_camera *pano, const struct fct_cylview_params *p,
                     struct fct_cylview *views, struct fct_err *err)
{
	if (check_pano_camera(pano, err))
		return -1;
	if (p->count < 1 || p->count > FCT_CYLVIEW_MAX_COUNT)
		return fct_fail(err, "%d views: the count must be in [1, %d]", p->count,
		                FCT_CYLVIEW_MAX_COUNT);
	if (!(p->fov > 0 && p->fov < 180))
		return fct_fail(err, "field of view %g degrees: it must be in (0, 180)", p->fov);
	if (!(p->step >= 0 && p->step <= 360) || !isfinite(p->yaw0))
		return fct_fail(err, "bad step or yaw");
	if (p->width < 0 || p->height < 0 || p->width > FCT_IMAGE_MAX_SIDE ||
	    p->height > FCT_IMAGE_MAX_SIDE)
		return fct_fail(err, "bad view size");
	double fov = p->fov * M_PI / 180;
	double step = (p->step > 0 ? p->step : 360.0 / p->count) * M_PI / 180;
	double F, W;
	if (p->width > 0) {
		W = p->width;
		F = W / (2 * tan(fov / 2));
	} else {
		F = pano->width / (2 * M_PI);
		W = ceil(2 * F * tan(fov / 2) - 1e-9);
	}
	double a = step / 2 < fov / 2 ? (step / 2 + fov / 2) / 2 : fov / 2;
	double rc = 1 / cos(a), hmin, hmax;
	pano_heights(pano, &hmin, &hmax);
	double H = p->height > 0 ? p->height : ceil(F * (hmax - hmin) * rc - 1e-9);
	if (!(W >= 1 && H >= 1))
		return fct_fail(err, "views of %.0fx%.0f pixels: empty", W, H);
	/* A view's pixels beyond a few per panorama pixel only interpolate:
	 * near 180 degrees its edges stretch without end (179.999 degrees of a
	 * 1024 x 256 panorama asked 37351042 x 461 pixels), and a size may ask
	 * gigabytes of a small picture. */
	double most = fmax(FCT_CYLVIEW_MAX_ZOOM * pano->width * (double)pano->height, 1 << 20);
	if (W * H > most)
		return fct_fail(err, "views of %.0fx%.0f pixels from a %dx%d panorama: more than %d "
		                "times its pixels%s", W, H, pano->width, pano->height, FCT_CYLVIEW_MAX_ZOOM,
		                p->width > 0 ? "" : " (a field of view near 180 degrees stretches a "
		                "view's edges without end)");
	if (!(W <= FCT_IMAGE_MAX_SIDE && H <= FCT_IMAGE_MAX_SIDE))
		return fct_fail(err, "views of %.0fx%.0f pixels: too large", W, H);
	if (W * H > (double)FCT_IMAGE_MAX_PIXELS)
		return fct_fail(err, "views of %.0fx%.0f pixels: too large", W, H);
	/* The horizon's relative place: top edge -0.5 at hmin (scaled by the
	 * automatic height's rc, or spread over the given height). */
	double cyv = p->height > 0 ? -0.5 - H * hmin / (hmax - hmin) : -0.5 - F * hmin * rc;
	for (int k = 0; k < p->count; k++) {
		struct fct_cylview *v = &views[k];
		memset(v, 0, sizeof *v);
		double yaw = fmod(p->yaw0 * M_PI / 180 + k * step, 2 * M_PI);
		if (yaw < 0)
			yaw += 2 * M_PI;
		v->yaw = yaw;
		v->cam.kind = FCT_CAMERA_PINHOLE;
		v->cam.width = (int)W, v->cam.height = (int)H;
		v->cam.fx = v->cam.fy = F;
		v->cam.cx = (W - 1) / 2;
		v->cam.cy = cyv;
		double c = cos(yaw), s = sin(yaw);
		double r[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
		memcpy(v->rot, r, sizeof r);
	}
	return 0;
}

int fct_cylview_project(const struct fct_cylview *view, const double p[3], double *u, double *v,
                        double *depth)
{
	const double *r = view->rot;
	double x = r[0] * p[0] + r[3] * p[1] + r[6] * p[2];
	double y = r[1] * p[0] + r[4] * p[1] + r[7] * p[2];
	double z = r[2] * p[0] + r[5] * p[1] + r[8] * p[2];
	if (!(z > 0))
		return 0;
	*u = view->cam.cx + view->cam.fx * x / z;
	*v = view->cam.cy + view->cam.fy * y / z;
	*depth = z;
	return 1;
}

void fct_cylview_pose(const struct fct_cylview *view, const double *pano_pose, double pose[12])
{
	static const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
	const double *P = pano_pose ? pano_pose : id;
	const double *r = view->rot;
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			pose[4 * i + j] = P[4 * i] * r[j] + P[4 * i + 1] * r[3 + j] + P[4 * i + 2] * r[6 + j];
		pose[4 * i + 3] = P[4 * i + 3];
	}
}

/* Per column of a view: the two panorama columns and the weight of the
 * second, and the scale from view row offset to panorama row offset. */
struct column {
	int i0, i1;
	float w;
	double a;
};

#define RENDER_LOOP(T, ROUND)                                                                   \
	do {                                                                                    \
		const T *src = img->data;                                                       \
		T *dst = out->data;                                                             \
		for (int y = 0; y < Hv; y++) {                                                  \
			double dy = y - cyv;                                                    \
			T *row = dst + (size_t)y * Wv * nc;                                     \
			for (int x = 0; x < Wv; x++) {                                          \
				const struct column *c = &col[x];                               \
				double vp = cyp + c->a * dy;                                    \
				T *o = row + (size_t)x * nc;                                    \
				if (!(vp >= -0.5 && vp <= Hp - 0.5))                            \
					continue;                                               \
				int j0 = vp <= 0 ? 0 : (int)vp, j1;                             \
				float wv;                                                       \
				if (j0 >= Hp - 1) {                                             \
					j0 = j1 = Hp - 1;                                       \
					wv = 0;                                                 \
				} else {                                                        \
					j1 = j0 + 1;                                            \
					wv = vp <= 0 ? 0 : (float)(vp - j0);                    \
				}                                                               \
				const T *p00 = src + ((size_t)j0 * Wp + c->i0) * nc;            \
				const T *p01 = src + ((size_t)j0 * Wp + c->i1) * nc;            \
				const T *p10 = src + ((size_t)j1 * Wp + c->i0) * nc;            \
				const T *p11 = src + ((size_t)j1 * Wp + c->i1) * nc;            \
				float wu = c->w;                                                \
				float w00 = (1 - wu) * (1 - wv), w01 = wu * (1 - wv);           \
				float w10 = (1 - wu) * wv, w11 = wu * wv;                       \
				for (int k = 0; k < nc; k++)                                    \
					o[k] = (T)(w00 * p00[k] + w01 * p01[k] + w10 * p10[k] + \
					           w11 * p11[k] + ROUND);                       \
			}                                                                       \
		}                                                                               \
	} while (0)

int fct_cylview_render(const struct fct_image *img, const struct fct_camera *pano,
                       const struct fct_cylview *view, struct fct_image *out,
                       struct fct_err *err)
{
	memset(out, 0, sizeof *out);
	if (check_pano_camera(pano, err))
		return -1;
	if (img->width != pano->width || img->height != pano->height)
		return fct_fail(err, "the panorama is %dx%d, its camera %dx%d", img->width,
		                img->height, pano->width, pano->height);
	const struct fct_camera *vc = &view->cam;
	int Wv = vc->width, Hv = vc->height, Wp = img->width, Hp = img->height;
	int nc = img->channels;
	struct column *col = fct_alloc_array((size_t)Wv, sizeof *col, err);
	if (!col)
		return -1;
	if (fct_image_alloc(out, Wv, Hv, nc, img->type, err)) {
		free(col);
		return -1;
	}
	double per_rad = Wp / (2 * M_PI);
	for (int x = 0; x < Wv; x++) {
		double xn = (x - vc->cx) / vc->fx;
		double th = view->yaw + atan(xn);
		double up = (th - pano->theta0) * per_rad;
		up -= Wp * floor(up / Wp);
		if (!(up >= 0 && up < Wp))
			up = 0;
		int i0 = (int)up;
		if (i0 > Wp - 1)
			i0 = Wp - 1;
		col[x].i0 = i0;
		col[x].i1 = i0 + 1 < Wp ? i0 + 1 : 0;
		col[x].w = (float)(up - i0);
		col[x].a = pano->f / (vc->fy * sqrt(1 + xn * xn));
	}
	double cyv = vc->cy, cyp = pano->cy;
	switch (img->type) {
	case FCT_PIX_U8: RENDER_LOOP(uint8_t, 0.5f); break;
	case FCT_PIX_U16: RENDER_LOOP(uint16_t, 0.5f); break;
	case FCT_PIX_F32: RENDER_LOOP(float, 0.0f); break;
	}
	free(col);
	return 0;
}

int fct_cylview_check_panorama(const struct fct_image *img, const struct fct_camera *pano,
                               int check_seam, double *seam_ratio, struct fct_err *err)
{
	if (seam_ratio)
		*seam_ratio = 0;
	if (check_pano_camera(pano, err))
		return -1;
	if (img->width != pano->width || img->height != pano->height)
		return fct_fail(err, "the image is %dx%d but its cylindrical camera, 360 degrees "
		                "round, is %dx%d", img->width, img->height, pano->width, pano->height);
	int W = img->width, H = img->height, nc = img->channels;
	if (W < 8)
		return 0;
	/* Alpha takes no part. */
	int ncol = nc == 2 || nc == 4 ? nc - 1 : nc;
	double *d = fct_alloc_array((size_t)W, sizeof *d, err);
	if (!d)
		return -1;
	double lo = HUGE_VAL, hi = -HUGE_VAL;
	for (int x = 0; x < W; x++) {
		int x1 = x + 1 < W ? x + 1 : 0;
		double s = 0;
		for (int y = 0; y < H; y++) {
			size_t a = ((size_t)y * W + x) * nc, b = ((size_t)y * W + x1) * nc;
			for (int c = 0; c < ncol; c++) {
				double p = fct_image_sample(img, a + c), q = fct_image_sample(img, b + c);
				if (isfinite(p) && isfinite(q))
					s += fabs(p - q);
				if (isfinite(p))
					lo = p < lo ? p : lo, hi = p > hi ? p : hi;
			}
		}
		d[x] = s / ((double)H * ncol);
	}
	double seam = d[W - 1];
	qsort(d, (size_t)W - 1, sizeof *d, fct_cmp_double);
	double p99 = d[(size_t)floor(0.99 * (W - 2))];
	free(d);
	double range = img->type == FCT_PIX_U8 ? 255 : img->type == FCT_PIX_U16 ? 65535
	             : (hi > lo ? hi - lo : 0);
	double ratio = p99 > 0 ? seam / p99 : seam > 0 ? HUGE_VAL : 0;
	if (seam_ratio)
		*seam_ratio = ratio;
	if (check_seam && seam > 3 * p99 && seam > 0.02 * range)
		return fct_fail(err, "the last and first columns do not meet (their difference is "
		                "%.3g times the 99th percentile of neighbouring columns'): not a "
		                "360-degree panorama", ratio);
	return 0;
}

/* ---- face assignment ---------------------------------------------------- */

/* The best view of the polygon whose corners (panorama frame) are pts[0..n):
 * the index, or -1; *ratio gets its depth ratio. */
static int best_view(const double *pts, size_t n, const struct fct_cylview *views, size_t nviews,
                     double *ratio)
{
	double c[3] = {0, 0, 0};
	for (size_t i = 0; i < n; i++)
		for (int j = 0; j < 3; j++)
			c[j] += pts[3 * i + j];
	double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
	int best = -1;
	double best_r = HUGE_VAL, best_cos = -HUGE_VAL;
	for (size_t k = 0; k < nviews; k++) {
		const struct fct_cylview *v = &views[k];
		double W1 = v->cam.width - 1, H1 = v->cam.height - 1, zmin = HUGE_VAL, zmax = 0;
		size_t i;
		for (i = 0; i < n; i++) {
			double u, w, z;
			if (!fct_cylview_project(v, pts + 3 * i, &u, &w, &z) ||
			    !(u >= 0 && u <= W1 && w >= 0 && w <= H1))
				break;
			zmin = z < zmin ? z : zmin;
			zmax = z > zmax ? z : zmax;
		}
		if (i < n)
			continue;
		double r = zmax / zmin;
		double cs = cl > 0 ? (v->rot[2] * c[0] + v->rot[5] * c[1] + v->rot[8] * c[2]) / cl : 0;
		if (r < best_r * (1 - 1e-12) || (r <= best_r * (1 + 1e-12) && cs > best_cos)) {
			best = (int)k;
			best_r = r < best_r ? r : best_r;
			best_cos = cs;
		}
	}
	*ratio = best_r;
	return best;
}

/* Does point p lie inside some view? */
static int in_some_view(const double *p, const struct fct_cylview *views, size_t nviews)
{
	double r;
	return best_view(p, 1, views, nviews, &r) >= 0;
}

/* Incidence lists: faces at each vertex. */
struct incid {
	uint32_t *head;     /* per vertex, entry + 1 (0: none) */
	size_t head_cap;
	uint32_t *face, *next;   /* per entry */
	size_t ent, face_cap, next_cap;
};

static int incid_add(struct incid *I, uint32_t v, uint32_t f, struct fct_err *err)
{
	if (I->ent >= UINT32_MAX - 1)
		return fct_fail(err, "too many faces");
	if (fct_grow((void **)&I->face, &I->face_cap, I->ent + 1, sizeof *I->face, err) ||
	    fct_grow((void **)&I->next, &I->next_cap, I->ent + 1, sizeof *I->next, err))
		return -1;
	I->face[I->ent] = f;
	I->next[I->ent] = I->head[v];
	I->head[v] = (uint32_t)(I->ent + 1);
	I->ent++;
	return 0;
}

static void incid_remove(struct incid *I, uint32_t v, uint32_t f)
{
	for (uint32_t *e = &I->head[v]; *e; e = &I->next[*e - 1])
		if (I->face[*e - 1] == f) {
			*e = I->next[*e - 1];
			return;
		}
}

static void incid_free(struct incid *I)
{
	free(I->head);
	free(I->face);
	free(I->next);
}

/* Bisect edge (a, b) of every triangle on it; the new vertex goes to the end
 * of m (and of P, the panorama-frame points). */
static int split_edge(struct fct_mesh *m, double **P, size_t *P_cap, struct incid *I, uint32_t a,
                      uint32_t b, struct fct_err *err)
{
	long mv = fct_mesh_add_vertex(m, 0.5 * (m->xyz[3 * a] + m->xyz[3 * b]),
	                              0.5 * (m->xyz[3 * a + 1] + m->xyz[3 * b + 1]),
	                              0.5 * (m->xyz[3 * a + 2] + m->xyz[3 * b + 2]), err);
	if (mv < 0 || mv > (long)UINT32_MAX - 1)
		return mv < 0 ? -1 : fct_fail(err, "too many vertices");
	uint32_t mid = (uint32_t)mv;
	for (size_t i = 0; i < m->vertex.nprops; i++) {
		struct fct_prop *p = &m->vertex.props[i];
		if (p->count_type == FCT_NONE)
			fct_prop_set(p, mid, 0.5 * (fct_prop_get(p, a) + fct_prop_get(p, b)));
	}
	if (fct_grow((void **)P, P_cap, 3 * (size_t)mid + 3, sizeof **P, err) ||
	    fct_grow((void **)&I->head, &I->head_cap, (size_t)mid + 1, sizeof *I->head, err))
		return -1;
	for (int j = 0; j < 3; j++)
		(*P)[3 * mid + j] = 0.5 * ((*P)[3 * a + j] + (*P)[3 * b + j]);
	I->head[mid] = 0;
	/* The faces on the edge, collected first: the lists change below. */
	uint32_t on[64];
	size_t non = 0;
	for (uint32_t e = I->head[a]; e && non < 64; e = I->next[e - 1]) {
		uint32_t g = I->face[e - 1];
		if (fct_face_size(m, g) != 3)
			continue;
		const uint32_t *c = m->fvert + m->fstart[g];
		if (c[0] == b || c[1] == b || c[2] == b)
			on[non++] = g;
	}
	for (size_t k = 0; k < non; k++) {
		uint32_t g = on[k], c[3];
		memcpy(c, m->fvert + m->fstart[g], sizeof c);
		uint32_t h[3];
		for (int j = 0; j < 3; j++)
			h[j] = c[j] == a ? mid : c[j];
		long nf = fct_mesh_add_face(m, h, 3, err);
		if (nf < 0)
			return -1;
		for (size_t i = 0; i < m->face.nprops; i++) {
			struct fct_prop *p = &m->face.props[i];
			if (p->count_type == FCT_NONE)
				fct_prop_set(p, (size_t)nf, fct_prop_get(p, g));
		}
		uint32_t *gc = m->fvert + m->fstart[g];
		for (int j = 0; j < 3; j++)
			if (gc[j] == b)
				gc[j] = mid;
		incid_remove(I, b, g);
		if (incid_add(I, mid, g, err) || incid_add(I, mid, (uint32_t)nf, err) ||
		    incid_add(I, b, (uint32_t)nf, err))
			return -1;
		for (int j = 0; j < 3; j++)
			if (h[j] != mid && h[j] != b && incid_add(I, h[j], (uint32_t)nf, err))
				return -1;
	}
	return 0;
}

/* The corners of face f in the panorama frame, into buf (grown). */
static int face_points(const struct fct_mesh *m, const double *P, size_t f, double **buf,
                       size_t *cap, struct fct_err *err)
{
	size_t n = fct_face_size(m, f);
	if (fct_grow((void **)buf, cap, 3 * n, sizeof **buf, err))
		return -1;
	const uint32_t *c = m->fvert + m->fstart[f];
	for (size_t i = 0; i < n; i++)
		memcpy(*buf + 3 * i, P + 3 * (size_t)c[i], 3 * sizeof **buf);
	return 0;
}

static double angle_between(const double *a, const double *b)
{
	double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2];
	double cz = a[0] * b[1] - a[1] * b[0];
	return atan2(sqrt(cx * cx + cy * cy + cz * cz), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

int fct_cylview_assign(struct fct_mesh *m, const double *pano_pose,
                       const struct fct_cylview *views, size_t nviews,
                       const struct fct_cylview_assign_params *p, int32_t **view_of,
                       struct fct_cylview_assign_stats *st, struct fct_err *err)
{
	struct fct_cylview_assign_stats s;
	memset(&s, 0, sizeof s);
	*view_of = NULL;
	size_t P_cap = 0, buf_cap = 0;
	double *P = NULL, *buf = NULL;
	struct incid I;
	memset(&I, 0, sizeof I);
	int32_t *vo = NULL;
	int rc = -1;
	if (m->nv > UINT32_MAX - 1 || m->nf > UINT32_MAX / 4)
		return fct_fail(err, "mesh too large");
	if (fct_grow((void **)&P, &P_cap, 3 * m->nv + 3, sizeof *P, err))
		goto out;
	double inv[12];
	if (pano_pose)
		fct_pose_invert(pano_pose, inv);
	for (size_t v = 0; v < m->nv; v++) {
		if (pano_pose)
			fct_pose_apply(inv, m->xyz + 3 * v, P + 3 * v);
		else
			memcpy(P + 3 * v, m->xyz + 3 * v, 3 * sizeof *P);
	}
	size_t budget = p->max_splits ? p->max_splits : 64 * m->nf + 1024;
	if (p->split) {
		if (fct_grow((void **)&I.head, &I.head_cap, m->nv + 1, sizeof *I.head, err))
			goto out;
		memset(I.head, 0, (m->nv + 1) * sizeof *I.head);
		for (size_t f = 0; f < m->nf; f++)
			for (uint32_t i = m->fstart[f]; i < m->fstart[f + 1]; i++)
				if (incid_add(&I, m->fvert[i], (uint32_t)f, err))
					goto out;
		for (size_t f = 0; f < m->nf;) {
			double r;
			if (face_points(m, P, f, &buf, &buf_cap, err))
				goto out;
			size_t n = fct_face_size(m, f);
			if (n != 3 || s.splits >= budget || best_view(buf, n, views, nviews, &r) >= 0) {
				f++;
				continue;
			}
			/* Splitting helps only when every corner is in some view. */
			int j;
			for (j = 0; j < 3 && in_some_view(buf + 3 * j, views, nviews); j++)
				;
			double best = 0;
			int e = -1;
			for (int k = 0; j == 3 && k < 3; k++) {
				double ang = angle_between(buf + 3 * k, buf + 3 * ((k + 1) % 3));
				if (ang > best)
					best = ang, e = k;
			}
			if (e < 0 || best < 1e-4) {
				f++;
				continue;
			}
			const uint32_t *c = m->fvert + m->fstart[f];
			if (split_edge(m, &P, &P_cap, &I, c[e], c[(e + 1) % 3], err))
				goto out;
			s.splits++;
		}
	}
	vo = fct_alloc_array(m->nf, sizeof *vo, err);
	if (!vo)
		goto out;
	char *used = calloc(nviews ? nviews : 1, 1);
	if (!used) {
		fct_fail(err, "out of memory");
		goto out;
	}
	for (size_t f = 0; f < m->nf; f++) {
		double r;
		if (face_points(m, P, f, &buf, &buf_cap, err)) {
			free(used);
			goto out;
		}
		vo[f] = best_view(buf, fct_face_size(m, f), views, nviews, &r);
		if (vo[f] < 0) {
			s.uncovered++;
			continue;
		}
		used[vo[f]] = 1;
		if (r > s.max_ratio)
			s.max_ratio = r;
	}
	for (size_t k = 0; k < nviews; k++)
		s.views_used += used[k];
	free(used);
	s.faces = m->nf;
	*view_of = vo;
	vo = NULL;
	rc = 0;
out:
	free(vo);
	free(P);
	free(buf);
	incid_free(&I);
	if (st)
		*st = s;
	return rc;
}

/* ---- texture coordinates -------------------------------------------------- */

static void texcoord(const struct fct_cylview *v, const double p[3], float st[2])
{
	double u, w, z;
	if (!fct_cylview_project(v, p, &u, &w, &z)) {
		st[0] = st[1] = 0;
		return;
	}
	st[0] = (float)((u + 0.5) / v->cam.width);
	st[1] = (float)(1 - (w + 0.5) / v->cam.height);
}

/* Replace the TextureFile comments of m by names[k] of the used views. */
static int set_textures(struct fct_mesh *m, const char *used, size_t nviews, char *const *names,
                        struct fct_err *err)
{
	fct_header_remove_textures(m);
	size_t t = 0;
	for (size_t k = 0; k < nviews; k++)
		if (used[k] && fct_header_set_texture(m, t++, names[k], err))
			return -1;
	return 0;
}

int fct_cylview_texture(struct fct_mesh *m, const double *pano_pose,
                        const struct fct_cylview *views, size_t nviews, const int32_t *view_of,
                        char *const *names, int per_face, struct fct_err *err)
{
	double inv[12];
	if (pano_pose)
		fct_pose_invert(pano_pose, inv);
	if (m->nf > INT32_MAX || m->fstart[m->nf] > UINT32_MAX / 2)
		return fct_fail(err, "mesh too large");
	char *used = calloc(nviews ? nviews : 1, 1);
	int32_t *rank = fct_alloc_array(nviews, sizeof *rank, err);
	float *st = fct_alloc_array(m->fstart[m->nf], 2 * sizeof *st, err);
	int32_t *texnum = fct_alloc_array(m->nf, sizeof *texnum, err);
	int rc = -1;
	if (!used || !rank || !st || !texnum) {
		if (!used)
			fct_fail(err, "out of memory");
		goto out;
	}
	for (size_t f = 0; f < m->nf; f++)
		if (view_of[f] >= 0 && (size_t)view_of[f] < nviews)
			used[view_of[f]] = 1;
	int32_t r = 0;
	for (size_t k = 0; k < nviews; k++)
		rank[k] = used[k] ? r++ : -1;
	for (size_t f = 0; f < m->nf; f++) {
		int32_t k = view_of[f];
		for (uint32_t i = m->fstart[f]; i < m->fstart[f + 1]; i++) {
			double p[3];
			const double *x = m->xyz + 3 * (size_t)m->fvert[i];
			if (pano_pose)
				fct_pose_apply(inv, x, p);
			else
				memcpy(p, x, sizeof p);
			if (k >= 0)
				texcoord(&views[k], p, st + 2 * (size_t)i);
			else
				st[2 * i] = st[2 * i + 1] = 0;
		}
		texnum[f] = k >= 0 ? rank[k] : -1;
	}
	if (fct_texmap_set_corners(m, st, texnum, per_face, err) ||
	    set_textures(m, used, nviews, names, err))
		goto out;
	rc = 0;
out:
	free(used);
	free(rank);
	free(st);
	free(texnum);
	return rc;
}

/* Render view and write it to path atomically (output.h); *pixels gets its
 * pixel count. */
static int write_view(const struct fct_image *img, const struct fct_camera *pano,
                      const struct fct_cylview *view, const char *path, size_t *pixels,
                      struct fct_err *err)
{
	struct fct_image vi;
	if (fct_cylview_render(img, pano, view, &vi, err))
		return -1;
	struct fct_out o;
	int rc = fct_out_open(&o, path, err);
	if (!rc) {
		if ((rc = fct_png_write(&vi, o.f, err))) {
			fct_out_abort(&o);
			fct_err_prefix(err, "%s", path);
		} else {
			rc = fct_out_commit(&o, err);
		}
	}
	*pixels = (size_t)vi.width * (size_t)vi.height;
	fct_image_free(&vi);
	return rc;
}

/* The message for faces in no view: their count and the first ten. */
static int fail_uncovered(const int32_t *view_of, size_t nf, size_t uncovered, int split,
                          struct fct_err *err)
{
	char list[200] = "";
	size_t len = 0, shown = 0;
	for (size_t f = 0; f < nf && shown < 10; f++)
		if (view_of[f] < 0) {
			len += (size_t)snprintf(list + len, sizeof list - len, "%s%zu", shown ? ", " : "", f);
			shown++;
		}
	return fct_fail(err, "%zu face%s (%s%s) lie whole in no view: give more views (--count) or a "
	                "wider --fov%s (no view holds a face over the zenith or the nadir)", uncovered,
	                uncovered == 1 ? "" : "s", list, uncovered > shown ? ", ..." : "",
	                split ? "" : ", or let them be split");
}

int fct_cylview_texture_model(struct fct_mesh *m, const struct fct_image *img,
                              const struct fct_camera *pano, const double *pano_pose,
                              const struct fct_cylview_params *p, int split, const char *name,
                              const char *out, struct fct_cylview_model_stats *st,
                              struct fct_err *err)
{
	struct fct_cylview_model_stats local;
	if (!st)
		st = &local;
	memset(st, 0, sizeof *st);
	if (img->type == FCT_PIX_F32)
		return fct_fail(err, "a PFM image cannot texture a model: give a PNG or JPEG");
	size_t nviews = p->count > 0 ? (size_t)p->count : 0;
	struct fct_cylview *views = calloc(nviews ? nviews : 1, sizeof *views);
	char **names = calloc(nviews ? nviews : 1, sizeof *names);
	int32_t *view_of = NULL;
	int rc = -1;
	if (!views || !names) {
		fct_fail(err, "out of memory for %zu views", nviews);
		goto out;
	}
	struct fct_cylview_assign_params ap = { split, 0 };
	if (fct_cylview_plan(pano, p, views, err))
		goto out;
	if (fct_cylview_assign(m, pano_pose, views, nviews, &ap, &view_of, &st->assign, err) ||
	    (st->assign.uncovered && fail_uncovered(view_of, m->nf, st->assign.uncovered, split, err))) {
		fct_err_prefix(err, "%s", name);
		goto out;
	}
	/* name.obj -> name.viewNN.png, for the views some face uses */
	size_t stem = fct_path_stem_length(out);
	for (size_t f = 0; f < m->nf; f++) {
		size_t k = (size_t)view_of[f];
		if (names[k])
			continue;
		if (!(names[k] = malloc(stem + 32))) {
			fct_fail(err, "out of memory");
			goto out;
		}
		snprintf(names[k], stem + 32, "%.*s.view%02d.png", (int)stem, out, (int)k);
	}
	for (size_t k = 0; k < nviews; k++) {
		size_t px;
		if (!names[k])
			continue;
		if (write_view(img, pano, &views[k], names[k], &px, err))
			goto out;
		st->written++;
		st->pixels += px;
	}
	rc = fct_cylview_texture(m, pano_pose, views, nviews, view_of, names,
	                         !fct_path_has_suffix(out, ".obj"), err);
out:
	for (size_t k = 0; names && k < nviews; k++)
		free(names[k]);
	free(names);
	free(views);
	free(view_of);
	return rc;
}

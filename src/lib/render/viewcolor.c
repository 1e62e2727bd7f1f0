/* viewcolor.c - vertex colour of a fused surface from the views' images;
 * see viewcolor.h.  Each view: the vertex is moved into the camera
 * (fct_pose_apply with the range image's inverse pose, fct_camera_project),
 * tested against the four range-image pixels around it, and the image
 * sampled there. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "render/raster.h"
#include "render/viewcolor.h"

int fct_viewcolor_init(struct fct_viewcolor *c, size_t nv, struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	c->nv = nv;
	c->sum = fct_alloc_array(nv ? nv : 1, 4 * sizeof *c->sum, err);
	if (!c->sum)
		return -1;
	memset(c->sum, 0, (nv ? nv : 1) * 4 * sizeof *c->sum);
	return 0;
}

void fct_viewcolor_free(struct fct_viewcolor *c)
{
	if (c) {
		free(c->sum);
		c->sum = NULL;
		c->nv = 0;
	}
}

/* Are ranges a and b of neighbouring pixels one surface?  Within band,
 * or within what a surface seen at up to dm2mesh's steepest angle changes
 * over one pixel (slope = FCT_DEFAULT_MAX_JUMP times the pixel angle). */
static inline int continuous(double a, double b, double band, double slope)
{
	return fabs(a - b) <= band + slope * fmin(a, b);
}

float *fct_depth_edge_distance(const float *R, int W, int H, double band, double slope,
                              double cap, struct fct_err *err)
{
	size_t n = (size_t)W * (size_t)H;
	float *d = fct_alloc_array(n, sizeof *d, err);
	if (!d)
		return NULL;
	for (int y = 0; y < H; y++)
		for (int x = 0; x < W; x++) {
			size_t i = (size_t)y * (size_t)W + (size_t)x;
			int edge = !(R[i] > 0);
			static const int off[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
			for (int k = 0; k < 4 && !edge; k++) {
				int xx = x + off[k][0], yy = y + off[k][1];
				if (xx < 0 || yy < 0 || xx >= W || yy >= H)
					continue;
				float q = R[(size_t)yy * (size_t)W + (size_t)xx];
				edge = !(q > 0) || !continuous(q, R[i], band, slope);
			}
			d[i] = edge ? 0 : (float)cap;
		}
	const float s2 = (float)M_SQRT2;
	for (int y = 0; y < H; y++)         /* forward pass */
		for (int x = 0; x < W; x++) {
			float *p = &d[(size_t)y * (size_t)W + (size_t)x];
			if (x > 0)
				*p = fminf(*p, p[-1] + 1);
			if (y > 0) {
				const float *u = p - W;
				*p = fminf(*p, u[0] + 1);
				if (x > 0)
					*p = fminf(*p, u[-1] + s2);
				if (x + 1 < W)
					*p = fminf(*p, u[1] + s2);
			}
		}
	for (int y = H - 1; y >= 0; y--)    /* backward pass */
		for (int x = W - 1; x >= 0; x--) {
			float *p = &d[(size_t)y * (size_t)W + (size_t)x];
			if (x + 1 < W)
				*p = fminf(*p, p[1] + 1);
			if (y + 1 < H) {
				const float *b = p + W;
				*p = fminf(*p, b[0] + 1);
				if (x + 1 < W)
					*p = fminf(*p, b[1] + s2);
				if (x > 0)
					*p = fminf(*p, b[-1] + s2);
			}
		}
	return d;
}

int fct_viewcolor_add(struct fct_viewcolor *c, const struct fct_mesh *m,
                      const struct fct_range_image *r, const struct fct_image *image,
                      const struct fct_viewcolor_params *p, size_t *seen, struct fct_err *err)
{
	if (seen)
		*seen = 0;
	const struct fct_camera *cam = &r->view.cam;
	if (cam->kind == FCT_CAMERA_NONE)
		return fct_fail(err, "an orthographic range scan has no colour image");
	if (m->nv != c->nv)
		return fct_fail(err, "colour of %zu vertices asked of a mesh of %zu", c->nv, m->nv);
	int W = r->width, H = r->height, cyl = cam->kind == FCT_CAMERA_CYLINDRICAL;
	struct fct_image rgb = { 0 };
	const struct fct_image *img = image;
	if (image->type != FCT_PIX_U8 || image->channels != 3) {
		static const unsigned char black[3] = { 0, 0, 0 };
		if (fct_image_to_rgb8(image, black, &rgb, err))
			return -1;
		img = &rgb;
	}
	int same = img->width == W && img->height == H;
	double slope = FCT_DEFAULT_MAX_JUMP * fct_camera_pixel_angle(cam);
	float *edge = NULL;
	if (p->edge_px > 0 &&
	    !(edge = fct_depth_edge_distance(r->range, W, H, p->band, slope, p->edge_px, err))) {
		fct_image_free(&rgb);
		return -1;
	}
	const struct fct_prop *nx = fct_elem_find(&m->vertex, "nx");
	const struct fct_prop *ny = fct_elem_find(&m->vertex, "ny");
	const struct fct_prop *nz = fct_elem_find(&m->vertex, "nz");
	int normals = nx && ny && nz;
	const double centre[3] = { r->view.pose[3], r->view.pose[7], r->view.pose[11] };
	const unsigned char *pix = img->data;
	size_t nseen = 0;
	for (size_t i = 0; i < m->nv; i++) {
		const double *x = &m->xyz[3 * i];
		double q[3], u, v, depth;
		fct_pose_apply(r->inv, x, q);
		if (!fct_camera_project(cam, q, &u, &v, &depth) || !(depth > 0) ||
		    !(u > -1 && v > -1 && u < W && v < H))
			continue;
		double conf = 1;
		if (normals || p->weight == FCT_FUSE_INCIDENCE) {
			double ray[3], n[3] = { 0, 0, 0 };
			fct_v3_sub(ray, centre, x);
			double len = sqrt(fct_v3_dot(ray, ray));
			if (normals) {
				n[0] = fct_prop_get(nx, i), n[1] = fct_prop_get(ny, i), n[2] = fct_prop_get(nz, i);
			}
			double cs = len > 0 ? fct_v3_dot(ray, n) / len : 0;
			if (normals && !(cs > 0))
				continue;       /* seen from behind */
			if (p->weight == FCT_FUSE_INCIDENCE)
				conf = normals ? fmax(cs, 1e-3) : 1;
		}
		if (p->weight == FCT_FUSE_DEPTH2)
			conf = depth > 1e-3 ? 1 / (depth * depth) : 1e6;
		/* The four pixels around (u, v) whose range agrees with depth. */
		int x0 = (int)floor(u), y0 = (int)floor(v);
		double fx = u - x0, fy = v - y0, wsum = 0, col[3] = { 0, 0, 0 };
		int nearest = -1;
		double wnear = -1;
		for (int b = 0; b < 2; b++)
			for (int a = 0; a < 2; a++) {
				int xx = x0 + a, yy = y0 + b;
				if (cyl)
					xx = (xx % W + W) % W;
				if (xx < 0 || yy < 0 || xx >= W || yy >= H)
					continue;
				size_t k = (size_t)yy * (size_t)W + (size_t)xx;
				double w = (a ? fx : 1 - fx) * (b ? fy : 1 - fy);
				double R = r->range[k];
				if (!(R > 0) || !(w > 0))
					continue;
				/* The depth test allows the change of range across the
				 * pixel's own surface over the distance to its centre,
				 * so grazing surfaces are seen. */
				double s = 0, reach = fmax(a ? 1 - fx : fx, b ? 1 - fy : fy);
				for (int e = 0; e < 4; e++) {
					int x2 = xx + (e == 0) - (e == 1), y2 = yy + (e == 2) - (e == 3);
					if (cyl)
						x2 = (x2 % W + W) % W;
					if (x2 < 0 || y2 < 0 || x2 >= W || y2 >= H)
						continue;
					double R2 = r->range[(size_t)y2 * (size_t)W + (size_t)x2];
					if (R2 > 0 && continuous(R, R2, p->band, slope))
						s = fmax(s, fabs(R2 - R));
				}
				if (!(fabs(depth - R) <= p->band + s * reach))
					continue;
				wsum += w;
				if (w > wnear)
					wnear = w, nearest = (int)k;
				if (same)
					for (int ch = 0; ch < 3; ch++)
						col[ch] += w * pix[3 * k + (size_t)ch];
			}
		if (!(wsum > 0))
			continue;
		if (same) {
			for (int ch = 0; ch < 3; ch++)
				col[ch] /= wsum;
		} else {
			fct_texture_sample(img, (u + 0.5) / W, 1 - (v + 0.5) / H, col);
		}
		double w = conf * wsum;
		if (edge) {
			double d = edge[nearest];
			if (d < p->edge_px)
				w *= (1 + d) / (1 + p->edge_px);
		}
		double *s = &c->sum[4 * i];
		s[0] += w * col[0], s[1] += w * col[1], s[2] += w * col[2], s[3] += w;
		nseen++;
	}
	c->samples += nseen;
	if (seen)
		*seen = nseen;
	free(edge);
	fct_image_free(&rgb);
	return 0;
}

int fct_viewcolor_write(const struct fct_viewcolor *c, struct fct_mesh *m, const uint8_t fallback[3],
                        struct fct_viewcolor_stats *stats, struct fct_err *err)
{
	static const char *const names[3] = { "red", "green", "blue" };
	if (m->nv != c->nv)
		return fct_fail(err, "colour of %zu vertices for a mesh of %zu", c->nv, m->nv);
	for (int k = 0; k < 3; k++)
		if (!fct_elem_add_scalar(&m->vertex, names[k], FCT_UINT8, err))
			return -1;
	struct fct_prop *col[3];
	for (int k = 0; k < 3; k++)
		col[k] = fct_elem_find(&m->vertex, names[k]);
	size_t colored = 0;
	for (size_t i = 0; i < m->nv; i++) {
		const double *s = &c->sum[4 * i];
		int ok = s[3] > 0;
		colored += (size_t)ok;
		for (int k = 0; k < 3; k++) {
			double v = ok ? floor(s[k] / s[3] + 0.5) : fallback[k];
			fct_prop_set(col[k], i, v < 0 ? 0 : v > 255 ? 255 : v);
		}
	}
	if (stats) {
		stats->colored = colored;
		stats->unseen = m->nv - colored;
		stats->views_per_vertex = colored ? (double)c->samples / (double)colored : 0;
	}
	return 0;
}

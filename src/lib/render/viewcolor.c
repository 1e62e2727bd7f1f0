/* viewcolor.c - vertex colour and noise of a fused surface from the views;
 * see viewcolor.h.  Each view: the vertex is moved into the camera
 * (fct_pose_apply with the range image's inverse pose, fct_camera_project)
 * and tested against the four range-image pixels around it (sight); the
 * image is sampled there, or the sensor's noise taken at its depth. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/par.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "render/raster.h"
#include "render/viewcolor.h"

/* nv vertices' sums, per doubles each, zeroed (NULL: out of memory). */
static double *zeroed_sums(size_t nv, size_t per, struct fct_err *err)
{
	size_t n = (nv ? nv : 1) * per;
	double *sum = fct_alloc_array(n, sizeof *sum, err);
	if (sum)
		memset(sum, 0, n * sizeof *sum);
	return sum;
}

int fct_viewcolor_init(struct fct_viewcolor *c, size_t nv, struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	c->nv = nv;
	return (c->sum = zeroed_sums(nv, 4, err)) ? 0 : -1;
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

/* How a view sees the vertices of a mesh: its camera and range image, the
 * depth test's tolerances, the mesh's normals when it has them. */
struct sight_ctx {
	const struct fct_range_image *r;
	const struct fct_camera *cam;
	int W, H, cyl;
	double band, slope, centre[3];
	enum fct_fuse_weight weight;
	const struct fct_prop *nx, *ny, *nz;
};

/* What the view sees of one vertex: its depth along the sensor, the
 * confidence of fuse.h's weight, and the four pixels around its projection
 * (k) with their bilinear weights (w, 0 for pixels whose range does not
 * agree with depth or that are outside), their sum and the heaviest. */
struct sight {
	double depth, conf, w[4], wsum;
	size_t k[4];
	int nearest;
	double u, v;
};

static void sight_init(struct sight_ctx *c, const struct fct_mesh *m, const struct fct_range_image *r,
                       double band, enum fct_fuse_weight weight)
{
	memset(c, 0, sizeof *c);
	c->r = r;
	c->cam = &r->view.cam;
	c->W = r->width, c->H = r->height;
	c->cyl = c->cam->kind == FCT_CAMERA_CYLINDRICAL;
	c->band = band;
	c->slope = FCT_DEFAULT_MAX_JUMP * fct_camera_pixel_angle(c->cam);
	c->weight = weight;
	c->nx = fct_elem_find(&m->vertex, "nx");
	c->ny = fct_elem_find(&m->vertex, "ny");
	c->nz = fct_elem_find(&m->vertex, "nz");
	if (!(c->nx && c->ny && c->nz))
		c->nx = c->ny = c->nz = NULL;
	c->centre[0] = r->view.pose[3], c->centre[1] = r->view.pose[7], c->centre[2] = r->view.pose[11];
}

/* 1 when the view sees vertex i of m (in front of the camera, inside its
 * image, from the side its normal points to, and some pixel around it
 * agrees with its depth), with *s filled; 0 when it does not. */
static int sight(struct sight *s, const struct sight_ctx *c, const struct fct_mesh *m, size_t i)
{
	const struct fct_range_image *r = c->r;
	int W = c->W, H = c->H;
	const double *x = &m->xyz[3 * i];
	double q[3], u, v, depth;
	fct_pose_apply(r->inv, x, q);
	if (!fct_camera_project(c->cam, q, &u, &v, &depth) || !(depth > 0) ||
	    !(u > -1 && v > -1 && u < W && v < H))
		return 0;
	double conf = 1;
	if (c->nx || c->weight == FCT_FUSE_INCIDENCE) {
		double ray[3], n[3] = { 0, 0, 0 };
		fct_v3_sub(ray, c->centre, x);
		double len = sqrt(fct_v3_dot(ray, ray));
		if (c->nx) {
			n[0] = fct_prop_get(c->nx, i), n[1] = fct_prop_get(c->ny, i), n[2] = fct_prop_get(c->nz, i);
		}
		double cs = len > 0 ? fct_v3_dot(ray, n) / len : 0;
		if (c->nx && !(cs > 0))
			return 0;       /* seen from behind */
		if (c->weight == FCT_FUSE_INCIDENCE)
			conf = c->nx ? fmax(cs, 1e-3) : 1;
	}
	if (c->weight == FCT_FUSE_DEPTH2)
		conf = depth > 1e-3 ? 1 / (depth * depth) : 1e6;
	/* The four pixels around (u, v) whose range agrees with depth. */
	int x0 = (int)floor(u), y0 = (int)floor(v);
	double fx = u - x0, fy = v - y0;
	s->wsum = 0;
	s->nearest = -1;
	double wnear = -1;
	for (int b = 0; b < 2; b++)
		for (int a = 0; a < 2; a++) {
			int j = 2 * b + a, xx = x0 + a, yy = y0 + b;
			s->w[j] = 0, s->k[j] = 0;
			if (c->cyl)
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
			 * so grazing surfaces are seen (asked only when the
			 * band alone does not do). */
			double ds = 0, reach = fmax(a ? 1 - fx : fx, b ? 1 - fy : fy);
			for (int e = 0; e < 4 && !(fabs(depth - R) <= c->band); e++) {
				int x2 = xx + (e == 0) - (e == 1), y2 = yy + (e == 2) - (e == 3);
				if (c->cyl)
					x2 = (x2 % W + W) % W;
				if (x2 < 0 || y2 < 0 || x2 >= W || y2 >= H)
					continue;
				double R2 = r->range[(size_t)y2 * (size_t)W + (size_t)x2];
				if (R2 > 0 && continuous(R, R2, c->band, c->slope))
					ds = fmax(ds, fabs(R2 - R));
			}
			if (!(fabs(depth - R) <= c->band + ds * reach))
				continue;
			s->w[j] = w, s->k[j] = k;
			s->wsum += w;
			if (w > wnear)
				wnear = w, s->nearest = (int)k;
		}
	if (!(s->wsum > 0))
		return 0;
	s->depth = depth, s->conf = conf, s->u = u, s->v = v;
	return 1;
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
	struct fct_image rgb = { 0 };
	const struct fct_image *img = image;
	if (image->type != FCT_PIX_U8 || image->channels != 3) {
		static const unsigned char black[3] = { 0, 0, 0 };
		if (fct_image_to_rgb8(image, black, &rgb, err))
			return -1;
		img = &rgb;
	}
	struct sight_ctx sc;
	sight_init(&sc, m, r, p->band, p->weight);
	int W = r->width, H = r->height, same = img->width == W && img->height == H;
	float *edge = NULL;
	if (p->edge_px > 0 &&
	    !(edge = fct_depth_edge_distance(r->range, W, H, p->band, sc.slope, p->edge_px, err))) {
		fct_image_free(&rgb);
		return -1;
	}
	const unsigned char *pix = img->data;
	size_t nseen = 0;
	for (size_t i = 0; i < m->nv; i++) {
		struct sight s;
		if (!sight(&s, &sc, m, i))
			continue;
		double col[3] = { 0, 0, 0 };
		if (same) {
			for (int j = 0; j < 4; j++)
				for (int ch = 0; ch < 3; ch++)
					col[ch] += s.w[j] * pix[3 * s.k[j] + (size_t)ch];
			for (int ch = 0; ch < 3; ch++)
				col[ch] /= s.wsum;
		} else {
			fct_texture_sample(img, (s.u + 0.5) / W, 1 - (s.v + 0.5) / H, col);
		}
		double w = s.conf * s.wsum;
		if (edge) {
			double d = edge[s.nearest];
			if (d < p->edge_px)
				w *= (1 + d) / (1 + p->edge_px);
		}
		double *sum = &c->sum[4 * i];
		sum[0] += w * col[0], sum[1] += w * col[1], sum[2] += w * col[2], sum[3] += w;
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

int fct_viewnoise_init(struct fct_viewnoise *c, size_t nv, struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	c->nv = nv;
	return (c->sum = zeroed_sums(nv, 3, err)) ? 0 : -1;
}

void fct_viewnoise_free(struct fct_viewnoise *c)
{
	if (c) {
		free(c->sum);
		c->sum = NULL;
		c->nv = 0;
	}
}

/* fct_viewnoise_add's loop over a range of vertices: each writes its own
 * sums, so the result is the same on any number of threads. */
struct noise_pass {
	struct fct_viewnoise *c;
	const struct fct_mesh *m;
	const struct sight_ctx *sc;
	const struct fct_noise *nz;
	double vox;
	size_t seen[FCT_PAR_MAX];
};

static void noise_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	struct noise_pass *N = ctx;
	for (size_t i = lo; i < hi; i++) {
		struct sight s;
		if (!sight(&s, N->sc, N->m, i))
			continue;
		double sd = fct_noise_sigma(N->nz, s.depth), t = 2 * sd / N->vox;
		double w = s.conf / (1 + t * t);
		double *sum = &N->c->sum[3 * i];
		sum[0] += w;
		sum[1] += w * sd * sd;
		sum[2] += w * w * sd * sd;
		N->seen[worker]++;
	}
}

int fct_viewnoise_add(struct fct_viewnoise *c, const struct fct_mesh *m, const struct fct_range_image *r,
                      const struct fct_noise *nz, double vox, const struct fct_viewcolor_params *p,
                      int threads, size_t *seen, struct fct_err *err)
{
	if (seen)
		*seen = 0;
	if (r->view.cam.kind == FCT_CAMERA_NONE)
		return fct_fail(err, "an orthographic range scan has no noise model");
	if (m->nv != c->nv)
		return fct_fail(err, "noise of %zu vertices asked of a mesh of %zu", c->nv, m->nv);
	struct sight_ctx sc;
	sight_init(&sc, m, r, p->band, p->weight);
	struct noise_pass N = { .c = c, .m = m, .sc = &sc, .nz = nz, .vox = vox };
	fct_par_run(fct_par_threads(threads), m->nv, 0, noise_chunk, &N);
	if (seen)
		for (int k = 0; k < FCT_PAR_MAX; k++)
			*seen += N.seen[k];
	return 0;
}

/* The noise of a weighted mean of views (viewcolor.h): the geometric mean
 * of what it would be were the views' errors one and the same, the
 * weighted root mean square sqrt(sum w s^2 / sum w), and what it would be
 * were they independent, sqrt(sum w^2 s^2) / sum w. */
static double fused_noise(const double sum[3])
{
	return sqrt(sqrt(sum[1] / sum[0]) * sqrt(sum[2]) / sum[0]);
}

int fct_viewnoise_write(const struct fct_viewnoise *c, struct fct_mesh *m, double level, double floor_,
                        size_t *seen, struct fct_err *err)
{
	if (seen)
		*seen = 0;
	if (m->nv != c->nv)
		return fct_fail(err, "noise of %zu vertices for a mesh of %zu", c->nv, m->nv);
	double *mean = fct_alloc_array(c->nv ? c->nv : 1, sizeof *mean, err);
	if (!mean)
		return -1;
	size_t n = 0;
	for (size_t i = 0; i < c->nv; i++)
		if (c->sum[3 * i] > 0)
			mean[n++] = fused_noise(&c->sum[3 * i]);
	if (n == 0 || !(level > 0)) {
		free(mean);
		return fct_fail(err, "no vertex seen by a view with a noise model");
	}
	double med = fct_select_kth(mean, n, n / 2);
	free(mean);
	struct fct_prop *sg = fct_elem_add_scalar(&m->vertex, "sigma", FCT_FLOAT32, err);
	if (!sg)
		return -1;
	/* sqrt((scale x)^2 + floor^2) grows with x: the median vertex's is
	 * level when scale x is sqrt(level^2 - floor^2) there. */
	double f2 = floor_ > 0 ? floor_ * floor_ : 0, above = level * level - f2;
	double scale = med > 0 && above > 0 ? sqrt(above) / med : 0;
	for (size_t i = 0; i < c->nv; i++) {
		const double *s = &c->sum[3 * i];
		double v = level;
		if (s[0] > 0 && scale > 0) {
			double x = fused_noise(s) * scale;
			v = sqrt(x * x + f2);
		}
		fct_prop_set(sg, i, v);
	}
	if (seen)
		*seen = n;
	return 0;
}

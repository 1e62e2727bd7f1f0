/* raster.c - the software rasteriser of raster.h.
 *
 * Triangles: clipped in the camera frame against z = near and a guard band
 * around the picture (Sutherland-Hodgman), projected, snapped to a 1/256
 * pixel grid and scanned with exact integer edge functions (Pineda, "A
 * Parallel Algorithm for Polygon Rasterization", SIGGRAPH 1988), a tie rule
 * giving each pixel centre on a shared edge to exactly one triangle.  1/z is
 * affine in screen space, so depth and the perspective-correct barycentrics
 * come from the affine weights divided by the interpolated 1/z (Heckbert
 * and Moreton, "Interpolation for Polygon Texture Mapping and Shading",
 * 1991). */
#include "render/raster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

void fct_view_to_camera(const struct fct_view *v, const double p[3], double q[3])
{
	const double *R = v->R;
	double x = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + v->t[0];
	double y = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + v->t[1];
	double z = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + v->t[2];
	q[0] = x, q[1] = y, q[2] = z;
}

int fct_view_from_camera(struct fct_view *v, const struct fct_camera *cam, const double *pose,
                         int width, int height, double near, struct fct_err *err)
{
	memset(v, 0, sizeof *v);
	if (cam->kind != FCT_CAMERA_PINHOLE || cam->width < 1 || cam->height < 1 ||
	    !(cam->fx > 0 && cam->fy > 0) || !isfinite(cam->fx + cam->fy + cam->cx + cam->cy))
		return fct_fail(err, "not a pinhole camera with a size and positive focal lengths");
	int W = width > 0 ? width : cam->width, H = height > 0 ? height : cam->height;
	if (W > FCT_IMAGE_MAX_SIDE || H > FCT_IMAGE_MAX_SIDE)
		return fct_fail(err, "picture size %dx%d out of range", W, H);
	double sx = (double)W / cam->width, sy = (double)H / cam->height;
	v->fx = cam->fx * sx, v->fy = cam->fy * sy;
	v->cx = (cam->cx + 0.5) * sx - 0.5, v->cy = (cam->cy + 0.5) * sy - 0.5;
	v->width = W, v->height = H;
	v->near = near;
	if (pose) {
		double inv[12];
		fct_pose_invert(pose, inv);
		for (int r = 0; r < 3; r++) {
			for (int c = 0; c < 3; c++)
				v->R[3 * r + c] = inv[4 * r + c];
			v->t[r] = inv[4 * r + 3];
		}
		for (int k = 0; k < 12; k++)
			if (!isfinite(pose[k]))
				return fct_fail(err, "pose is not finite");
	} else {
		v->R[0] = v->R[4] = v->R[8] = 1;
	}
	return 0;
}

static int normalize(double v[3])
{
	double n = sqrt(fct_v3_dot(v, v));
	if (!(n > 0) || !isfinite(n))
		return -1;
	v[0] /= n, v[1] /= n, v[2] /= n;
	return 0;
}

int fct_view_look_at(struct fct_view *v, const double eye[3], const double target[3],
                     const double up[3], double fov_deg, int width, int height,
                     struct fct_err *err)
{
	double Z[3], Y[3], X[3];
	fct_v3_sub(Z, target, eye);
	double dist = sqrt(fct_v3_dot(Z, Z));
	if (normalize(Z))
		return fct_fail(err, "the eye and the target are the same point");
	fct_v3_axpy(Y, up, -fct_v3_dot(up, Z), Z);   /* up without its part along the sight */
	if (normalize(Y) || sqrt(fct_v3_dot(up, up)) * 1e-9 > sqrt(fct_v3_dot(Y, Y)))
		return fct_fail(err, "the up direction is parallel to the line of sight");
	Y[0] = -Y[0], Y[1] = -Y[1], Y[2] = -Y[2];      /* camera y points down */
	fct_v3_cross(X, Y, Z);
	if (!(fov_deg > 0 && fov_deg < 180) || width < 1 || height < 1)
		return fct_fail(err, "bad field of view or picture size");
	for (int k = 0; k < 3; k++) {
		v->R[k] = X[k];
		v->R[3 + k] = Y[k];
		v->R[6 + k] = Z[k];
	}
	for (int k = 0; k < 3; k++)
		v->t[k] = -(v->R[3 * k] * eye[0] + v->R[3 * k + 1] * eye[1] + v->R[3 * k + 2] * eye[2]);
	v->fy = 0.5 * height / tan(0.5 * fov_deg * M_PI / 180);
	v->fx = v->fy;
	v->cx = 0.5 * (width - 1);
	v->cy = 0.5 * (height - 1);
	v->width = width;
	v->height = height;
	v->near = 1e-3 * dist;
	return 0;
}

/* The spread of the points' tangents along camera axis A with the eye at
 * distance d behind centre: [lo, hi] of (A.q) / (Z.q + d). */
static void spread(const double *pts, size_t n, const double centre[3], const double A[3],
                   const double Z[3], double d, double *lo, double *hi)
{
	*lo = INFINITY, *hi = -INFINITY;
	for (size_t i = 0; i < n; i++) {
		const double *p = pts + 3 * i;
		if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
			continue;
		double q[3];
		fct_v3_sub(q, p, centre);
		double u = fct_v3_dot(A, q) / (fct_v3_dot(Z, q) + d);
		*lo = fmin(*lo, u);
		*hi = fmax(*hi, u);
	}
}

void fct_view_fit(struct fct_view *v, const double centre[3], const double *pts, size_t n,
                  double margin)
{
	const double *X = v->R, *Y = v->R + 3, *Z = v->R + 6;
	if (!(margin >= 0 && margin <= 0.5))
		margin = 0;
	double tx = (1 - margin) * 0.5 * v->width / v->fx, ty = (1 - margin) * 0.5 * v->height / v->fy;
	double d = -INFINITY, ext = 0, zmin = INFINITY;
	for (size_t i = 0; i < n; i++) {
		const double *p = pts + 3 * i;
		if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
			continue;
		double q[3];
		fct_v3_sub(q, p, centre);
		double a = fct_v3_dot(X, q), b = fct_v3_dot(Y, q), c = fct_v3_dot(Z, q);
		d = fmax(d, fabs(a) / tx - c);
		d = fmax(d, fabs(b) / ty - c);
		ext = fmax(ext, sqrt(fct_v3_dot(q, q)));
		zmin = fmin(zmin, c);
	}
	double cx = 0.5 * (v->width - 1), cy = 0.5 * (v->height - 1);
	if (!(ext > 0) || !isfinite(d)) {   /* nothing, or one point: any distance frames it */
		ext = 1;
		d = 1;
		zmin = 0;
	} else {
		/* d frames the points symmetrically about centre.  Shifting the
		 * principal point (an off-axis view, still a pinhole) centres
		 * their picture instead, which lets the eye come closer: the
		 * nearest distance whose spreads fit, by bisection (spreads only
		 * shrink as the eye backs away). */
		double lo = -zmin + 1e-3 * ext, hi = fmax(d, lo);
		for (int it = 0; it < 40 && hi - lo > 1e-6 * hi; it++) {
			double mid = 0.5 * (lo + hi), a0, a1, b0, b1;
			spread(pts, n, centre, X, Z, mid, &a0, &a1);
			spread(pts, n, centre, Y, Z, mid, &b0, &b1);
			if (a1 - a0 <= 2 * tx && b1 - b0 <= 2 * ty)
				hi = mid;
			else
				lo = mid;
		}
		d = hi;
		double a0, a1, b0, b1;
		spread(pts, n, centre, X, Z, d, &a0, &a1);
		spread(pts, n, centre, Y, Z, d, &b0, &b1);
		cx -= v->fx * 0.5 * (a0 + a1);
		cy -= v->fy * 0.5 * (b0 + b1);
	}
	if (d < -zmin + 1e-3 * ext)
		d = -zmin + 1e-3 * ext;
	double eye[3];
	fct_v3_axpy(eye, centre, -d, Z);
	for (int k = 0; k < 3; k++)
		v->t[k] = -(v->R[3 * k] * eye[0] + v->R[3 * k + 1] * eye[1] + v->R[3 * k + 2] * eye[2]);
	v->cx = cx, v->cy = cy;
	v->near = 0.5 * fmax(zmin + d, 1e-6 * ext);
}

int fct_raster_init(struct fct_raster *r, int width, int height, struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	if (width < 1 || height < 1 || width > FCT_IMAGE_MAX_SIDE || height > FCT_IMAGE_MAX_SIDE ||
	    (size_t)width * (size_t)height > FCT_IMAGE_MAX_PIXELS / 4)
		return fct_fail(err, "picture size %dx%d out of range", width, height);
	size_t n = (size_t)width * (size_t)height;
	r->w = calloc(n, sizeof *r->w);
	r->id = malloc(n * sizeof *r->id);
	r->b = calloc(2 * n, sizeof *r->b);
	if (!r->w || !r->id || !r->b) {
		fct_raster_free(r);
		return fct_fail(err, "out of memory for a %dx%d picture", width, height);
	}
	for (size_t i = 0; i < n; i++)
		r->id[i] = FCT_RASTER_EMPTY;
	r->width = width;
	r->height = height;
	r->cap = n;
	return 0;
}

int fct_raster_reset(struct fct_raster *r, int width, int height, struct fct_err *err)
{
	if (width < 1 || height < 1 || (size_t)width * (size_t)height > r->cap)
		return fct_fail(err, "picture size %dx%d beyond the buffer's %zu pixels", width, height,
		                r->cap);
	size_t n = (size_t)width * (size_t)height;
	memset(r->w, 0, n * sizeof *r->w);
	memset(r->b, 0, 2 * n * sizeof *r->b);
	for (size_t i = 0; i < n; i++)
		r->id[i] = FCT_RASTER_EMPTY;
	r->width = width;
	r->height = height;
	return 0;
}

void fct_raster_free(struct fct_raster *r)
{
	if (!r)
		return;
	free(r->w);
	free(r->id);
	free(r->b);
	memset(r, 0, sizeof *r);
}

/* Clipping ---------------------------------------------------------------- */

/* The five half-spaces a drawn point must be in, as a q + d >= 0 ... written
 * as plane k evaluated at q.  The guard band is one picture side beyond each
 * edge, so projected coordinates stay within a few times the picture size
 * and the fixed-point products within 2^52. */
static double plane_eval(const struct fct_view *v, int k, const double q[3])
{
	double gx = v->width, gy = v->height;
	switch (k) {
	case 0: return q[2] - v->near;
	case 1: return v->fx * q[0] + (v->cx + gx) * q[2];
	case 2: return (v->width - 1 + gx - v->cx) * q[2] - v->fx * q[0];
	case 3: return v->fy * q[1] + (v->cy + gy) * q[2];
	default: return (v->height - 1 + gy - v->cy) * q[2] - v->fy * q[1];
	}
}

static unsigned outcode(const struct fct_view *v, const double q[3])
{
	unsigned c = 0;
	for (int k = 0; k < 5; k++)
		if (!(plane_eval(v, k, q) >= 0))
			c |= 1u << k;
	return c;
}

struct cv {          /* a clipped corner: camera point, barycentrics of corners 1, 2 */
	double q[3], b1, b2;
};

/* Clip the polygon in[0..n) against plane k into out; returns the count. */
static int clip_poly(const struct fct_view *v, int k, const struct cv *in, int n, struct cv *out)
{
	int m = 0;
	for (int i = 0; i < n; i++) {
		const struct cv *a = &in[i], *b = &in[(i + 1) % n];
		double fa = plane_eval(v, k, a->q), fb = plane_eval(v, k, b->q);
		if (fa >= 0)
			out[m++] = *a;
		if ((fa >= 0) != (fb >= 0)) {
			double s = fa / (fa - fb);
			struct cv *c = &out[m++];
			for (int j = 0; j < 3; j++)
				c->q[j] = a->q[j] + s * (b->q[j] - a->q[j]);
			c->b1 = a->b1 + s * (b->b1 - a->b1);
			c->b2 = a->b2 + s * (b->b2 - a->b2);
		}
	}
	return m;
}

/* Scan conversion --------------------------------------------------------- */

struct sv {          /* a screen corner: 1/256 pixel fixed point, 1/z, barycentrics */
	int64_t x, y;
	double w, b1, b2;
};

static void project(const struct fct_view *v, const double q[3], double b1, double b2, struct sv *s)
{
	double iz = 1 / q[2];
	s->x = llround((v->fx * q[0] * iz + v->cx) * 256);
	s->y = llround((v->fy * q[1] * iz + v->cy) * 256);
	s->w = iz;
	s->b1 = b1;
	s->b2 = b2;
}

/* Is edge a -> b one whose pixel centres belong to this triangle?  Exactly
 * one of a -> b and b -> a is. */
static int edge_owns(const struct sv *a, const struct sv *b)
{
	int64_t dx = b->x - a->x, dy = b->y - a->y;
	return dy > 0 || (dy == 0 && dx < 0);
}

static long scan(struct fct_raster *r, const struct sv *p0, const struct sv *p1,
                 const struct sv *p2, uint32_t id)
{
	int64_t area = (p1->x - p0->x) * (p2->y - p0->y) - (p1->y - p0->y) * (p2->x - p0->x);
	if (area == 0)
		return 0;
	if (area < 0) {
		const struct sv *t = p1;
		p1 = p2;
		p2 = t;
		area = -area;
	}
	int64_t minx = p0->x < p1->x ? p0->x : p1->x, maxx = p0->x > p1->x ? p0->x : p1->x;
	int64_t miny = p0->y < p1->y ? p0->y : p1->y, maxy = p0->y > p1->y ? p0->y : p1->y;
	minx = p2->x < minx ? p2->x : minx, maxx = p2->x > maxx ? p2->x : maxx;
	miny = p2->y < miny ? p2->y : miny, maxy = p2->y > maxy ? p2->y : maxy;
	/* Pixel centres k * 256 inside the box (floor division of negatives). */
	int64_t x0 = minx >= 0 ? (minx + 255) / 256 : -((-minx) / 256);
	int64_t y0 = miny >= 0 ? (miny + 255) / 256 : -((-miny) / 256);
	int64_t x1 = maxx >= 0 ? maxx / 256 : -((-maxx + 255) / 256);
	int64_t y1 = maxy >= 0 ? maxy / 256 : -((-maxy + 255) / 256);
	if (x0 < 0) x0 = 0;
	if (y0 < 0) y0 = 0;
	if (x1 > r->width - 1) x1 = r->width - 1;
	if (y1 > r->height - 1) y1 = r->height - 1;
	if (x0 > x1 || y0 > y1)
		return 0;
	/* Edge k is opposite corner k; E_k > 0 inside. */
	const struct sv *P[3] = { p0, p1, p2 };
	int64_t A[3], B[3], Emin[3], E[3];
	for (int k = 0; k < 3; k++) {
		const struct sv *a = P[(k + 1) % 3], *b = P[(k + 2) % 3];
		A[k] = -(b->y - a->y) * 256;          /* step in x */
		B[k] = (b->x - a->x) * 256;           /* step in y */
		E[k] = (b->x - a->x) * (y0 * 256 - a->y) - (b->y - a->y) * (x0 * 256 - a->x);
		Emin[k] = edge_owns(a, b) ? 0 : 1;
	}
	double inv = 1 / (double)area;
	double w0 = p0->w, w1 = p1->w, w2 = p2->w;
	long written = 0;
	for (int64_t y = y0; y <= y1; y++) {
		int64_t e0 = E[0], e1 = E[1], e2 = E[2];
		size_t row = (size_t)y * (size_t)r->width;
		for (int64_t x = x0; x <= x1; x++) {
			if (e0 >= Emin[0] && e1 >= Emin[1] && e2 >= Emin[2]) {
				double l0 = (double)e0 * inv * w0, l1 = (double)e1 * inv * w1;
				double l2 = (double)e2 * inv * w2;
				double w = l0 + l1 + l2;
				size_t i = row + (size_t)x;
				if ((float)w > r->w[i]) {
					r->w[i] = (float)w;
					r->id[i] = id;
					r->b[2 * i] = (float)((l0 * p0->b1 + l1 * p1->b1 + l2 * p2->b1) / w);
					r->b[2 * i + 1] = (float)((l0 * p0->b2 + l1 * p1->b2 + l2 * p2->b2) / w);
					written++;
				}
			}
			e0 += A[0], e1 += A[1], e2 += A[2];
		}
		E[0] += B[0], E[1] += B[1], E[2] += B[2];
	}
	return written;
}

long fct_raster_triangle(struct fct_raster *r, const struct fct_view *v, const double q0[3],
                         const double q1[3], const double q2[3], uint32_t id)
{
	unsigned c0 = outcode(v, q0), c1 = outcode(v, q1), c2 = outcode(v, q2);
	for (int k = 0; k < 3; k++)
		if (!isfinite(q0[k]) || !isfinite(q1[k]) || !isfinite(q2[k]))
			return 0;
	if (c0 & c1 & c2)
		return 0;
	struct sv s[3];
	if (!(c0 | c1 | c2)) {
		project(v, q0, 0, 0, &s[0]);
		project(v, q1, 1, 0, &s[1]);
		project(v, q2, 0, 1, &s[2]);
		return scan(r, &s[0], &s[1], &s[2], id);
	}
	struct cv a[8], b[8];
	memcpy(a[0].q, q0, sizeof a[0].q), a[0].b1 = 0, a[0].b2 = 0;
	memcpy(a[1].q, q1, sizeof a[1].q), a[1].b1 = 1, a[1].b2 = 0;
	memcpy(a[2].q, q2, sizeof a[2].q), a[2].b1 = 0, a[2].b2 = 1;
	int n = 3;
	unsigned any = c0 | c1 | c2;
	for (int k = 0; k < 5 && n >= 3; k++) {
		if (!(any & (1u << k)))
			continue;
		n = clip_poly(v, k, a, n, b);
		memcpy(a, b, sizeof a[0] * (size_t)n);
	}
	if (n < 3)
		return 0;
	struct sv p[8];
	for (int i = 0; i < n; i++)
		project(v, a[i].q, a[i].b1, a[i].b2, &p[i]);
	long written = 0;
	for (int i = 1; i + 1 < n; i++)
		written += scan(r, &p[0], &p[i], &p[i + 1], id);
	return written;
}

/* Lines --------------------------------------------------------------------- */

static void blend(unsigned char *px, const unsigned char rgb[3], double a)
{
	for (int k = 0; k < 3; k++)
		px[k] = (unsigned char)lround(px[k] + a * (rgb[k] - px[k]));
}

/* The line kernel: w0 w1 the 1/z of the ends (for the depth test when r is
 * not NULL). */
static long line(struct fct_image *img, const struct fct_raster *r, double x0, double y0,
                 double x1, double y1, double w0, double w1, double width,
                 const unsigned char rgb[3], double opacity)
{
	if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1) || !(width > 0) ||
	    img->type != FCT_PIX_U8 || img->channels != 3)
		return 0;
	double half = width < 1 ? 0.5 : 0.5 * width;
	double fade = width < 1 ? width : 1;
	int W = img->width, H = img->height;
	int steep = fabs(y1 - y0) > fabs(x1 - x0);
	/* Work in (major, minor) coordinates. */
	double a0 = steep ? y0 : x0, b0 = steep ? x0 : y0, a1 = steep ? y1 : x1, b1 = steep ? x1 : y1;
	int amax = steep ? H - 1 : W - 1, bmax = steep ? W - 1 : H - 1;
	double da = a1 - a0, db = b1 - b0, len2 = da * da + db * db;
	double slope = da != 0 ? db / da : 0;
	double ext = (half + 1) * sqrt(1 + slope * slope);
	double alo = fmax(floor(fmin(a0, a1) - half - 1), 0), ahi = fmin(ceil(fmax(a0, a1) + half + 1), amax);
	unsigned char *data = img->data;
	long touched = 0;
	for (double a = alo; a <= ahi; a++) {
		double t = da != 0 ? (a - a0) / da : 0;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		double bc = b0 + t * db;
		double blo = fmax(floor(bc - ext), 0), bhi = fmin(ceil(bc + ext), bmax);
		for (double b = blo; b <= bhi; b++) {
			double u = len2 > 0 ? ((a - a0) * da + (b - b0) * db) / len2 : 0;
			u = u < 0 ? 0 : u > 1 ? 1 : u;
			double ea = a - (a0 + u * da), eb = b - (b0 + u * db);
			double cov = half + 0.5 - sqrt(ea * ea + eb * eb);
			if (cov <= 0)
				continue;
			if (cov > 1)
				cov = 1;
			int x = (int)(steep ? b : a), y = (int)(steep ? a : b);
			if (r) {
				double wl = w0 + u * (w1 - w0);
				float wmin = INFINITY;
				for (int yy = y - 1; yy <= y + 1; yy++)
					for (int xx = x - 1; xx <= x + 1; xx++)
						if (xx >= 0 && yy >= 0 && xx < r->width && yy < r->height) {
							float ws = r->w[(size_t)yy * (size_t)r->width + (size_t)xx];
							if (ws < wmin)
								wmin = ws;
						}
				if (wl < wmin * (1 - 1e-3))
					continue;
			}
			blend(data + 3 * ((size_t)y * (size_t)W + (size_t)x), rgb, cov * fade * opacity);
			touched++;
		}
	}
	return touched;
}

long fct_draw_line2d(struct fct_image *img, double x0, double y0, double x1, double y1,
                     double width, const unsigned char rgb[3], double opacity)
{
	return line(img, NULL, x0, y0, x1, y1, 0, 0, width, rgb, opacity);
}

long fct_draw_line3d(struct fct_image *img, const struct fct_raster *r, const struct fct_view *v,
                     const double q0[3], const double q1[3], double width,
                     const unsigned char rgb[3], double opacity)
{
	for (int k = 0; k < 3; k++)
		if (!isfinite(q0[k]) || !isfinite(q1[k]))
			return 0;
	double t0 = 0, t1 = 1;
	for (int k = 0; k < 5; k++) {     /* Liang-Barsky against the clip planes */
		double f0 = plane_eval(v, k, q0), f1 = plane_eval(v, k, q1);
		if (f0 < 0 && f1 < 0)
			return 0;
		if (f0 < 0)
			t0 = fmax(t0, f0 / (f0 - f1));
		else if (f1 < 0)
			t1 = fmin(t1, f0 / (f0 - f1));
	}
	if (t0 >= t1)
		return 0;
	double a[3], b[3];
	for (int k = 0; k < 3; k++) {
		a[k] = q0[k] + t0 * (q1[k] - q0[k]);
		b[k] = q0[k] + t1 * (q1[k] - q0[k]);
	}
	double wa = 1 / a[2], wb = 1 / b[2];
	return line(img, r, v->fx * a[0] * wa + v->cx, v->fy * a[1] * wa + v->cy,
	            v->fx * b[0] * wb + v->cx, v->fy * b[1] * wb + v->cy, wa, wb, width, rgb, opacity);
}

void fct_draw_rect(struct fct_image *img, int x0, int y0, int x1, int y1,
                   const unsigned char rgb[3])
{
	if (img->type != FCT_PIX_U8 || img->channels != 3)
		return;
	x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
	x1 = x1 > img->width ? img->width : x1, y1 = y1 > img->height ? img->height : y1;
	unsigned char *data = img->data;
	for (int y = y0; y < y1; y++)
		for (int x = x0; x < x1; x++)
			memcpy(data + 3 * ((size_t)y * (size_t)img->width + (size_t)x), rgb, 3);
}

/* Text ---------------------------------------------------------------------- */

/* The 5x7 font, printable ASCII from ' ': 7 rows per glyph, bit 4 the
 * leftmost column. */
static const unsigned char font5x7[95][7] = {
	{0x00,0x00,0x00,0x00,0x00,0x00,0x00}, {0x04,0x04,0x04,0x04,0x04,0x00,0x04}, /* ' ' ! */
	{0x0A,0x0A,0x00,0x00,0x00,0x00,0x00}, {0x0A,0x0A,0x1F,0x0A,0x1F,0x0A,0x0A}, /* " # */
	{0x04,0x0F,0x14,0x0E,0x05,0x1E,0x04}, {0x18,0x19,0x02,0x04,0x08,0x13,0x03}, /* $ % */
	{0x0C,0x12,0x14,0x08,0x15,0x12,0x0D}, {0x04,0x04,0x00,0x00,0x00,0x00,0x00}, /* & ' */
	{0x02,0x04,0x08,0x08,0x08,0x04,0x02}, {0x08,0x04,0x02,0x02,0x02,0x04,0x08}, /* ( ) */
	{0x00,0x04,0x15,0x0E,0x15,0x04,0x00}, {0x00,0x04,0x04,0x1F,0x04,0x04,0x00}, /* * + */
	{0x00,0x00,0x00,0x00,0x0C,0x04,0x08}, {0x00,0x00,0x00,0x1F,0x00,0x00,0x00}, /* , - */
	{0x00,0x00,0x00,0x00,0x00,0x0C,0x0C}, {0x00,0x01,0x02,0x04,0x08,0x10,0x00}, /* . / */
	{0x0E,0x11,0x13,0x15,0x19,0x11,0x0E}, {0x04,0x0C,0x04,0x04,0x04,0x04,0x0E}, /* 0 1 */
	{0x0E,0x11,0x01,0x02,0x04,0x08,0x1F}, {0x1F,0x02,0x04,0x02,0x01,0x11,0x0E}, /* 2 3 */
	{0x02,0x06,0x0A,0x12,0x1F,0x02,0x02}, {0x1F,0x10,0x1E,0x01,0x01,0x11,0x0E}, /* 4 5 */
	{0x06,0x08,0x10,0x1E,0x11,0x11,0x0E}, {0x1F,0x01,0x02,0x04,0x08,0x08,0x08}, /* 6 7 */
	{0x0E,0x11,0x11,0x0E,0x11,0x11,0x0E}, {0x0E,0x11,0x11,0x0F,0x01,0x02,0x0C}, /* 8 9 */
	{0x00,0x0C,0x0C,0x00,0x0C,0x0C,0x00}, {0x00,0x0C,0x0C,0x00,0x0C,0x04,0x08}, /* : ; */
	{0x02,0x04,0x08,0x10,0x08,0x04,0x02}, {0x00,0x00,0x1F,0x00,0x1F,0x00,0x00}, /* < = */
	{0x08,0x04,0x02,0x01,0x02,0x04,0x08}, {0x0E,0x11,0x01,0x02,0x04,0x00,0x04}, /* > ? */
	{0x0E,0x11,0x01,0x0D,0x15,0x15,0x0E}, {0x0E,0x11,0x11,0x11,0x1F,0x11,0x11}, /* @ A */
	{0x1E,0x11,0x11,0x1E,0x11,0x11,0x1E}, {0x0E,0x11,0x10,0x10,0x10,0x11,0x0E}, /* B C */
	{0x1C,0x12,0x11,0x11,0x11,0x12,0x1C}, {0x1F,0x10,0x10,0x1E,0x10,0x10,0x1F}, /* D E */
	{0x1F,0x10,0x10,0x1E,0x10,0x10,0x10}, {0x0E,0x11,0x10,0x17,0x11,0x11,0x0F}, /* F G */
	{0x11,0x11,0x11,0x1F,0x11,0x11,0x11}, {0x0E,0x04,0x04,0x04,0x04,0x04,0x0E}, /* H I */
	{0x07,0x02,0x02,0x02,0x02,0x12,0x0C}, {0x11,0x12,0x14,0x18,0x14,0x12,0x11}, /* J K */
	{0x10,0x10,0x10,0x10,0x10,0x10,0x1F}, {0x11,0x1B,0x15,0x15,0x11,0x11,0x11}, /* L M */
	{0x11,0x11,0x19,0x15,0x13,0x11,0x11}, {0x0E,0x11,0x11,0x11,0x11,0x11,0x0E}, /* N O */
	{0x1E,0x11,0x11,0x1E,0x10,0x10,0x10}, {0x0E,0x11,0x11,0x11,0x15,0x12,0x0D}, /* P Q */
	{0x1E,0x11,0x11,0x1E,0x14,0x12,0x11}, {0x0F,0x10,0x10,0x0E,0x01,0x01,0x1E}, /* R S */
	{0x1F,0x04,0x04,0x04,0x04,0x04,0x04}, {0x11,0x11,0x11,0x11,0x11,0x11,0x0E}, /* T U */
	{0x11,0x11,0x11,0x11,0x11,0x0A,0x04}, {0x11,0x11,0x11,0x15,0x15,0x15,0x0A}, /* V W */
	{0x11,0x11,0x0A,0x04,0x0A,0x11,0x11}, {0x11,0x11,0x11,0x0A,0x04,0x04,0x04}, /* X Y */
	{0x1F,0x01,0x02,0x04,0x08,0x10,0x1F}, {0x0E,0x08,0x08,0x08,0x08,0x08,0x0E}, /* Z [ */
	{0x00,0x10,0x08,0x04,0x02,0x01,0x00}, {0x0E,0x02,0x02,0x02,0x02,0x02,0x0E}, /* \ ] */
	{0x04,0x0A,0x11,0x00,0x00,0x00,0x00}, {0x00,0x00,0x00,0x00,0x00,0x00,0x1F}, /* ^ _ */
	{0x08,0x04,0x00,0x00,0x00,0x00,0x00}, {0x00,0x00,0x0E,0x01,0x0F,0x11,0x0F}, /* ` a */
	{0x10,0x10,0x16,0x19,0x11,0x11,0x1E}, {0x00,0x00,0x0E,0x10,0x10,0x11,0x0E}, /* b c */
	{0x01,0x01,0x0D,0x13,0x11,0x11,0x0F}, {0x00,0x00,0x0E,0x11,0x1F,0x10,0x0E}, /* d e */
	{0x06,0x09,0x08,0x1C,0x08,0x08,0x08}, {0x00,0x0F,0x11,0x11,0x0F,0x01,0x0E}, /* f g */
	{0x10,0x10,0x16,0x19,0x11,0x11,0x11}, {0x04,0x00,0x0C,0x04,0x04,0x04,0x0E}, /* h i */
	{0x02,0x00,0x06,0x02,0x02,0x12,0x0C}, {0x10,0x10,0x12,0x14,0x18,0x14,0x12}, /* j k */
	{0x0C,0x04,0x04,0x04,0x04,0x04,0x0E}, {0x00,0x00,0x1A,0x15,0x15,0x11,0x11}, /* l m */
	{0x00,0x00,0x16,0x19,0x11,0x11,0x11}, {0x00,0x00,0x0E,0x11,0x11,0x11,0x0E}, /* n o */
	{0x00,0x00,0x1E,0x11,0x1E,0x10,0x10}, {0x00,0x00,0x0D,0x13,0x0F,0x01,0x01}, /* p q */
	{0x00,0x00,0x16,0x19,0x10,0x10,0x10}, {0x00,0x00,0x0E,0x10,0x0E,0x01,0x1E}, /* r s */
	{0x08,0x08,0x1C,0x08,0x08,0x09,0x06}, {0x00,0x00,0x11,0x11,0x11,0x13,0x0D}, /* t u */
	{0x00,0x00,0x11,0x11,0x11,0x0A,0x04}, {0x00,0x00,0x11,0x11,0x15,0x15,0x0A}, /* v w */
	{0x00,0x00,0x11,0x0A,0x04,0x0A,0x11}, {0x00,0x00,0x11,0x11,0x0F,0x01,0x0E}, /* x y */
	{0x00,0x00,0x1F,0x02,0x04,0x08,0x1F}, {0x02,0x04,0x04,0x08,0x04,0x04,0x02}, /* z { */
	{0x04,0x04,0x04,0x04,0x04,0x04,0x04}, {0x08,0x04,0x04,0x02,0x04,0x04,0x08}, /* | } */
	{0x00,0x00,0x08,0x15,0x02,0x00,0x00},                                       /* ~ */
};

void fct_text_size(const char *text, int scale, int *width, int *height)
{
	int col = 0, maxcol = 0, lines = 1;
	for (const char *s = text; *s; s++) {
		if (*s == '\n') {
			lines++;
			col = 0;
			continue;
		}
		col++;
		if (col > maxcol)
			maxcol = col;
	}
	*width = maxcol ? (6 * maxcol - 1) * scale : 0;
	*height = (9 * lines - 2) * scale;
}

int fct_draw_text(struct fct_image *img, int x, int y, int scale, const unsigned char rgb[3],
                  const char *text)
{
	int cx = x, cy = y, maxx = x;
	if (scale < 1)
		scale = 1;
	for (const unsigned char *s = (const unsigned char *)text; *s; s++) {
		if (*s == '\n') {
			cx = x;
			cy += 9 * scale;
			continue;
		}
		unsigned g = (*s >= 32 && *s < 127) ? *s - 32u : '?' - 32u;
		for (int row = 0; row < 7; row++)
			for (int col = 0; col < 5; col++)
				if (font5x7[g][row] & (0x10 >> col))
					fct_draw_rect(img, cx + col * scale, cy + row * scale,
					              cx + (col + 1) * scale, cy + (row + 1) * scale, rgb);
		cx += 6 * scale;
		if (cx - scale > maxx)
			maxx = cx - scale;
	}
	return maxx - x;
}

/* Colours ------------------------------------------------------------------- */

int fct_cmap_parse(const char *name, enum fct_cmap *map)
{
	if (!strcmp(name, "viridis"))
		*map = FCT_CMAP_VIRIDIS;
	else if (!strcmp(name, "gray") || !strcmp(name, "grey"))
		*map = FCT_CMAP_GRAY;
	else if (!strcmp(name, "coolwarm"))
		*map = FCT_CMAP_COOLWARM;
	else
		return -1;
	return 0;
}

void fct_cmap_color(enum fct_cmap map, double t, unsigned char rgb[3])
{
	/* matplotlib's viridis at t = 0, 1/8, ..., 1. */
	static const unsigned char viridis[9][3] = {
		{68, 1, 84}, {71, 44, 122}, {59, 82, 139}, {44, 113, 142}, {33, 145, 140},
		{40, 174, 128}, {94, 201, 98}, {173, 220, 48}, {253, 231, 37},
	};
	/* Moreland's diverging map: its end colours and its grey middle. */
	static const unsigned char coolwarm[3][3] = { {59, 76, 192}, {221, 221, 221}, {180, 4, 38} };
	if (isnan(t)) {
		rgb[0] = rgb[1] = rgb[2] = 128;
		return;
	}
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	const unsigned char (*tab)[3];
	int n;
	switch (map) {
	case FCT_CMAP_GRAY:
		rgb[0] = rgb[1] = rgb[2] = (unsigned char)lround(255 * t);
		return;
	case FCT_CMAP_COOLWARM:
		tab = coolwarm, n = 3;
		break;
	default:
		tab = viridis, n = 9;
		break;
	}
	double x = t * (n - 1);
	int i = (int)x;
	if (i >= n - 1)
		i = n - 2;
	double f = x - i;
	for (int k = 0; k < 3; k++)
		rgb[k] = (unsigned char)lround(tab[i][k] + f * (tab[i + 1][k] - tab[i][k]));
}

void fct_patch_color(long id, unsigned char rgb[3])
{
	if (id < 0) {
		rgb[0] = rgb[1] = rgb[2] = 200;
		return;
	}
	/* Golden-ratio hues; the value alternates over three levels so that
	 * labels whose hues come close again still differ in brightness. */
	double h = fmod((double)id * 0.6180339887498949, 1.0) * 6;
	double s = 0.6, v = (id % 3 == 0) ? 0.95 : (id % 3 == 1) ? 0.8 : 0.65;
	int i = (int)h;
	double f = h - i, p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
	double r, g, b;
	switch (i % 6) {
	case 0: r = v, g = u, b = p; break;
	case 1: r = q, g = v, b = p; break;
	case 2: r = p, g = v, b = u; break;
	case 3: r = p, g = q, b = v; break;
	case 4: r = u, g = p, b = v; break;
	default: r = v, g = p, b = q; break;
	}
	rgb[0] = (unsigned char)lround(255 * r);
	rgb[1] = (unsigned char)lround(255 * g);
	rgb[2] = (unsigned char)lround(255 * b);
}

int fct_image_to_rgb8(const struct fct_image *src, const unsigned char bg[3],
                      struct fct_image *dst, struct fct_err *err)
{
	if (fct_image_alloc(dst, src->width, src->height, 3, FCT_PIX_U8, err))
		return -1;
	int ch = src->channels;
	double scale = src->type == FCT_PIX_U8 ? 1 : src->type == FCT_PIX_U16 ? 255.0 / 65535 : 255;
	unsigned char *out = dst->data;
	size_t n = (size_t)src->width * (size_t)src->height;
	for (size_t i = 0; i < n; i++) {
		double c[4];
		for (int k = 0; k < ch; k++) {
			double v = fct_image_sample(src, i * (size_t)ch + (size_t)k) * scale;
			c[k] = !(v > 0) ? 0 : v > 255 ? 255 : v;
		}
		double rgb[3], a = 255;
		if (ch <= 2)
			rgb[0] = rgb[1] = rgb[2] = c[0];
		else
			rgb[0] = c[0], rgb[1] = c[1], rgb[2] = c[2];
		if (ch == 2 || ch == 4)
			a = c[ch - 1];
		for (int k = 0; k < 3; k++)
			out[3 * i + k] = (unsigned char)lround((rgb[k] * a + bg[k] * (255 - a)) / 255);
	}
	return 0;
}

void fct_texture_sample(const struct fct_image *tex, double s, double t, double rgb[3])
{
	int W = tex->width, H = tex->height;
	double x = s * W - 0.5, y = (1 - t) * H - 0.5;
	x = !(x > 0) ? 0 : x > W - 1 ? W - 1 : x;
	y = !(y > 0) ? 0 : y > H - 1 ? H - 1 : y;
	int i = (int)x, j = (int)y;
	int i1 = i + 1 < W ? i + 1 : i, j1 = j + 1 < H ? j + 1 : j;
	double fx = x - i, fy = y - j;
	const unsigned char *d = tex->data;
	const unsigned char *p00 = d + 3 * ((size_t)j * (size_t)W + (size_t)i);
	const unsigned char *p10 = d + 3 * ((size_t)j * (size_t)W + (size_t)i1);
	const unsigned char *p01 = d + 3 * ((size_t)j1 * (size_t)W + (size_t)i);
	const unsigned char *p11 = d + 3 * ((size_t)j1 * (size_t)W + (size_t)i1);
	for (int k = 0; k < 3; k++) {
		double top = p00[k] + fx * (p10[k] - p00[k]);
		double bot = p01[k] + fx * (p11[k] - p01[k]);
		rgb[k] = top + fy * (bot - top);
	}
}

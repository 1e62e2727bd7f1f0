/* depthsmooth.c - the noise-aware smoothing of a depth image (see
 * depthsmooth.h). */
#include "depth/depthsmooth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

void fct_depth_smooth_default(struct fct_depth_smooth *p)
{
	p->radius = FCT_DEPTH_SMOOTH_RADIUS;
	p->range = FCT_DEPTH_SMOOTH_RANGE;
	p->voxel = 0;
}

static inline int has_data(float z)
{
	return z > 0 && z < INFINITY;
}

/* One pass over the image: out[i] from the pixels of the padded images
 * z (depths, 0: none) and iv (their inverses) around i, the range taken
 * from ref[i] (the depth the pass compares with) and c[i] (1 / (k
 * sigma)), the space from g[j][i] (the spatial weight j pixels off along
 * an axis; the weight at (dx, dy) is g[|dx|] g[|dy|]).  The taps are the
 * outer loops and the pixels of a row the inner one, so that each tap is
 * a loop without branches over the row: a pixel without data or one more
 * than 3 k sigma off has a range weight of 0 by the kernel itself (Tukey's
 * biweight (1 - q / 9)^2 of q = (d / (k sigma))^2, a smooth kernel of
 * bounded support: no exp per tap). */
struct pass {
	size_t w, h, R, pw;          /* image, radius, padded row length */
	const float *z, *iv;         /* padded: pixel (x, y) at (y + R) pw + x + R */
	const float *c;              /* per pixel, unpadded */
	float *const *g;             /* g[0 .. R], each per pixel */
	float *sw, *si;              /* one row of sums */
};

/* One tap over a row: the sums of the row's pixels gain the weighted
 * inverse depth of their neighbour at the tap's offset (zz, vv), gx and gy
 * the spatial weights along the axes.  Four pixels at a time where there
 * is SSE2 (the filter's whole cost; the compiler does not vectorise it at
 * -O2), the same operations in the same order as the scalar loop, so the
 * same floats. */
static inline float tap_weight(float zz, float zc, float c, float gx, float gy)
{
	float d = (zz - zc) * c;
	float t = 1 - d * d * (1.0f / 9);
	t = t > 0 ? t : 0;
	return gx * gy * t * t;
}

static void tap_row(float *restrict sw, float *restrict si, const float *restrict zz, const float *restrict vv,
                    const float *restrict zc, const float *restrict c, const float *restrict gx,
                    const float *restrict gy, size_t w)
{
	size_t x = 0;
#if defined(__SSE2__)
	const __m128 one = _mm_set1_ps(1), ninth = _mm_set1_ps(1.0f / 9), zero = _mm_setzero_ps();
	for (; x + 4 <= w; x += 4) {
		__m128 d = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&zz[x]), _mm_loadu_ps(&zc[x])), _mm_loadu_ps(&c[x]));
		__m128 t = _mm_sub_ps(one, _mm_mul_ps(_mm_mul_ps(d, d), ninth));
		t = _mm_and_ps(t, _mm_cmpgt_ps(t, zero));   /* t > 0 ? t : 0 */
		__m128 wt = _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(_mm_loadu_ps(&gx[x]), _mm_loadu_ps(&gy[x])), t), t);
		_mm_storeu_ps(&sw[x], _mm_add_ps(_mm_loadu_ps(&sw[x]), wt));
		_mm_storeu_ps(&si[x], _mm_add_ps(_mm_loadu_ps(&si[x]), _mm_mul_ps(wt, _mm_loadu_ps(&vv[x]))));
	}
#endif
	for (; x < w; x++) {
		float wt = tap_weight(zz[x], zc[x], c[x], gx[x], gy[x]);
		sw[x] += wt, si[x] += wt * vv[x];
	}
}

static void smooth_pass(const struct pass *P, const float *ref, float *out)
{
	size_t w = P->w, R = P->R, pw = P->pw, side = 2 * R + 1;
	float *sw = P->sw, *si = P->si;
	for (size_t y = 0; y < P->h; y++) {
		size_t r = y * w;
		for (size_t x = 0; x < w; x++)
			sw[x] = 0, si[x] = 0;
		for (size_t dy = 0; dy < side; dy++)
			for (size_t dx = 0; dx < side; dx++) {
				size_t ax = dx > R ? dx - R : R - dx, ay = dy > R ? dy - R : R - dy;
				tap_row(sw, si, &P->z[(y + dy) * pw + dx], &P->iv[(y + dy) * pw + dx], &ref[r], &P->c[r],
				        &P->g[ax][r], &P->g[ay][r], w);
			}
		for (size_t x = 0; x < w; x++) {
			float z = P->z[(y + R) * pw + x + R];
			out[r + x] = z > 0 && P->c[r + x] > 0 && sw[x] > 0 ? sw[x] / si[x] : z;
		}
	}
}

/* The spatial deviation of the window in pixels at a pixel of depth z and
 * sigma sg (see depthsmooth.h): the radius's, narrowed to what costs
 * nothing the volume resolves or what the noise needs, whichever is
 * wider. */
static double spatial_sd(const struct fct_depth_smooth *p, double footprint, double z, double sg)
{
	double s0 = (p->radius + 0.5) / 2;
	if (!(p->voxel > 0) || !(footprint > 0))
		return s0;
	double free = p->voxel / (4 * footprint * z);
	double need = sg / (FCT_DEPTH_SMOOTH_LEFT * p->voxel * sqrt(4 * M_PI));
	double s = free > need ? free : need;
	return s < s0 ? s : s0;
}

int fct_depth_smooth(float *out, const float *depth, size_t w, size_t h, double footprint,
                     const struct fct_noise *nz, const struct fct_depth_smooth *p, struct fct_err *err)
{
	size_t n = w * h;
	if (p->radius > 0 && !(p->range > 0))
		return fct_fail(err, "depth smoothing: range %g is not positive", p->range);
	if (p->radius <= 0 || nz->model == FCT_NOISE_UNKNOWN || nz->model == FCT_NOISE_NONE || n == 0) {
		for (size_t i = 0; i < n; i++)
			out[i] = has_data(depth[i]) ? depth[i] : 0;
		return 0;
	}
	size_t R = (size_t)(p->radius < FCT_DEPTH_SMOOTH_MAX ? p->radius : FCT_DEPTH_SMOOTH_MAX);
	size_t pw = w + 2 * R, ph = h + 2 * R;
	float *g[FCT_DEPTH_SMOOTH_MAX + 1] = { NULL };
	struct pass P = { w, h, R, pw, NULL, NULL, NULL, g, NULL, NULL };
	float *z = fct_alloc_array(pw * ph, sizeof *z, err);
	float *iv = fct_alloc_array(pw * ph, sizeof *iv, err);
	float *c = fct_alloc_array(n, sizeof *c, err);
	float *ref = fct_alloc_array(n, sizeof *ref, err);
	double *row = fct_alloc_array(w, sizeof *row, err);
	P.sw = fct_alloc_array(w, sizeof *P.sw, err);
	P.si = fct_alloc_array(w, sizeof *P.si, err);
	int rc = -1, ok = z && iv && c && ref && row && P.sw && P.si;
	for (size_t j = 0; j <= R && ok; j++)
		ok = (g[j] = fct_alloc_array(n, sizeof *g[j], err)) != NULL;
	if (!ok)
		goto done;
	memset(z, 0, pw * ph * sizeof *z);
	memset(iv, 0, pw * ph * sizeof *iv);
	float *sg = c;
	for (size_t y = 0; y < h; y++) {
		const float *d = &depth[y * w];
		float *zr = &z[(y + R) * pw + R], *vr = &iv[(y + R) * pw + R];
		for (size_t x = 0; x < w; x++) {
			row[x] = has_data(d[x]) ? d[x] : 0;
			zr[x] = (float)row[x];
			vr[x] = row[x] > 0 ? (float)(1 / row[x]) : 0;
			ref[y * w + x] = zr[x];
		}
		fct_noise_sigmas(nz, row, &sg[y * w], w);
	}
	for (size_t i = 0; i < n; i++) {
		/* The spatial weights j pixels off along an axis,
		 * exp(-j^2 / (2 s^2)), as powers of the first; 1 / (k sigma),
		 * 0 where sigma is 0 (nothing else is the same surface: the
		 * pixel keeps its depth). */
		double zi = z[(i / w + R) * pw + i % w + R], s = spatial_sd(p, footprint, zi, sg[i]);
		double g1 = exp(-0.5 / (s * s)), odd = g1, gj = 1;   /* g1^(j^2) = g1^(1 + 3 + ... + 2j - 1) */
		for (size_t j = 0; j <= R; j++) {
			g[j][i] = (float)gj;
			gj *= odd, odd *= g1 * g1;
		}
		c[i] = sg[i] > 0 ? (float)(1 / (p->range * sg[i])) : 0;
	}
	P.z = z, P.iv = iv, P.c = c;
	/* The second pass compares with the first's result: a noisy centre
	 * would otherwise keep the neighbours that agree with its error (a
	 * bilateral filter's bias toward its input). */
	smooth_pass(&P, ref, out);
	memcpy(ref, out, n * sizeof *ref);
	smooth_pass(&P, ref, out);
	rc = 0;
done:
	free(z);
	free(iv);
	free(c);
	free(ref);
	free(row);
	for (size_t j = 0; j <= R; j++)
		free(g[j]);
	free(P.sw);
	free(P.si);
	return rc;
}

int fct_depth_smooth_image(struct fct_image *out, const struct fct_image *img, const struct fct_camera *cam,
                           struct fct_depth_params *p, const struct fct_depth_smooth *sp, struct fct_err *err)
{
	memset(out, 0, sizeof *out);
	size_t w = (size_t)img->width, h = (size_t)img->height;
	size_t n = w * h > 0 ? w * h : 1;
	float *depth = fct_alloc_array(n, sizeof *depth, err);
	float *sm = fct_alloc_array(n, sizeof *sm, err);
	if (!depth || !sm) {
		free(depth);
		free(sm);
		return -1;
	}
	for (size_t y = 0; y < h; y++)
		for (size_t x = 0; x < w; x++)
			depth[y * w + x] = (float)fct_depth_at(img, (int)x, (int)y, p);
	fct_depth_noise_unit(p, img);   /* before p reads metres */
	int rc = fct_depth_smooth(sm, depth, w, h, fct_camera_pixel_angle(cam), &p->noise, sp, err);
	free(depth);
	if (rc) {
		free(sm);
		return -1;
	}
	out->width = img->width, out->height = img->height;
	out->channels = 1;
	out->type = FCT_PIX_F32;
	out->data = sm;
	p->scale_float = 0;
	p->baseline = 0;
	p->min_depth = 0, p->max_depth = INFINITY;   /* applied already */
	return 0;
}

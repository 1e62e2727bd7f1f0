/* depthmesh.c - depth images to meshes (see depthmesh.h). */
#include "depth/depthmesh.h"
#include "geom/geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void fct_depth_params_default(struct fct_depth_params *p)
{
	memset(p, 0, sizeof *p);
	p->depth_scale = 1000;
	p->max_depth = HUGE_VAL;
	p->step = 1;
	p->grid.max_jump = FCT_DEFAULT_MAX_JUMP;
	p->grid.min_faces = FCT_DEFAULT_MIN_FACES;
	p->texcoords = 1;
	p->noise_jump = FCT_DEFAULT_NOISE_JUMP;
}

/* A sample v (metres, or a disparity) made a depth: 0 for no data. */
static inline double sample_depth(double v, const struct fct_depth_params *p)
{
	if (p->baseline > 0)
		v = v > 0 && v + p->doffs > 0 ? p->baseline * p->focal / (v + p->doffs) : 0;
	return v > 0 && v >= p->min_depth && v <= p->max_depth && isfinite(v) ? v : 0;
}

/* A 16-bit sample as a value before sample_depth: 65535 is no data. */
static inline double u16_value(unsigned s, const struct fct_depth_params *p)
{
	return s == 65535 ? 0 : s / p->depth_scale;
}

/* Sample x of an image row as a value before sample_depth. */
static inline double sample_at(const struct fct_image *img, size_t i, const struct fct_depth_params *p)
{
	switch (img->type) {
	case FCT_PIX_U8:
		return ((const unsigned char *)img->data)[i] / p->depth_scale;
	case FCT_PIX_U16:
		return u16_value(((const uint16_t *)img->data)[i], p);
	default: {
		double v = ((const float *)img->data)[i];
		return p->scale_float ? v / p->depth_scale : v;
	}
	}
}

double fct_depth_at(const struct fct_image *img, int x, int y, const struct fct_depth_params *p)
{
	return sample_depth(sample_at(img, (size_t)y * (size_t)img->width + (size_t)x, p), p);
}

/* A 16-bit image's depths and sigmas looked up by sample: most depth
 * frames hold a few thousand distinct millimetre values in 300,000 pixels,
 * and a division and a square root per pixel cost more than a table of
 * each value's (about 0.3 ms of dm2mesh's 18.7 on a 640x480 Kinect frame,
 * 7-Scenes 000000: x0.904 -> x0.888 against the build before, medians of
 * 15).
 * The tables hold the values of every sample up to the largest in the
 * image (65535 aside), made by the same functions as pixel by pixel. */
struct sample_tables {
	double *depth;   /* per sample value, or NULL: no tables */
	float *sigma;    /* the same, or NULL without a noise model */
};

/* Where a 16-bit sample's values are in the tables: 65535 is no data, as
 * 0 is (u16_value). */
static inline unsigned sample_index(unsigned s)
{
	return s == 65535 ? 0 : s;
}

typedef uint16_t v8u16 __attribute__((vector_size(16)));

/* The largest sample_index of r[0..n): eight samples a step with GCC's
 * and Clang's vector extension, 65535 made 0 by adding 1 (one branchless
 * select a sample was 0.15 ms of dm2mesh's 640x480 frame). */
static unsigned largest_sample(const uint16_t *r, size_t n)
{
	const v8u16 one = { 1, 1, 1, 1, 1, 1, 1, 1 };
	v8u16 top8 = { 0, 0, 0, 0, 0, 0, 0, 0 };
	size_t i = 0;
	for (; i + 8 <= n; i += 8) {
		v8u16 v;
		memcpy(&v, r + i, sizeof v);
		v += one;   /* 65535 wraps to 0, the rest are one more */
		v8u16 up = (v8u16)(v > top8);
		top8 = (v & up) | (top8 & ~up);
	}
	unsigned top = 0;
	for (int k = 0; k < 8; k++)
		top = top8[k] > top ? top8[k] : top;
	top = top ? top - 1 : 0;
	for (; i < n; i++)
		top = sample_index(r[i]) > top ? sample_index(r[i]) : top;
	return top;
}

/* The tables of img if it is 16-bit and they are smaller than its ncells
 * cells, else none; 0, or -1 when out of memory. */
static int sample_tables_make(struct sample_tables *t, const struct fct_image *img, size_t ncells,
                              const struct fct_depth_params *p, int noisy, struct fct_err *err)
{
	t->depth = NULL, t->sigma = NULL;
	if (img->type != FCT_PIX_U16)
		return 0;
	unsigned top = largest_sample(img->data, (size_t)img->width * (size_t)img->height);
	size_t values = (size_t)top + 1;
	if (values > ncells)
		return 0;
	if (!(t->depth = fct_alloc_array(values, sizeof *t->depth, err)) ||
	    (noisy && !(t->sigma = fct_alloc_array(values, sizeof *t->sigma, err)))) {
		free(t->depth);
		t->depth = NULL;
		return -1;
	}
	for (unsigned v = 0; v <= top; v++)
		t->depth[v] = sample_depth(u16_value(v, p), p);
	if (noisy)
		fct_noise_sigmas(&p->noise, t->depth, t->sigma, values);
	return 0;
}

static void sample_tables_free(struct sample_tables *t)
{
	free(t->depth);
	free(t->sigma);
}

/* The sigmas of every step-th sample of image row y into out[0..n), by
 * table. */
static void sigma_row(const struct fct_image *img, int y, int step, const float *table, float *out,
                      int n)
{
	const uint16_t *r = (const uint16_t *)img->data + (size_t)y * (size_t)img->width;
	for (int i = 0; i < n; i++)
		out[i] = table[sample_index(r[(size_t)i * (size_t)step])];
}

/* The depths of every step-th sample of image row y into out[0..n): the
 * loop of fct_depth_at with the sample type decided once per row (and a
 * 16-bit sample's depth looked up in table when there is one). */
static void depth_row(const struct fct_image *img, int y, int step, const struct fct_depth_params *p,
                      const double *table, double *out, int n)
{
	size_t base = (size_t)y * (size_t)img->width;
	switch (img->type) {
	case FCT_PIX_U16: {
		const uint16_t *r = (const uint16_t *)img->data + base;
		if (table)
			for (int i = 0; i < n; i++)
				out[i] = table[sample_index(r[(size_t)i * (size_t)step])];
		else
			for (int i = 0; i < n; i++)
				out[i] = sample_depth(u16_value(r[(size_t)i * (size_t)step], p), p);
		break;
	}
	case FCT_PIX_F32: {
		const float *r = (const float *)img->data + base;
		for (int i = 0; i < n; i++) {
			double v = r[(size_t)i * (size_t)step];
			out[i] = sample_depth(p->scale_float ? v / p->depth_scale : v, p);
		}
		break;
	}
	default:
		for (int i = 0; i < n; i++)
			out[i] = sample_depth(sample_at(img, base + (size_t)i * (size_t)step, p), p);
	}
}

double fct_depth_unit(const struct fct_image *img, const struct fct_depth_params *p)
{
	int integer = img->type == FCT_PIX_U8 || img->type == FCT_PIX_U16;
	return integer && !(p->baseline > 0) ? 1 / p->depth_scale : 0;
}

void fct_depth_noise_unit(struct fct_depth_params *p, const struct fct_image *img)
{
	if (p->noise.model != FCT_NOISE_UNKNOWN && p->noise.unit == 0)
		p->noise.unit = fct_depth_unit(img, p);
}

/* The vertex properties that come from each vertex's cell (s t, sigma, and
 * the kept depths): vertices are in cell order, so the rows are walked
 * alongside instead of dividing each cell index.  s depends on the column
 * alone and t on the row, and the sum of squares under sigma's root is
 * made of a column's and a row's squares: each is computed once, by the
 * same expressions in the same order. */
static int cell_properties(struct fct_mesh *m, const struct fct_image *img, int step, int gw, int gh,
                           const uint32_t *cell_of, const double *depth, const double *col,
                           const double *row, const float *cell_sigma, int texcoords, float *kept,
                           struct fct_err *err)
{
	float *s = NULL, *t = NULL, *sigma = NULL;
	/* The float vertex properties, in one block, for the loop below to
	 * fill; a mesh without vertices (every piece too small) has them
	 * without data. */
	static const char *const names[] = { "s", "t", "sigma" };
	size_t first = texcoords ? 0 : 2, last = cell_sigma ? 3 : 2;
	if (fct_elem_add_scalars_big(&m->vertex, names + first, last - first, FCT_FLOAT32, err))
		return -1;
	if (texcoords)   /* adding a property may move the others */
		s = fct_elem_find(&m->vertex, "s")->data, t = fct_elem_find(&m->vertex, "t")->data;
	if (cell_sigma)
		sigma = fct_elem_find(&m->vertex, "sigma")->data;
	size_t w = (size_t)img->width, j = 0, start = 0, gwz = (size_t)gw, st = (size_t)step;
	/* per column: s, x^2, z^2 of the ray; per row: t, y^2 */
	double *tab = fct_alloc_array(3 * gwz + 2 * (size_t)gh, sizeof *tab, err);
	if (!tab)
		return -1;
	double *s_col = tab, *xx = tab + gwz, *zz = tab + 2 * gwz, *t_row = tab + 3 * gwz, *yy = t_row + gh;
	for (size_t i = 0; i < gwz; i++) {
		s_col[i] = (float)(((double)(i * st) + 0.5) / img->width);
		xx[i] = col[3 * i] * col[3 * i], zz[i] = col[3 * i + 2] * col[3 * i + 2];
	}
	for (size_t r = 0; r < (size_t)gh; r++) {
		t_row[r] = (float)(1 - ((double)(r * st) + 0.5) / img->height);
		yy[r] = row[r] * row[r];
	}
	for (size_t v = 0; v < m->nv; v++) {
		size_t c = cell_of[v];
		while (c >= start + gwz)
			start += gwz, j++;
		size_t i = c - start;
		if (texcoords)
			s[v] = (float)s_col[i], t[v] = (float)t_row[j];
		if (sigma)
			sigma[v] = (float)(cell_sigma[c] * sqrt(xx[i] + yy[j] + zz[i]));
		if (kept)   /* cell (i, j) is pixel (i step, j step) */
			kept[j * st * w + i * st] = (float)depth[c];
	}
	free(tab);
	return 0;
}

double fct_depth_median(const struct fct_image *img, const struct fct_depth_params *p)
{
	if (img->channels != 1)
		return 0;
	size_t n = 0, cap = ((size_t)img->width / 4 + 1) * ((size_t)img->height / 4 + 1);
	/* Samples rounded to float: no depth image holds more. */
	double *d = malloc(cap * sizeof *d);
	if (!d)
		return 0;
	for (int y = 0; y < img->height; y += 4)
		for (int x = 0; x < img->width; x += 4) {
			double v = fct_depth_at(img, x, y, p);
			if (v > 0)
				d[n++] = (float)v;
		}
	double med = n > 0 ? fct_select_kth(d, n, n / 2) : 0;
	free(d);
	return med;
}

int fct_depth_implausible(char *msg, size_t size, const struct fct_image *img,
                          const struct fct_camera *cam, const struct fct_depth_params *p)
{
	double scale = 0;
	const char *name = fct_camera_known(cam, p->depth_scale, &scale);
	if (!name || img->channels != 1)
		return 0;
	double med = fct_depth_median(img, p);
	int bad = 0;
	if (med > 0) {
		bad = !(med >= FCT_SENSOR_MIN_DEPTH && med <= FCT_SENSOR_MAX_DEPTH);
		int integer = img->type != FCT_PIX_F32 || p->scale_float;
		if (bad && integer && scale != p->depth_scale)
			snprintf(msg, size, "median depth %.3g m: implausible for an RGB-D sensor (%g to %g "
			         "m); the camera is %s's, whose depth units are %g a metre, not %g "
			         "(--depth-scale)", med, FCT_SENSOR_MIN_DEPTH, FCT_SENSOR_MAX_DEPTH, name,
			         scale, p->depth_scale);
		else if (bad)
			snprintf(msg, size, "median depth %.3g m: implausible for an RGB-D sensor (%g to %g "
			         "m; the camera is %s's): is the depth scale right?", med,
			         FCT_SENSOR_MIN_DEPTH, FCT_SENSOR_MAX_DEPTH, name);
	}
	return bad;
}

int fct_depth_mesh(struct fct_mesh *m, const struct fct_image *img, const struct fct_camera *cam,
                   const struct fct_depth_params *p, struct fct_grid_stats *stats,
                   struct fct_err *err)
{
	return fct_depth_mesh_kept(m, img, cam, p, stats, NULL, err);
}

int fct_depth_mesh_kept(struct fct_mesh *m, const struct fct_image *img, const struct fct_camera *cam,
                        const struct fct_depth_params *p, struct fct_grid_stats *stats, float **kept,
                        struct fct_err *err)
{
	fct_mesh_init(m);
	if (kept)
		*kept = NULL;
	if (img->channels != 1)
		return fct_fail(err, "depth image has %d channels; one is needed", img->channels);
	if (cam->kind == FCT_CAMERA_NONE)
		return fct_fail(err, "no camera");
	if (cam->width != img->width || cam->height != img->height)
		return fct_fail(err, "the camera is %dx%d but the depth image is %dx%d",
		                cam->width, cam->height, img->width, img->height);
	if (p->step < 1)
		return fct_fail(err, "step must be at least 1");
	int step = p->step, gw = (img->width + step - 1) / step, gh = (img->height + step - 1) / step;
	size_t ncells = (size_t)gw * (size_t)gh;
	int noisy = p->noise.model != FCT_NOISE_UNKNOWN;
	/* With a noise model the cells' sigmas follow their depths in one
	 * block: fresh memory is cleared by the kernel a 2 MB page at a time
	 * (fct_alloc_big), and 640x480 depths (2.5 MB) and sigmas (1.2 MB) fill
	 * two pages together but three apart. */
	size_t cell_bytes = sizeof(double) + (noisy ? sizeof(float) : 0);
	double *depth = fct_alloc_big(ncells, cell_bytes, err);
	double *col = fct_alloc_array((size_t)gw, 3 * sizeof *col, err);
	double *row = fct_alloc_array((size_t)gh, sizeof *row, err);
	uint32_t *cell_of = NULL;
	float *sigma = NULL;
	int rc = -1;
	struct sample_tables tab = { NULL, NULL };
	if (!depth || !col || !row || sample_tables_make(&tab, img, ncells, p, noisy, err))
		goto out;

	/* Rays factor into a column part and a row part for both models:
	 * pinhole ((u-cx)/fx, (v-cy)/fy, 1), cylindrical (sin, (v-cy)/f, cos). */
	for (int i = 0; i < gw; i++)
		fct_camera_ray(cam, (double)i * step, 0, &col[3 * i]);
	for (int j = 0; j < gh; j++) {
		double ray[3];
		fct_camera_ray(cam, 0, (double)j * step, ray);
		row[j] = ray[1];
		depth_row(img, j * step, step, p, tab.depth, depth + (size_t)j * (size_t)gw, gw);
	}
	if (noisy) {
		sigma = (float *)(depth + ncells);
		if (tab.sigma)
			for (int j = 0; j < gh; j++)
				sigma_row(img, j * step, step, tab.sigma, sigma + (size_t)j * (size_t)gw, gw);
		else
			fct_noise_sigmas(&p->noise, depth, sigma, ncells);
	}
	struct fct_range_grid g = { gw, gh, NULL, col, row, depth, step * fct_camera_pixel_angle(cam),
	                            cam->kind == FCT_CAMERA_CYLINDRICAL, sigma, noisy ? p->noise_jump : 0 };
	if (fct_grid_mesh(m, &g, &p->grid, &cell_of, stats, err))
		goto out;

	if (kept && !(*kept = calloc((size_t)img->width * (size_t)img->height, sizeof **kept))) {
		fct_fail(err, "out of memory");
		goto out;
	}
	if (cell_properties(m, img, step, gw, gh, cell_of, depth, col, row, sigma, p->texcoords,
	                    kept ? *kept : NULL, err))
		goto out;
	rc = 0;
out:
	sample_tables_free(&tab);
	free(depth);   /* and sigma */
	free(col);
	free(row);
	free(cell_of);
	if (rc) {
		fct_mesh_free(m);
		if (kept) {
			free(*kept);
			*kept = NULL;
		}
	}
	return rc;
}

int fct_mesh_noise_sigma(struct fct_mesh *m, const struct fct_noise *nz, const struct fct_camera *cam,
                         const double *inv, struct fct_err *err)
{
	int seen = cam && cam->kind != FCT_CAMERA_NONE;
	if (nz->model == FCT_NOISE_UNKNOWN)
		return fct_fail(err, "no noise model");
	if (!seen && fct_noise_grows_with_depth(nz)) {
		char text[256];
		fct_noise_format(nz, text, sizeof text);
		return fct_fail(err, "the noise model \"%s\" grows with depth, and the mesh has no camera "
		                "(poly:A,0,0 is one figure)", text);
	}
	struct fct_prop *sg = fct_elem_add_scalar(&m->vertex, "sigma", FCT_FLOAT32, err);
	if (!sg)
		return -1;
	double one = fct_noise_sigma(nz, 1);
	for (size_t i = 0; i < m->nv; i++) {
		double s = one;
		if (seen) {
			double q[3], u, v, depth;
			const double *x = &m->xyz[3 * i];
			if (inv)
				fct_pose_apply(inv, x, q);
			else
				q[0] = x[0], q[1] = x[1], q[2] = x[2];
			double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
			if (fct_camera_project(cam, q, &u, &v, &depth) && depth > 0)
				s = fct_noise_sigma(nz, depth) * len / depth;
			else
				s = fct_noise_sigma(nz, len);
		}
		fct_prop_set(sg, i, s);
	}
	return 0;
}

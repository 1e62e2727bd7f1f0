/* depthmesh.c - depth images to meshes (see depthmesh.h). */
#include "depthmesh.h"

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

double fct_depth_at(const struct fct_image *img, int x, int y, const struct fct_depth_params *p)
{
	size_t i = (size_t)y * (size_t)img->width + (size_t)x;
	double v;
	switch (img->type) {
	case FCT_PIX_U8:
		v = ((const unsigned char *)img->data)[i] / p->depth_scale;
		break;
	case FCT_PIX_U16: {
		unsigned s = ((const uint16_t *)img->data)[i];
		v = s == 65535 ? 0 : s / p->depth_scale;
		break;
	}
	default:
		v = ((const float *)img->data)[i];
		if (p->scale_float)
			v /= p->depth_scale;
	}
	if (p->baseline > 0)
		v = v > 0 ? p->baseline * p->focal / v : 0;
	return v > 0 && v >= p->min_depth && v <= p->max_depth && isfinite(v) ? v : 0;
}

double fct_depth_unit(const struct fct_image *img, const struct fct_depth_params *p)
{
	int integer = img->type == FCT_PIX_U8 || img->type == FCT_PIX_U16;
	return integer && !(p->baseline > 0) ? 1 / p->depth_scale : 0;
}

/* The float vertex property sigma: each vertex's depth deviation under nz
 * times its ray's length (the rays factor as in fct_depth_mesh_kept). */
static int add_sigma(struct fct_mesh *m, const struct fct_noise *nz, const uint32_t *cell_of, int gw,
                     const double *depth, const double *col, const double *row, struct fct_err *err)
{
	struct fct_prop *ps = fct_elem_add_scalar(&m->vertex, "sigma", FCT_FLOAT32, err);
	if (!ps)
		return -1;
	float *sigma = ps->data;
	for (size_t v = 0; v < m->nv; v++) {
		size_t c = cell_of[v], i = c % (size_t)gw, j = c / (size_t)gw;
		const double *r = &col[3 * i];
		double len = sqrt(r[0] * r[0] + row[j] * row[j] + r[2] * r[2]);
		sigma[v] = (float)(fct_noise_sigma(nz, depth[c]) * len);
	}
	return 0;
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
	double *depth = fct_alloc_array(ncells, sizeof *depth, err);
	double *col = fct_alloc_array((size_t)gw, 3 * sizeof *col, err);
	double *row = fct_alloc_array((size_t)gh, sizeof *row, err);
	uint32_t *cell_of = NULL;
	float *allow = NULL;
	int rc = -1;
	if (!depth || !col || !row)
		goto out;

	/* Rays factor into a column part and a row part for both models:
	 * pinhole ((u-cx)/fx, (v-cy)/fy, 1), cylindrical (sin, (v-cy)/f, cos). */
	for (int i = 0; i < gw; i++)
		fct_camera_ray(cam, (double)i * step, 0, &col[3 * i]);
	for (int j = 0; j < gh; j++) {
		double ray[3];
		fct_camera_ray(cam, 0, (double)j * step, ray);
		row[j] = ray[1];
		for (int i = 0; i < gw; i++)
			depth[(size_t)j * gw + i] = fct_depth_at(img, i * step, j * step, p);
	}
	if (p->noise.model != FCT_NOISE_UNKNOWN && p->noise_jump > 0) {
		if (!(allow = fct_alloc_array(ncells, sizeof *allow, err)))
			goto out;
		double k = M_SQRT2 * p->noise_jump;
		for (size_t c = 0; c < ncells; c++)
			allow[c] = depth[c] > 0 ? (float)(k * fct_noise_sigma(&p->noise, depth[c])) : 0;
	}
	struct fct_range_grid g = { gw, gh, NULL, col, row, depth, step * fct_camera_pixel_angle(cam),
	                            cam->kind == FCT_CAMERA_CYLINDRICAL, allow };
	if (fct_grid_mesh(m, &g, &p->grid, &cell_of, stats, err))
		goto out;

	if (p->texcoords) {
		struct fct_prop *ps = fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, err);
		if (!ps || !fct_elem_add_scalar(&m->vertex, "t", FCT_FLOAT32, err))
			goto out;
		ps = fct_elem_find(&m->vertex, "s");
		float *s = ps->data, *t = fct_elem_find(&m->vertex, "t")->data;
		for (size_t v = 0; v < m->nv; v++) {
			size_t u = cell_of[v] % (size_t)gw * (size_t)step;
			size_t r = cell_of[v] / (size_t)gw * (size_t)step;
			s[v] = (float)((u + 0.5) / img->width);
			t[v] = (float)(1 - (r + 0.5) / img->height);
		}
	}
	if (p->noise.model != FCT_NOISE_UNKNOWN && add_sigma(m, &p->noise, cell_of, gw, depth, col, row, err))
		goto out;
	if (kept) {
		size_t w = (size_t)img->width;
		if (!(*kept = calloc(w * (size_t)img->height, sizeof **kept))) {
			fct_fail(err, "out of memory");
			goto out;
		}
		/* Cell (i, j) is pixel (i step, j step). */
		for (size_t v = 0; v < m->nv; v++) {
			size_t i = cell_of[v] % (size_t)gw, j = cell_of[v] / (size_t)gw;
			(*kept)[j * (size_t)step * w + i * (size_t)step] = (float)depth[cell_of[v]];
		}
	}
	rc = 0;
out:
	free(depth);
	free(allow);
	free(col);
	free(row);
	free(cell_of);
	if (rc)
		fct_mesh_free(m);
	return rc;
}

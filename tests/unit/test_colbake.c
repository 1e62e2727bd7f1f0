/* test_colbake.c - a texture baked from a dense mesh's vertex colours onto
 * the planar model made from it (segmentation and planar model as
 * planarize makes them): a 1.2 m square grid at 1 cm, its vertices
 * coloured with three green lines 3 cm wide (x = 0.37, y = 0.61, x + y =
 * 1.0) on a light ground.  At 60 points on the lines' centres and 60 on the
 * ground, 3 cm or more from any line, the model's texture gives the true
 * colour within 8 levels (mean within 3); the model's own vertex colours
 * (what it carried before: a few vertices, all on the ground) miss the
 * lines by more than 100 levels.  The pages are the same bytes on 1 and 3
 * threads; the texel is half the mean edge; a sliver narrower than a texel
 * is textured along its length; the nearest-point colour is the barycentric
 * one; a NaN vertex in the dense mesh is left out, a model without faces
 * refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/mesh.h"
#include "io/header.h"
#include "planar/planemodel.h"
#include "planar/segment.h"
#include "planar/segmesh.h"
#include "render/colbake.h"
#include "render/raster.h"
#include "render/texmap.h"
#include "render/viewtex.h"

#define N 121                 /* grid vertices per side, 1 cm apart */
#define SPACING 0.01
#define HALF_WIDTH 0.015      /* a vertex this close to a line's centre is green */

static const double green[3] = { 60, 140, 40 }, ground[3] = { 210, 200, 190 };

/* The distance from (x, y) to the nearest line's centre. */
static double line_dist(double x, double y)
{
	double d = fabs(x - 0.37);
	d = fmin(d, fabs(y - 0.61));
	return fmin(d, fabs(x + y - 1.0) / sqrt(2));
}

/* The dense grid on the plane z = 1 with its lines drawn in vertex colours. */
static void dense_grid(struct fct_mesh *m)
{
	struct fct_err err;
	fct_mesh_init(m);
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++)
			fct_mesh_add_vertex(m, i * SPACING, j * SPACING, 1, &err);
	for (int j = 0; j + 1 < N; j++)
		for (int i = 0; i + 1 < N; i++) {
			uint32_t a = (uint32_t)(j * N + i), b = a + 1, c = a + N, d = c + 1;
			uint32_t t1[3] = { a, b, c }, t2[3] = { b, d, c };
			fct_mesh_add_face(m, t1, 3, &err);
			fct_mesh_add_face(m, t2, 3, &err);
		}
	static const char *const names[3] = { "red", "green", "blue" };
	for (int k = 0; k < 3; k++) {
		struct fct_prop *p = fct_elem_add_scalar(&m->vertex, names[k], FCT_UINT8, &err);
		for (size_t i = 0; i < m->nv; i++) {
			const double *x = m->xyz + 3 * i;
			fct_prop_set(p, i, line_dist(x[0], x[1]) < HALF_WIDTH ? green[k] : ground[k]);
		}
	}
}

/* Segmentation and the planar model, as planarize runs them. */
static int planar_model(struct fct_mesh *m)
{
	struct fct_err err;
	struct fct_segment_params sp;
	struct fct_planar_params pp;
	struct fct_segment_stats sst;
	struct fct_planar_stats pst;
	fct_segment_params_default(&sp);
	fct_planar_params_default(&pp);
	return fct_segment_mesh(m, &sp, 0, &sst, &err) || fct_planar_model(m, &pp, &pst, &err);
}

/* The face of the model (on z = 1) over (x, y), its fanned triangle's
 * corners (fvert indices) and barycentrics; 0 when none. */
static int locate(const struct fct_mesh *m, double x, double y, uint32_t c[3], double w[3])
{
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], n = fct_face_size(m, f);
		for (uint32_t k = 1; k + 1 < n; k++) {
			uint32_t cc[3] = { s, s + k, s + k + 1 };
			const double *p0 = m->xyz + 3 * (size_t)m->fvert[cc[0]];
			const double *p1 = m->xyz + 3 * (size_t)m->fvert[cc[1]];
			const double *p2 = m->xyz + 3 * (size_t)m->fvert[cc[2]];
			double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
			if (fabs(det) < 1e-12)
				continue;
			double b1 = ((x - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (y - p0[1])) / det;
			double b2 = ((p1[0] - p0[0]) * (y - p0[1]) - (x - p0[0]) * (p1[1] - p0[1])) / det;
			if (b1 >= -1e-9 && b2 >= -1e-9 && b1 + b2 <= 1 + 1e-9) {
				memcpy(c, cc, sizeof cc);
				w[0] = 1 - b1 - b2, w[1] = b1, w[2] = b2;
				return 1;
			}
		}
	}
	return 0;
}

/* Largest channel difference between a and b. */
static double cdiff(const double a[3], const double b[3])
{
	return fmax(fabs(a[0] - b[0]), fmax(fabs(a[1] - b[1]), fabs(a[2] - b[2])));
}

static void test_lines(void)
{
	struct fct_mesh dense, model;
	struct fct_err err;
	dense_grid(&dense);
	struct fct_colbake B;
	CHECK(fct_colbake_init(&B, &dense, &err) == 0);
	CHECK_NEAR(B.mean_edge, SPACING * (2 + sqrt(2)) / 3, 1e-9);
	fct_mesh_copy(&model, &dense, &err);
	CHECK(fct_colbake_applies(&model));
	CHECK(planar_model(&model) == 0);
	CHECK_MSG(model.nf > 0 && model.nf < 200, "model of %zu faces", model.nf);
	fct_mesh_free(&dense);

	struct fct_colbake_params p;
	fct_colbake_params_default(&p);
	CHECK_NEAR(fct_colbake_texel(&B, &model, &p), 0.5 * B.mean_edge, 1e-12);
	p.nthreads = 1;
	struct fct_viewtex *T1 = fct_colbake_texture(&B, &model, &p, &err);
	p.nthreads = 3;
	struct fct_viewtex *T3 = fct_colbake_texture(&B, &model, &p, &err);
	CHECK(T1 && T3);
	if (!T1 || !T3)
		goto out;
	CHECK_INT(fct_viewtex_npages(T1), 1);
	const struct fct_image *pg1 = fct_viewtex_page(T1, 0), *pg3 = fct_viewtex_page(T3, 0);
	CHECK(pg1->width == pg3->width && pg1->height == pg3->height &&
	      !memcmp(pg1->data, pg3->data, (size_t)pg1->width * (size_t)pg1->height * 3));
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T1, &st);
	CHECK_MSG(st.charts >= 1 && st.rectified == st.charts, "%zu charts, %zu rectified", st.charts,
	          st.rectified);

	/* The model's own vertex colours, before the texture's coordinates. */
	const struct fct_prop *vc[3] = { fct_elem_find(&model.vertex, "red"),
	                                 fct_elem_find(&model.vertex, "green"),
	                                 fct_elem_find(&model.vertex, "blue") };
	CHECK(vc[0] && vc[1] && vc[2]);
	struct fct_mesh vmodel;
	fct_mesh_copy(&vmodel, &model, &err);
	char *names[1] = { "atlas.png" };
	CHECK(fct_viewtex_apply(T1, &model, names, 1, &err) == 0);
	float *tst = NULL;
	int32_t *tn = NULL;
	CHECK(fct_texmap_corners(&model, &tst, &tn, &err) == 1);
	CHECK_STR(fct_header_texture(&model, 0), "atlas.png");

	double tex_max = 0, tex_sum = 0, vert_line_min = INFINITY, vert_ground_max = 0;
	int n = 0, located = 0;
	for (int on_line = 1; on_line >= 0; on_line--)
		for (int i = 0; i < 60; i++) {
			double x, y, t = (i + 0.5) / 60;
			if (on_line) {
				/* Along the three lines, away from their crossings. */
				if (i % 3 == 0)
					x = 0.37, y = 0.05 + 1.1 * t;
				else if (i % 3 == 1)
					x = 0.05 + 1.1 * t, y = 0.61;
				else
					x = 0.05 + 0.9 * t, y = 1.0 - x;
				if (line_dist(x, y) > 1e-9 || (fabs(x - 0.37) < 0.05 && fabs(y - 0.61) < 0.05) ||
				    (fabs(x - 0.37) < 0.05 && fabs(y - 0.63) < 0.05) ||
				    (fabs(x - 0.39) < 0.05 && fabs(y - 0.61) < 0.05))
					continue;
			} else {
				x = 0.05 + 1.1 * t, y = 0.05 + 1.1 * fmod(t * 7.31, 1);
				if (line_dist(x, y) < 0.03)
					continue;
			}
			uint32_t c[3];
			double w[3], s = 0, tt = 0, tex[3], vert[3] = { 0, 0, 0 };
			if (!locate(&vmodel, x, y, c, w))
				continue;
			located++;
			for (int k = 0; k < 3; k++) {
				s += w[k] * tst[2 * (size_t)c[k]];
				tt += w[k] * tst[2 * (size_t)c[k] + 1];
				for (int j = 0; j < 3; j++)
					vert[j] += w[k] * fct_prop_get(vc[j], vmodel.fvert[c[k]]);
			}
			fct_texture_sample(pg1, s, tt, tex);
			const double *truth = on_line ? green : ground;
			double e = cdiff(tex, truth);
			tex_max = fmax(tex_max, e);
			tex_sum += e;
			n++;
			if (on_line)
				vert_line_min = fmin(vert_line_min, cdiff(vert, truth));
			else
				vert_ground_max = fmax(vert_ground_max, cdiff(vert, truth));
		}
	CHECK_MSG(located == n && n >= 90, "%d points located, %d measured", located, n);
	CHECK_MSG(tex_max <= 8, "texture: largest error %.2f levels", tex_max);
	CHECK_MSG(n && tex_sum / n <= 3, "texture: mean error %.2f levels", n ? tex_sum / n : 0);
	/* The vertex colours know nothing of the lines (the ground's colour,
	 * within a few levels, everywhere). */
	CHECK_MSG(vert_line_min > 100, "vertex colours: nearest to a line's green %.2f levels", vert_line_min);
	CHECK_MSG(vert_ground_max < 20, "vertex colours: ground error %.2f levels", vert_ground_max);
	free(tst);
	free(tn);
	fct_mesh_free(&vmodel);
out:
	fct_viewtex_free(T1);
	fct_viewtex_free(T3);
	fct_mesh_free(&model);
	fct_colbake_free(&B);
}

/* The nearest point's colour is the barycentric mix of its triangle's. */
static void test_colour(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0, 0, 0, &err);
	fct_mesh_add_vertex(&m, 1, 0, 0, &err);
	fct_mesh_add_vertex(&m, 0, 1, 0, &err);
	fct_mesh_add_vertex(&m, NAN, 0, 0, &err);
	uint32_t t[3] = { 0, 1, 2 }, bad[3] = { 0, 3, 1 };
	fct_mesh_add_face(&m, t, 3, &err);
	fct_mesh_add_face(&m, bad, 3, &err);
	CHECK(fct_colbake_applies(&m) == 0);
	struct fct_colbake B;
	CHECK(fct_colbake_init(&B, &m, &err) == -1);
	static const char *const names[3] = { "red", "green", "blue" };
	for (int k = 0; k < 3; k++) {
		struct fct_prop *p = fct_elem_add_scalar(&m.vertex, names[k], FCT_UINT8, &err);
		fct_prop_set(p, 0, k == 0 ? 200 : 0);
		fct_prop_set(p, 1, k == 1 ? 200 : 0);
		fct_prop_set(p, 2, k == 2 ? 200 : 0);
	}
	CHECK(fct_colbake_applies(&m));
	CHECK(fct_colbake_init(&B, &m, &err) == 0);
	CHECK_INT(B.ntri, 1);                       /* the face with the NaN corner left out */
	double rgb[3], x[3] = { 0.25, 0.5, 0.3 };   /* above (0.25, 0.5): weights 0.25 0.25 0.5 */
	CHECK(fct_colbake_colour(&B, x, rgb) == 0);
	CHECK_NEAR(rgb[0], 50, 1e-9);
	CHECK_NEAR(rgb[1], 50, 1e-9);
	CHECK_NEAR(rgb[2], 100, 1e-9);
	double far[3] = { 3, 3, 0 };                /* nearest the edge's middle (0.5, 0.5) */
	CHECK(fct_colbake_colour(&B, far, rgb) == 0);
	CHECK_NEAR(rgb[1], 100, 1e-9);
	CHECK_NEAR(rgb[2], 100, 1e-9);
	struct fct_mesh empty;
	fct_mesh_init(&empty);
	fct_mesh_add_vertex(&empty, 0, 0, 0, &err);
	struct fct_colbake_params p;
	fct_colbake_params_default(&p);
	CHECK(fct_colbake_texture(&B, &empty, &p, &err) == NULL);
	fct_mesh_free(&empty);
	fct_colbake_free(&B);
	fct_colbake_free(&B);                       /* twice: zeroed */
	fct_mesh_free(&m);
}

/* A sliver 3 mm wide and 1 m long, under the 5.7 mm texel: no texel's
 * centre lies in it, yet its texture along its whole length is the dense
 * mesh's colour there, not the black between charts. */
static void test_sliver(void)
{
	struct fct_mesh dense, model;
	struct fct_err err;
	dense_grid(&dense);
	struct fct_colbake B;
	CHECK(fct_colbake_init(&B, &dense, &err) == 0);
	fct_mesh_init(&model);
	fct_mesh_add_vertex(&model, 0.1, 0.5, 1, &err);
	fct_mesh_add_vertex(&model, 1.1, 0.5, 1, &err);
	fct_mesh_add_vertex(&model, 1.1, 0.503, 1, &err);
	uint32_t t[3] = { 0, 1, 2 };
	fct_mesh_add_face(&model, t, 3, &err);
	struct fct_colbake_params p;
	fct_colbake_params_default(&p);
	struct fct_viewtex *T = fct_colbake_texture(&B, &model, &p, &err);
	CHECK(T != NULL);
	char *names[1] = { "atlas.png" };
	float *st = NULL;
	int32_t *tn = NULL;
	if (T && fct_viewtex_apply(T, &model, names, 1, &err) == 0 &&
	    fct_texmap_corners(&model, &st, &tn, &err) == 1) {
		double worst = 0;
		for (int i = 1; i < 20; i++) {
			/* Along the sliver's middle, at x from 0.15 to 1.05. */
			double u = i / 20.0, w[3] = { 1 - u, 0.5 * u, 0.5 * u };
			double s = 0, tt = 0, x = 0, y = 0, tex[3];
			for (int k = 0; k < 3; k++) {
				s += w[k] * st[2 * k], tt += w[k] * st[2 * k + 1];
				x += w[k] * model.xyz[3 * k], y += w[k] * model.xyz[3 * k + 1];
			}
			fct_texture_sample(fct_viewtex_page(T, 0), s, tt, tex);
			const double *truth = line_dist(x, y) > 0.03 ? ground : line_dist(x, y) < 0.01 ? green : NULL;
			if (truth)
				worst = fmax(worst, cdiff(tex, truth));
		}
		CHECK_MSG(worst <= 8, "sliver: largest error %.2f levels", worst);
	} else {
		CHECK(0);
	}
	free(st);
	free(tn);
	fct_viewtex_free(T);
	fct_mesh_free(&model);
	fct_mesh_free(&dense);
	fct_colbake_free(&B);
}

int main(void)
{
	test_colour();
	test_lines();
	test_sliver();
	CHECK_DONE();
}

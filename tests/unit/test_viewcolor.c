/* test_viewcolor.c - vertex colour from the views' images: a flat view of
 * a uniform image gives exactly its colour (at the camera's resolution and
 * at another), vertices out of view, occluded or facing away get the
 * fallback, two views average, and on mkscene's room fused from three views
 * the colour of each fused vertex is close to the scene's true colour at
 * that point (far closer than the best constant colour); the noise of a
 * fused vertex from the views that see it, by hand, and its range image
 * from a depth image. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "depth/depthmesh.h"
#include "fusion/fuse.h"
#include "fusion/mcubes.h"
#include "scene/scene.h"
#include "square.h"
#include "render/viewcolor.h"

static void add_normals(struct fct_mesh *m)
{
	struct fct_err err;
	fct_elem_add_scalar(&m->vertex, "nx", FCT_FLOAT32, &err);
	fct_elem_add_scalar(&m->vertex, "ny", FCT_FLOAT32, &err);
	struct fct_prop *nz = fct_elem_add_scalar(&m->vertex, "nz", FCT_FLOAT32, &err);
	for (size_t i = 0; i < m->nv; i++)
		fct_prop_set(nz, i, -1);
}

static void uniform(struct fct_image *img, int w, int h, const uint8_t rgb[3])
{
	struct fct_err err;
	fct_image_alloc(img, w, h, 3, FCT_PIX_U8, &err);
	for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
		memcpy((uint8_t *)img->data + 3 * i, rgb, 3);
}

static int colour_of(const struct fct_mesh *m, size_t i, int c)
{
	static const char *const names[3] = { "red", "green", "blue" };
	return (int)fct_prop_get(fct_elem_find(&m->vertex, names[c]), i);
}

static void test_flat(void)
{
	struct fct_err err;
	struct fct_mesh view, out;
	square(&view, 40, 0.5);
	struct fct_fuse_view v;
	view_of(&v, &view);
	struct fct_range_image r;
	CHECK(fct_range_image_make(&r, &v, 1 << 20, &err) == 0);
	/* The "fused" surface: the same square, finer, with normals, and the
	 * two extra vertices. */
	square(&out, 50, 0.5);
	size_t behind = (size_t)fct_mesh_add_vertex(&out, 0.1, 0.1, 1.0, &err);
	size_t away = (size_t)fct_mesh_add_vertex(&out, -0.1, -0.1, 0.5, &err);
	add_normals(&out);
	fct_prop_set(fct_elem_find(&out.vertex, "nz"), away, 1);
	const uint8_t c0[3] = { 200, 100, 50 }, grey[3] = { 128, 128, 128 };
	struct fct_viewcolor_params p = { 0.03, FCT_FUSE_INCIDENCE, 4 };
	for (int size = 64; size >= 4; size -= 60) {
		struct fct_image img;
		uniform(&img, size, size, c0);
		struct fct_viewcolor acc;
		CHECK(fct_viewcolor_init(&acc, out.nv, &err) == 0);
		size_t seen = 0;
		CHECK(fct_viewcolor_add(&acc, &out, &r, &img, &p, &seen, &err) == 0);
		struct fct_viewcolor_stats st;
		CHECK(fct_viewcolor_write(&acc, &out, grey, &st, &err) == 0);
		CHECK_INT(st.colored, seen);
		CHECK_INT(st.colored + st.unseen, out.nv);
		/* Seen: exactly c0; out of the picture (more than a pixel),
		 * behind the square or facing away: grey. */
		size_t wrong = 0, inside = 0;
		for (size_t i = 0; i < out.nv; i++) {
			const double *x = &out.xyz[3 * i];
			double u = 32 * x[0] / x[2] + 31.5, w = 32 * x[1] / x[2] + 31.5;
			int in = u >= 0 && u <= 63 && w >= 0 && w <= 63 && i != behind && i != away;
			int outside = u < -1 || u > 64 || w < -1 || w > 64 || i == behind || i == away;
			inside += (size_t)in;
			for (int c = 0; c < 3; c++) {
				int got = colour_of(&out, i, c);
				if ((in && got != c0[c]) || (outside && got != 128) ||
				    (!in && !outside && got != c0[c] && got != 128))
					wrong++;
			}
		}
		CHECK_MSG(wrong == 0, "image %dx%d: %zu wrong channels", size, size, wrong);
		/* 50 x 50 cells over [-1,1]: x in [-0.4968, 0.4968] projects into
		 * the picture, x = -0.52 + 0.04 k for k = 1..25: 25 x 25 vertices. */
		CHECK_INT(inside, 25 * 25);
		CHECK(st.colored >= inside);
		CHECK(st.unseen >= 2);
		fct_viewcolor_free(&acc);
		fct_image_free(&img);
	}
	fct_range_image_free(&r);
	fct_mesh_free(&view);
	fct_mesh_free(&out);
}

/* Two views of the plane, the second 0.5 m to the right, images of two
 * colours: constant weights average them; depth2 weights favour the nearer. */
static void test_two(void)
{
	struct fct_err err;
	struct fct_mesh view, out;
	square(&view, 40, 0.5);
	struct fct_fuse_view v1;
	view_of(&v1, &view);
	struct fct_fuse_view v2 = v1;
	v2.pose[3] = 0.1;
	v2.pose[11] = -0.5;      /* twice as far */
	struct fct_range_image r1, r2;
	CHECK(fct_range_image_make(&r1, &v1, 1 << 20, &err) == 0);
	CHECK(fct_range_image_make(&r2, &v2, 1 << 20, &err) == 0);
	fct_mesh_init(&out);
	fct_mesh_add_vertex(&out, 0.05, 0.02, 0.5, &err);
	add_normals(&out);
	const uint8_t a[3] = { 200, 100, 50 }, b[3] = { 100, 50, 0 }, grey[3] = { 128, 128, 128 };
	struct fct_image ia, ib;
	uniform(&ia, 64, 64, a);
	uniform(&ib, 64, 64, b);
	for (int wt = 0; wt < 2; wt++) {
		struct fct_viewcolor_params p = { 0.03, wt ? FCT_FUSE_DEPTH2 : FCT_FUSE_CONSTANT, 0 };
		struct fct_viewcolor acc;
		CHECK(fct_viewcolor_init(&acc, 1, &err) == 0);
		CHECK(fct_viewcolor_add(&acc, &out, &r1, &ia, &p, NULL, &err) == 0);
		CHECK(fct_viewcolor_add(&acc, &out, &r2, &ib, &p, NULL, &err) == 0);
		struct fct_viewcolor_stats st;
		CHECK(fct_viewcolor_write(&acc, &out, grey, &st, &err) == 0);
		CHECK_NEAR(st.views_per_vertex, 2, 0);
		/* depth2: weights 1/0.25 and 1/1 -> (4 a + b) / 5. */
		for (int c = 0; c < 3; c++)
			CHECK_INT(colour_of(&out, 0, c), wt ? (4 * a[c] + b[c]) / 5 : (a[c] + b[c]) / 2);
		fct_viewcolor_free(&acc);
	}
	fct_image_free(&ia);
	fct_image_free(&ib);
	fct_range_image_free(&r1);
	fct_range_image_free(&r2);
	fct_mesh_free(&view);
	fct_mesh_free(&out);
}

/* The noise of three vertices of the plane z = 0.5: A seen by both views of
 * test_two (the first a depth image of the plane, the second the square's
 * mesh twice as far), B beyond the first view's picture and seen by the
 * second only, C behind the plane (unseen).  Sensor noise 0.01 z: s = 5 mm
 * and 10 mm; at 2 cm voxels the weights 1 / (1 + (2 s / vox)^2) are 0.8 and
 * 0.5.  A: weighted rms sqrt((0.8 * 25e-6 + 0.5 * 1e-4) / 1.3) = 7.338 mm,
 * independent sqrt(0.64 * 25e-6 + 0.25 * 1e-4) / 1.3 = 4.925 mm, their
 * geometric mean 6.012 mm; B: 10 mm both ways.  The median of the two seen
 * (the upper one, fct_select_kth's n / 2) is B's: scaled to a level of 2 mm,
 * A has 1.2024 mm, B and C 2 mm; with a floor, below. */
static void test_noise(void)
{
	struct fct_err err;
	struct fct_mesh view, out;
	square(&view, 40, 0.5);
	struct fct_fuse_view v2;
	view_of(&v2, &view);
	v2.pose[3] = 0.1;
	v2.pose[11] = -0.5;
	struct fct_image depth;
	CHECK(fct_image_alloc(&depth, 64, 64, 1, FCT_PIX_F32, &err) == 0);
	for (size_t i = 0; i < 64 * 64; i++)
		((float *)depth.data)[i] = 0.5f;
	struct fct_depth_params dp;
	fct_depth_params_default(&dp);
	const double identity[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
	struct fct_range_image r1, r2;
	CHECK(fct_range_image_depth(&r1, &depth, &v2.cam, &dp, identity, &err) == 0);
	CHECK(r1.view.mesh == NULL && r1.width == 64 && r1.height == 64);
	CHECK_NEAR(r1.range[64 * 10 + 20], 0.5, 1e-7);
	CHECK(fct_range_image_make(&r2, &v2, 1 << 20, &err) == 0);
	fct_mesh_init(&out);
	fct_mesh_add_vertex(&out, 0.05, 0.02, 0.5, &err);      /* A */
	fct_mesh_add_vertex(&out, 0.8, 0.0, 0.5, &err);        /* B */
	fct_mesh_add_vertex(&out, 0.05, 0.02, 1.5, &err);      /* C */
	add_normals(&out);
	struct fct_noise nz;
	CHECK(fct_noise_parse(&nz, "poly:0,0.01,0", &err) == 0);
	struct fct_viewcolor_params p = { 0.03, FCT_FUSE_CONSTANT, 0 };
	for (int threads = 1; threads <= 2; threads++) {
		struct fct_viewnoise acc;
		CHECK(fct_viewnoise_init(&acc, out.nv, &err) == 0);
		size_t seen1, seen2, seen;
		CHECK(fct_viewnoise_add(&acc, &out, &r1, &nz, 0.02, &p, threads, &seen1, &err) == 0);
		CHECK(fct_viewnoise_add(&acc, &out, &r2, &nz, 0.02, &p, threads, &seen2, &err) == 0);
		CHECK_INT(seen1, 1);
		CHECK_INT(seen2, 2);
		CHECK(fct_viewnoise_write(&acc, &out, 0.002, 0, &seen, &err) == 0);
		CHECK_INT(seen, 2);
		const struct fct_prop *sg = fct_elem_find(&out.vertex, "sigma");
		CHECK(sg && sg->type == FCT_FLOAT32);
		double a = sqrt(sqrt(7e-5 / 1.3) * sqrt(4.1e-5) / 1.3);
		CHECK_NEAR(fct_prop_get(sg, 0), 0.002 * a / 0.01, 1e-9);
		CHECK_NEAR(fct_prop_get(sg, 0), 1.2024e-3, 1e-6);
		CHECK_NEAR(fct_prop_get(sg, 1), 0.002, 1e-9);
		CHECK_NEAR(fct_prop_get(sg, 2), 0.002, 1e-9);
		/* A floor of 1 mm in quadrature: k = sqrt(4e-6 - 1e-6) / 0.01 keeps
		 * B, the median, at 2 mm; A sqrt((k a)^2 + 1e-6) = 1.4437 mm. */
		CHECK(fct_viewnoise_write(&acc, &out, 0.002, 0.001, NULL, &err) == 0);
		sg = fct_elem_find(&out.vertex, "sigma");
		double k = sqrt(3e-6) / 0.01;
		CHECK_NEAR(fct_prop_get(sg, 0), sqrt(k * a * k * a + 1e-6), 1e-9);
		CHECK_NEAR(fct_prop_get(sg, 0), 1.4437e-3, 1e-6);
		CHECK_NEAR(fct_prop_get(sg, 1), 0.002, 1e-9);
		CHECK_NEAR(fct_prop_get(sg, 2), 0.002, 1e-9);
		/* A level under the floor: one figure, the level. */
		CHECK(fct_viewnoise_write(&acc, &out, 0.002, 0.003, NULL, &err) == 0);
		sg = fct_elem_find(&out.vertex, "sigma");
		for (size_t i = 0; i < 3; i++)
			CHECK_NEAR(fct_prop_get(sg, i), 0.002, 1e-9);
		fct_viewnoise_free(&acc);
	}
	/* No view with a noise model saw anything: nothing written. */
	struct fct_viewnoise none;
	CHECK(fct_viewnoise_init(&none, out.nv, &err) == 0);
	CHECK(fct_viewnoise_write(&none, &out, 0.002, 0, NULL, &err) == -1);
	fct_viewnoise_free(&none);
	fct_image_free(&depth);
	fct_range_image_free(&r1);
	fct_range_image_free(&r2);
	fct_mesh_free(&view);
	fct_mesh_free(&out);
}

/* mkscene's room, three views at 160 x 120, fused at 2 cm: the mean absolute
 * colour error of the fused vertices against the scene's colour at their
 * nearest point on the true surface. */
static void test_room(void)
{
	struct fct_err err;
	struct fct_scene s;
	CHECK(fct_scene_build(&s, "room", &err) == 0);
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, 160, 120, 131.25, 131.25, 79.5, 59.5, 0, 0 };
	enum { NV = 3 };
	double vox = 0.02, band = 3 * vox;
	struct fct_mesh meshes[NV];
	struct fct_image images[NV];
	struct fct_fuse_view views[NV];
	struct fct_voxgrid *g = fct_voxgrid_new(vox, 0, &err);
	struct fct_fuse_params fp = { band, FCT_FUSE_CONSTANT, 0, 0, { 0 }, { 0 }, 1 };
	for (int i = 0; i < NV; i++) {
		double pose[12];
		fct_scene_view_pose(&s, i, 4, pose);
		struct fct_render rd;
		CHECK(fct_scene_render(&s, &cam, pose, &rd, &err) == 0);
		struct fct_image depth;
		fct_image_alloc(&depth, cam.width, cam.height, 1, FCT_PIX_F32, &err);
		fct_image_alloc(&images[i], cam.width, cam.height, 3, FCT_PIX_U8, &err);
		size_t np = (size_t)cam.width * (size_t)cam.height;
		for (size_t k = 0; k < np; k++)
			((float *)depth.data)[k] = (float)rd.depth[k];
		memcpy(images[i].data, rd.rgb, 3 * np);
		fct_render_free(&rd);
		struct fct_depth_params dp;
		fct_depth_params_default(&dp);
		dp.texcoords = 0;
		CHECK(fct_depth_mesh(&meshes[i], &depth, &cam, &dp, NULL, &err) == 0);
		fct_image_free(&depth);
		for (size_t k = 0; k < meshes[i].nv; k++)
			fct_pose_apply(pose, &meshes[i].xyz[3 * k], &meshes[i].xyz[3 * k]);
		views[i] = (struct fct_fuse_view){ .mesh = &meshes[i], .cam = cam };
		memcpy(views[i].pose, pose, sizeof pose);
		CHECK(fct_fuse_view(g, &views[i], &fp, NULL, &err) == 0);
	}
	struct fct_mesh out;
	CHECK(fct_mcubes(&out, g, 0, NULL, NULL, &err) == 0);
	CHECK(out.nv > 10000);
	/* Truth: the scene's colour at the vertex's nearest point on the scene.
	 * The reference: the same views and sampler colouring those nearest
	 * points themselves (with the fused normals), what the images allow
	 * with perfect geometry -- 160 x 120 pixels leave the far floor's
	 * 25 cm checker a blur. */
	struct fct_mesh tru;
	CHECK(fct_mesh_copy(&tru, &out, &err) == 0);
	uint8_t *truth = malloc(3 * out.nv);
	for (size_t i = 0; i < out.nv; i++) {
		struct fct_bvh_hit hit;
		fct_bvh_closest(&s.bvh, &out.xyz[3 * i], INFINITY, &hit);
		fct_scene_color(&s, hit.id, hit.q, &truth[3 * i]);
		memcpy(&tru.xyz[3 * i], hit.q, sizeof hit.q);
	}
	struct fct_viewcolor acc, acct;
	CHECK(fct_viewcolor_init(&acc, out.nv, &err) == 0);
	CHECK(fct_viewcolor_init(&acct, out.nv, &err) == 0);
	struct fct_viewcolor_params p = { band, FCT_FUSE_INCIDENCE, 4 };
	for (int i = 0; i < NV; i++) {
		struct fct_range_image r;
		CHECK(fct_range_image_make(&r, &views[i], 1 << 20, &err) == 0);
		CHECK(fct_viewcolor_add(&acc, &out, &r, &images[i], &p, NULL, &err) == 0);
		CHECK(fct_viewcolor_add(&acct, &tru, &r, &images[i], &p, NULL, &err) == 0);
		fct_range_image_free(&r);
	}
	const uint8_t grey[3] = { 128, 128, 128 };
	struct fct_viewcolor_stats st, stt;
	CHECK(fct_viewcolor_write(&acc, &out, grey, &st, &err) == 0);
	CHECK(fct_viewcolor_write(&acct, &tru, grey, &stt, &err) == 0);
	double e = 0, et = 0, ec = 0, mean[3] = { 0, 0, 0 };
	size_t n = 0, big = 0;
	for (size_t i = 0; i < out.nv; i++)
		for (int c = 0; c < 3; c++)
			mean[c] += truth[3 * i + c] / (double)out.nv;
	for (size_t i = 0; i < out.nv; i++) {
		double ei = 0, eti = 0;
		for (int c = 0; c < 3; c++) {
			double t = truth[3 * i + c];
			ei += fabs(colour_of(&out, i, c) - t) / 3;
			eti += fabs(colour_of(&tru, i, c) - t) / 3;
			ec += fabs(mean[c] - t) / 3;
		}
		e += ei, et += eti;
		big += ei > 20;
		n++;
	}
	e /= (double)n, et /= (double)n, ec /= (double)n;
	printf("room: %zu vertices, %zu unseen (%zu at the true points), %.2f views each; mean colour "
	       "error %.2f levels, %.2f at the true points, %.2f for the mean colour; %.2f%% over 20\n",
	       out.nv, st.unseen, stt.unseen, st.views_per_vertex, e, et, ec,
	       100.0 * (double)big / (double)n);
	/* Nearly every fused vertex is seen by a view: the unseen are a few at
	 * the torn borders (occlusion edges, where the surface runs on behind
	 * what was seen, or curls back there), which get the fallback. */
	CHECK_MSG(st.unseen < out.nv / 200, "%zu of %zu vertices unseen", st.unseen, out.nv);
	/* The fused geometry (about half a voxel, 1 cm, from the truth) costs
	 * little over perfect geometry, and both are far better than the best
	 * single colour. */
	CHECK_MSG(e < et + 1.5, "mean colour error %.2f vs %.2f at the true points", e, et);
	CHECK_MSG(e < ec / 4, "mean colour error %.2f vs %.2f for the mean colour", e, ec);
	free(truth);
	fct_viewcolor_free(&acc);
	fct_viewcolor_free(&acct);
	fct_mesh_free(&tru);
	fct_mesh_free(&out);
	fct_voxgrid_free(g);
	for (int i = 0; i < NV; i++) {
		fct_mesh_free(&meshes[i]);
		fct_image_free(&images[i]);
	}
	fct_scene_free(&s);
}

int main(void)
{
	test_flat();
	test_two();
	test_noise();
	test_room();
	CHECK_DONE();
}

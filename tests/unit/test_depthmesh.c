/* test_depthmesh - depth images to meshes with a noise model (depthmesh.h):
 * the sigma property, and the jump test's noise allowance judged against
 * mkscene's truth: under structured Kinect noise the room stays in few
 * pieces, and no face spans a true occlusion. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "check.h"
#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "noisy_view.h"
#include "scene/scene.h"

/* What a mesh of a view makes of the scene. */
struct figures {
	size_t faces;
	long components;
	size_t border;
	size_t bridges;      /* faces whose corners' true points span a gap */
	double worst_ratio;  /* of a bridge's gap to the default test's limit there */
	double near_gap;     /* the largest gap a bridge spans nearer than 4.5 m */
};

/* A face bridges a true depth jump when the triangle of its corners' true
 * points has its centroid more than 2 cm off the scene's surface.  The
 * true point of a pixel is the depth the sensor sampled before its noise
 * (the truth along the jittered ray, `sampled`) put on the pixel's ray:
 * where jitter made a pixel near an edge sample the surface behind, its
 * data belong there, and the mesh rightly joins it to that surface.  Such
 * a point is off the surface by at most the jitter's lateral shift (under
 * 1 cm at 4 deviations and 5 m); on one surface, or across a crease, the
 * centroid is within that and a third of a pixel footprint of it; across
 * an occlusion gap g, about g / 3 away.  A bridge's gap is measured
 * against the default test with the kinect model (limit the footprint
 * term, allow the noise term of gridmesh.h), edge by edge. */
static struct figures measure(const struct fct_mesh *m, const struct fct_scene *s,
                              const struct fct_camera *cam, const double pose[12], const double *sampled,
                              const struct fct_noise *kinect)
{
	struct figures f;
	memset(&f, 0, sizeof f);
	struct fct_err err;
	struct fct_adj a;
	if (fct_adj_build(&a, m, &err))
		abort();
	uint32_t *label = malloc((m->nf ? m->nf : 1) * sizeof *label);
	if (!label)
		abort();
	f.components = fct_adj_components(&a, label, &err);
	f.border = a.nborder;
	f.faces = m->nf;
	free(label);
	fct_adj_free(&a);
	const float *su = fct_elem_find(&m->vertex, "s")->data, *sv = fct_elem_find(&m->vertex, "t")->data;
	double footprint = FCT_DEFAULT_MAX_JUMP / cam->fx, k = M_SQRT2 * FCT_DEFAULT_NOISE_JUMP;
	for (size_t t = 0; t < m->nf; t++) {
		double c[3] = {0, 0, 0}, z[3];
		long px[3][2];
		for (int i = 0; i < 3; i++) {
			uint32_t v = m->fvert[3 * t + i];
			px[i][0] = lround(su[v] * cam->width - 0.5), px[i][1] = lround((1 - sv[v]) * cam->height - 0.5);
			double ray[3], p[3];
			fct_camera_ray(cam, (double)px[i][0], (double)px[i][1], ray);
			z[i] = sampled[(size_t)px[i][1] * (size_t)cam->width + (size_t)px[i][0]];
			for (int j = 0; j < 3; j++)
				p[j] = z[i] * ray[j];
			fct_pose_apply(pose, p, p);
			for (int j = 0; j < 3; j++)
				c[j] += p[j] / 3;
		}
		struct fct_bvh_hit hit;
		if (!fct_bvh_closest(&s->bvh, c, INFINITY, &hit) || hit.d2 <= 0.02 * 0.02)
			continue;
		f.bridges++;
		for (int i = 0; i < 3; i++) {
			int j = (i + 1) % 3;
			double lo = fmin(z[i], z[j]), hi = fmax(z[i], z[j]);
			double steps = hypot((double)(px[i][0] - px[j][0]), (double)(px[i][1] - px[j][1]));
			double limit = footprint * steps * lo + k * fct_noise_sigma(kinect, hi);
			f.worst_ratio = fmax(f.worst_ratio, (hi - lo) / limit);
			if (hi < 4.5)
				f.near_gap = fmax(f.near_gap, hi - lo);
		}
	}
	return f;
}

static struct figures mesh_and_measure(const struct fct_scene *s, const struct fct_camera *cam,
                                       const double pose[12], const double *sampled,
                                       const struct fct_image *img, const struct fct_noise *model,
                                       double max_jump)
{
	struct fct_depth_params p;
	fct_depth_params_default(&p);
	if (model)
		p.noise = *model;
	if (max_jump > 0)
		p.grid.max_jump = max_jump;
	struct fct_mesh m;
	struct fct_err err;
	if (fct_depth_mesh(&m, img, cam, &p, NULL, &err))
		abort();
	struct fct_noise kinect;
	fct_noise_kinect(&kinect);
	struct figures f = measure(&m, s, cam, pose, sampled, &kinect);
	if (getenv("FCT_TEST_VERBOSE"))
		fprintf(stderr, "%s j %g: faces %zu components %ld border %zu bridges %zu, worst gap %.2f of "
		        "the limit, %.3f m nearer than 4.5 m\n", model ? "noise model" : "no model",
		        p.grid.max_jump, f.faces, f.components, f.border, f.bridges, f.worst_ratio, f.near_gap);
	fct_mesh_free(&m);
	return f;
}

/* Four views of mkscene's room (640x480, 525 px) with the structured
 * Kinect noise (kinect defaults, jitter 0.5 px), meshed at the default -j:
 *
 * - without a model (the test before) the noise tears the room into 48-104
 *   pieces with 27-35k border edges; with it, the room is in at most 13
 *   pieces (5, 13, 4, 8) with at most the border edges of the same views
 *   without noise (4.0-5.9k against 4.4-6.4k): noise no longer cuts;
 * - no face spans a true occlusion beyond the sensor's resolution: the
 *   faces that join the two sides of a true gap (47, 3, 11, 18 of 610k)
 *   span at most 1.39 times the test's limit there (what two levels of
 *   noise the wrong way make of a gap), and nearer than 4.5 m (the
 *   Kinect's range) at most 0.19 m, where -j 40 (planarize's setting so
 *   far) bridges 372, 29, 95, 114 faces, gaps up to 2.66 times the limit
 *   and 0.32 m. */
static void test_jump_allowance(void)
{
	struct fct_scene s;
	struct fct_err err;
	if (fct_scene_build(&s, "room", &err))
		abort();
	struct fct_camera cam;
	memset(&cam, 0, sizeof cam);
	cam.kind = FCT_CAMERA_PINHOLE;
	cam.width = 640, cam.height = 480;
	cam.fx = cam.fy = 525, cam.cx = 319.5, cam.cy = 239.5;
	struct fct_noise kinect, none;
	fct_noise_kinect(&kinect);
	CHECK_INT(fct_noise_parse(&none, "none", &err), 0);
	size_t bridges = 0, bridges40 = 0;
	for (int view = 0; view < 4; view++) {
		double pose[12], *sampled, *exact;
		struct fct_image img, clean;
		fct_scene_view_pose(&s, view, 4, pose);
		noisy_view(&s, &cam, pose, &kinect, 0.5, &sampled, &img);
		noisy_view(&s, &cam, pose, &none, 0.5, &exact, &clean);
		struct figures before = mesh_and_measure(&s, &cam, pose, sampled, &img, NULL, 0);
		struct figures after = mesh_and_measure(&s, &cam, pose, sampled, &img, &kinect, 0);
		struct figures j40 = mesh_and_measure(&s, &cam, pose, sampled, &img, NULL, 40);
		struct figures truth = mesh_and_measure(&s, &cam, pose, exact, &clean, NULL, 0);
		CHECK_MSG(before.components >= 40 && before.border > 4 * truth.border,
		          "view %d before: %ld pieces, %zu border edges", view, before.components, before.border);
		CHECK_MSG(after.components <= 15 && after.border <= truth.border,
		          "view %d: %ld pieces, %zu border edges (without noise %zu)", view, after.components,
		          after.border, truth.border);
		CHECK_MSG(after.worst_ratio < 1.5 && after.near_gap < 0.2,
		          "view %d: a face spans %.2f of the limit, %.3f m", view, after.worst_ratio, after.near_gap);
		CHECK_INT(truth.bridges, 0);
		bridges += after.bridges, bridges40 += j40.bridges;
		free(sampled);
		free(exact);
		fct_image_free(&img);
		fct_image_free(&clean);
	}
	CHECK_MSG(bridges * 4 < bridges40, "%zu faces across gaps, -j 40 %zu", bridges, bridges40);
	fct_scene_free(&s);
}

/* The same mesh, byte for byte: positions, faces and every float vertex
 * property (an empty mesh's arrays may be NULL, which memcmp must not get). */
static int same_mesh(const struct fct_mesh *a, const struct fct_mesh *b)
{
	if (a->nv != b->nv || a->nf != b->nf || a->vertex.nprops != b->vertex.nprops)
		return 0;
	if (a->nv && memcmp(a->xyz, b->xyz, 3 * a->nv * sizeof *a->xyz))
		return 0;
	if (a->nf && memcmp(a->fvert, b->fvert, 3 * a->nf * sizeof *a->fvert))
		return 0;
	for (size_t k = 0; a->nv && k < a->vertex.nprops; k++)
		if (memcmp(a->vertex.props[k].data, b->vertex.props[k].data, a->nv * sizeof(float)))
			return 0;
	return 1;
}

/* A 16-bit image's depths and sigmas are looked up by sample value where
 * the image has more pixels than values (depthmesh.c's sample tables), else
 * computed pixel by pixel: either way the mesh is the one of the float
 * image of the same values (computed pixel by pixel), with 65535 no data
 * as 0 is.  Images with tables (w x h above the largest value) and
 * without, 1 x N and odd widths, every step; the largest sample on the
 * last square. */
static void test_sample_tables(void)
{
	/* width, height, the smallest and largest sample of data */
	static const int size[][4] = { { 70, 50, 1000, 3000 }, { 71, 49, 1000, 3400 }, { 1, 40, 1, 30 },
	                               { 40, 1, 1, 30 }, { 3, 2, 1000, 2000 }, { 9, 7, 1000, 5000 } };
	struct fct_err err;
	uint32_t seed = 7;
	for (size_t n = 0; n < sizeof size / sizeof *size; n++) {
		int w = size[n][0], h = size[n][1];
		size_t np = (size_t)w * (size_t)h;
		uint16_t *u = malloc(np * sizeof *u);
		float *f = malloc(np * sizeof *f);
		if (!u || !f)
			abort();
		for (size_t i = 0; i < np; i++) {
			seed = seed * 1664525u + 1013904223u;
			unsigned v = (unsigned)size[n][2] + (seed >> 8) % (unsigned)(size[n][3] - size[n][2] + 1);
			if (seed % 13 == 0)
				v = 0;
			else if (seed % 17 == 0)
				v = 65535;
			else if (seed % 5 != 0 && i > 0)
				v = u[i - 1];   /* plateaus, as quantised sensors make */
			/* the largest sample on the last square: the eight-a-step
			 * search leaves the last pixel to its scalar tail */
			if (i + 2 >= np || (i + (size_t)w + 2 >= np && i + (size_t)w < np))
				v = (unsigned)size[n][3] + 7;
			u[i] = (uint16_t)v, f[i] = v == 65535 ? 0 : (float)v;
		}
		struct fct_image iu = { w, h, 1, FCT_PIX_U16, u }, ifl = { w, h, 1, FCT_PIX_F32, f };
		struct fct_camera cam = { FCT_CAMERA_PINHOLE, w, h, 50, 50, (w - 1) / 2.0, (h - 1) / 2.0, 0, 0 };
		for (int noisy = 0; noisy < 2; noisy++)
			for (int step = 1; step <= 3; step++) {
				struct fct_depth_params p;
				fct_depth_params_default(&p);
				p.step = step, p.scale_float = 1, p.grid.min_faces = noisy ? 3 : 0;
				if (noisy)
					fct_noise_kinect(&p.noise);
				struct fct_mesh a, b;
				CHECK_INT(fct_depth_mesh(&a, &iu, &cam, &p, NULL, &err), 0);
				CHECK_INT(fct_depth_mesh(&b, &ifl, &cam, &p, NULL, &err), 0);
				CHECK_MSG(same_mesh(&a, &b), "%dx%d step %d noise %d: 16-bit and float meshes differ",
				          w, h, step, noisy);
				CHECK_MSG(a.nf > 0 || np < 1000 || step > 1, "%dx%d: no faces", w, h);
				CHECK_INT(!!fct_elem_find(&a.vertex, "sigma"), noisy);
				fct_mesh_free(&a);
				fct_mesh_free(&b);
			}
		free(u);
		free(f);
	}
}

/* A view's mesh given its noise again from its vertices
 * (fct_mesh_noise_sigma) has the sigma dm2mesh gave it, in the camera's
 * frame and moved by a pose; without a camera a constant model gives its
 * figure and a model that grows with depth is refused. */
static void test_mesh_noise_sigma(void)
{
	enum { W = 64, H = 48 };
	static float depth[W * H];
	for (int y = 0; y < H; y++)
		for (int x = 0; x < W; x++)
			depth[y * W + x] = (float)(1.5 + 0.04 * x + 0.02 * y + 0.3 * sin(0.3 * x) * cos(0.2 * y));
	struct fct_image img = { W, H, 1, FCT_PIX_F32, depth };
	struct fct_camera cam = { FCT_CAMERA_PINHOLE, W, H, 60, 60, (W - 1) / 2.0, (H - 1) / 2.0, 0, 0 };
	struct fct_depth_params p;
	fct_depth_params_default(&p);
	fct_noise_kinect(&p.noise);
	p.noise.unit = 0.001;
	struct fct_mesh m;
	struct fct_err err;
	CHECK_INT(fct_depth_mesh(&m, &img, &cam, &p, NULL, &err), 0);
	CHECK(m.nv > 1000);
	const struct fct_prop *sg = fct_elem_find(&m.vertex, "sigma");
	CHECK(sg != NULL);
	float *want = malloc(m.nv * sizeof *want);
	if (!want)
		abort();
	for (size_t i = 0; i < m.nv; i++)
		want[i] = (float)fct_prop_get(sg, i);
	/* In the camera's frame, then moved by a pose (a turn about y and a
	 * shift) with its inverse given. */
	double pose[12] = { cos(0.5), 0, sin(0.5), 0.3, 0, 1, 0, -0.2, -sin(0.5), 0, cos(0.5), 2 }, inv[12];
	fct_pose_invert(pose, inv);
	for (int moved = 0; moved < 2; moved++) {
		if (moved)
			for (size_t i = 0; i < m.nv; i++) {
				double q[3];
				fct_pose_apply(pose, &m.xyz[3 * i], q);
				memcpy(&m.xyz[3 * i], q, sizeof q);
			}
		CHECK_INT(fct_mesh_noise_sigma(&m, &p.noise, &cam, moved ? inv : NULL, &err), 0);
		sg = fct_elem_find(&m.vertex, "sigma");
		double worst = 0;
		for (size_t i = 0; i < m.nv; i++)
			worst = fmax(worst, fabs(fct_prop_get(sg, i) / want[i] - 1));
		CHECK_MSG(worst < 1e-5, "moved %d: sigma %.3g off dm2mesh's", moved, worst);
	}
	/* No camera: poly A alone is one figure; kinect needs the depth. */
	struct fct_noise flat;
	CHECK_INT(fct_noise_parse(&flat, "poly:0.002,0,0", &err), 0);
	CHECK_INT(fct_noise_grows_with_depth(&flat), 0);
	CHECK_INT(fct_noise_grows_with_depth(&p.noise), 1);
	CHECK_INT(fct_mesh_noise_sigma(&m, &flat, NULL, NULL, &err), 0);
	sg = fct_elem_find(&m.vertex, "sigma");
	CHECK_NEAR(fct_prop_get(sg, 0), 0.002, 1e-9);
	CHECK_NEAR(fct_prop_get(sg, m.nv - 1), 0.002, 1e-9);
	CHECK_INT(fct_mesh_noise_sigma(&m, &p.noise, NULL, NULL, &err), -1);
	CHECK(strstr(err.msg, "grows with depth") != NULL);
	free(want);
	fct_mesh_free(&m);
}

int main(void)
{
	test_mesh_noise_sigma();
	test_sample_tables();
	test_jump_allowance();
	CHECK_DONE();
}

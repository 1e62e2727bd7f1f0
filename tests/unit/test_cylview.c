/* test_cylview.c - planar views of a cylindrical panorama (cylview.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "render/cylview.h"
#include "io/header.h"
#include "scene/scene.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static struct fct_camera cyl(int w, int h, double theta0)
{
	struct fct_camera c;
	memset(&c, 0, sizeof c);
	c.kind = FCT_CAMERA_CYLINDRICAL;
	c.width = w, c.height = h;
	c.f = w / (2 * M_PI);
	c.cy = (h - 1) / 2.0;
	c.theta0 = theta0;
	return c;
}

/* A view of 3 columns whose middle one looks between panorama columns 15
 * and 0 of a 16-column panorama: the seam, bilinear half and half. */
static void test_seam(void)
{
	struct fct_err err;
	struct fct_camera pc = cyl(16, 4, 0.25);
	struct fct_image img;
	CHECK(fct_image_alloc(&img, 16, 4, 1, FCT_PIX_U8, &err) == 0);
	uint8_t *d = img.data;
	for (int y = 0; y < 4; y++)
		for (int x = 0; x < 16; x++)
			d[y * 16 + x] = (uint8_t)(10 * x + 1);
	struct fct_cylview_params p;
	fct_cylview_params_default(&p);
	p.count = 2;
	p.width = 3, p.height = 3;
	/* theta at column 15.5, in degrees, plus theta0. */
	p.yaw0 = (0.25 + 2 * M_PI * 15.5 / 16) * 180 / M_PI;
	struct fct_cylview v[2];
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == 0);
	CHECK_NEAR(v[0].cam.cx, 1, 0);
	struct fct_image out;
	CHECK(fct_cylview_render(&img, &pc, &v[0], &out, &err) == 0);
	const uint8_t *o = out.data;
	/* Middle pixel of the middle row: (151 + 1) / 2. */
	CHECK_INT(o[1 * 3 + 1], 76);
	/* View 1 looks 180 degrees round: column 7.5, (71 + 81) / 2. */
	fct_image_free(&out);
	CHECK(fct_cylview_render(&img, &pc, &v[1], &out, &err) == 0);
	o = out.data;
	CHECK_INT(o[1 * 3 + 1], 76);
	fct_image_free(&out);

	/* A float panorama, a quarter of the way from column 15 to 0. */
	struct fct_image f;
	CHECK(fct_image_alloc(&f, 16, 4, 1, FCT_PIX_F32, &err) == 0);
	float *fd = f.data;
	for (int y = 0; y < 4; y++)
		for (int x = 0; x < 16; x++)
			fd[y * 16 + x] = (float)x;
	p.count = 1;
	p.yaw0 = (0.25 + 2 * M_PI * 15.25 / 16) * 180 / M_PI;
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == 0);
	CHECK(fct_cylview_render(&f, &pc, &v[0], &out, &err) == 0);
	CHECK_NEAR(((float *)out.data)[1 * 3 + 1], 0.75 * 15 + 0.25 * 0, 1e-4);
	fct_image_free(&out);
	fct_image_free(&f);

	/* The seam check: a 360-degree ramp that wraps passes; the same image
	 * claimed by a camera of another size fails. */
	CHECK(fct_cylview_check_panorama(&img, &pc, 1, NULL, &err) == -1);  /* 151 -> 1 jumps */
	for (int y = 0; y < 4; y++)
		for (int x = 0; x < 16; x++)
			d[y * 16 + x] = (uint8_t)(100 + 40 * sin(2 * M_PI * x / 16));
	CHECK(fct_cylview_check_panorama(&img, &pc, 1, NULL, &err) == 0);
	struct fct_camera wide = cyl(20, 4, 0);
	CHECK(fct_cylview_check_panorama(&img, &wide, 1, NULL, &err) == -1);
	CHECK(strstr(err.msg, "360") != NULL);
	fct_image_free(&img);

	/* Bad plans. */
	fct_cylview_params_default(&p);
	p.fov = 180;
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == -1);
	p.fov = 90, p.count = 0;
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == -1);

	/* Views the panorama cannot justify: at most 16 times its pixels (here
	 * 1024 x 256, so 4096 x 1024 passes and one column more does not); a
	 * field of view of 179.999 degrees asked 37351042 x 461 pixels. */
	struct fct_camera big = cyl(1024, 256, 0);
	struct fct_cylview bv[8];
	fct_cylview_params_default(&p);
	p.fov = 179.999;
	CHECK(fct_cylview_plan(&big, &p, bv, &err) == -1);
	CHECK(strstr(err.msg, "views of 37351042x461 pixels from a 1024x256 panorama: more than 16") != NULL);
	p.fov = 170;
	CHECK(fct_cylview_plan(&big, &p, bv, &err) == 0);
	p.fov = 90, p.width = 4096, p.height = 1024;
	CHECK(fct_cylview_plan(&big, &p, bv, &err) == 0);
	p.width = 4097;
	CHECK(fct_cylview_plan(&big, &p, bv, &err) == -1);
	/* a small panorama still gets views of up to 2^20 pixels */
	p.width = 1024;
	CHECK(fct_cylview_plan(&pc, &p, bv, &err) == 0);
	p.width = 1025;
	CHECK(fct_cylview_plan(&pc, &p, bv, &err) == -1);
}

/* The distance from the axis to the walls of a box room x in [-2, 2], z in
 * [-3, 3] (panorama frame) along azimuth th. */
static double wall_rho(double th)
{
	double s = sin(th), c = cos(th), r = HUGE_VAL;
	if (c > 1e-12)
		r = fmin(r, 3 / c);
	if (c < -1e-12)
		r = fmin(r, -3 / c);
	if (s > 1e-12)
		r = fmin(r, 2 / s);
	if (s < -1e-12)
		r = fmin(r, -2 / s);
	return r;
}

/* A straight 3-D edge, the ceiling (y = -1.4) meeting the wall z = 3, is a
 * curve in the panorama; in the planar view facing the wall it must be the
 * straight line v = cy + F (-1.4 / 3).  The panorama is the exact ceiling
 * coverage of each pixel (anti-aliased vertically), so the view's crossing
 * of the half level finds the edge to a fraction of a pixel. */
static void test_straight_edge(void)
{
	struct fct_err err;
	int W = 2048, H = 512;
	struct fct_camera pc = cyl(W, H, -M_PI);   /* the seam behind the camera */
	struct fct_image img;
	CHECK(fct_image_alloc(&img, W, H, 1, FCT_PIX_U8, &err) == 0);
	uint8_t *d = img.data;
	for (int x = 0; x < W; x++) {
		double th = pc.theta0 + 2 * M_PI * x / W;
		double ve = pc.cy + pc.f * (-1.4 / wall_rho(th));
		for (int y = 0; y < H; y++) {
			double c = ve - (y - 0.5);
			c = c < 0 ? 0 : c > 1 ? 1 : c;
			d[(size_t)y * W + x] = (uint8_t)lround(255 * c);
		}
	}
	struct fct_cylview_params p;
	fct_cylview_params_default(&p);
	struct fct_cylview v[8];
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == 0);
	struct fct_image out;
	CHECK(fct_cylview_render(&img, &pc, &v[0], &out, &err) == 0);
	const uint8_t *o = out.data;
	double F = v[0].cam.fx, want = v[0].cam.cy + F * (-1.4 / 3);
	/* Columns within 30 degrees of the axis: on the wall z = 3. */
	int x0 = (int)ceil(v[0].cam.cx - F * tan(30 * M_PI / 180));
	int x1 = (int)floor(v[0].cam.cx + F * tan(30 * M_PI / 180));
	double sx = 0, sy = 0, sxx = 0, sxy = 0, maxdev_true = 0;
	int n = 0;
	double *ys = malloc((size_t)(x1 - x0 + 1) * sizeof *ys);
	for (int x = x0; x <= x1; x++) {
		double yc = NAN;
		for (int y = 0; y + 1 < out.height; y++) {
			double a = o[(size_t)y * out.width + x], b = o[(size_t)(y + 1) * out.width + x];
			if (a >= 127.5 && b < 127.5) {
				yc = y + (a - 127.5) / (a - b);
				break;
			}
		}
		ys[x - x0] = yc;
		if (isnan(yc))
			continue;
		n++;
		sx += x, sy += yc, sxx += (double)x * x, sxy += x * yc;
		maxdev_true = fmax(maxdev_true, fabs(yc - want));
	}
	CHECK_INT(n, x1 - x0 + 1);
	double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), icpt = (sy - slope * sx) / n;
	double maxdev = 0;
	for (int x = x0; x <= x1; x++)
		if (!isnan(ys[x - x0]))
			maxdev = fmax(maxdev, fabs(ys[x - x0] - (icpt + slope * x)));
	free(ys);
	/* In the panorama the same edge bends by many pixels. */
	double bend = pc.f * 1.4 / 3 - pc.f * 1.4 / wall_rho(30 * M_PI / 180);
	CHECK_MSG(bend > 10, "the edge bends %g pixels in the panorama", bend);
	CHECK_MSG(maxdev < 0.5, "straight edge: max deviation from its fitted line %g px", maxdev);
	CHECK_MSG(maxdev_true < 0.5, "straight edge: max deviation from the true line %g px",
	          maxdev_true);
	fct_image_free(&out);
	fct_image_free(&img);
}

/* A planar view of mkscene's room panorama against a pinhole rendering of
 * the same scene from the same pose and intrinsics: PSNR over the view
 * without a 10% border. */
static void test_psnr(void)
{
	struct fct_err err;
	struct fct_scene s;
	CHECK(fct_scene_build(&s, "room", &err) == 0);
	double ppose[12];
	fct_scene_panorama_pose(&s, ppose);
	struct fct_camera pc = cyl(2048, 512, 0);
	struct fct_render pr;
	CHECK(fct_scene_render(&s, &pc, ppose, &pr, &err) == 0);
	struct fct_image img;
	CHECK(fct_image_alloc(&img, pc.width, pc.height, 3, FCT_PIX_U8, &err) == 0);
	memcpy(img.data, pr.rgb, (size_t)pc.width * pc.height * 3);
	struct fct_cylview_params p;
	fct_cylview_params_default(&p);
	p.yaw0 = 22.5;
	struct fct_cylview v[8];
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == 0);
	for (int k = 0; k < 8; k += 3) {
		struct fct_image out;
		CHECK(fct_cylview_render(&img, &pc, &v[k], &out, &err) == 0);
		double vpose[12];
		fct_cylview_pose(&v[k], ppose, vpose);
		struct fct_render vr;
		CHECK(fct_scene_render(&s, &v[k].cam, vpose, &vr, &err) == 0);
		int W = out.width, H = out.height, mx = W / 10, my = H / 10;
		double se = 0;
		size_t n = 0;
		const uint8_t *a = out.data;
		for (int y = my; y < H - my; y++)
			for (int x = mx; x < W - mx; x++)
				for (int c = 0; c < 3; c++) {
					size_t i = ((size_t)y * W + x) * 3 + c;
					double e = (double)a[i] - vr.rgb[i];
					se += e * e;
					n++;
				}
		double psnr = 10 * log10(255.0 * 255.0 / (se / n));
		CHECK_MSG(psnr > 30, "view %d: PSNR %.2f dB against the direct pinhole rendering", k,
		          psnr);
		fct_render_free(&vr);
		fct_image_free(&out);
	}
	fct_image_free(&img);
	fct_render_free(&pr);
	fct_scene_free(&s);
}

/* A simplified room, four walls of two triangles each (x in [-3, 3], y in
 * [-2, 2] world, z from 0 to 2.8, panorama at height 1.4): every face gets a
 * view whose image holds all its corners, after bisection; without it, some
 * wall triangles, wider than 90 degrees, fit in no view. */
static void test_assign(void)
{
	struct fct_err err;
	struct fct_mesh m;
	fct_mesh_init(&m);
	double cx[4] = {-3, 3, 3, -3}, cy[4] = {-2, -2, 2, 2};
	for (int i = 0; i < 4; i++) {
		CHECK(fct_mesh_add_vertex(&m, cx[i], cy[i], 0, &err) == 2 * i);
		CHECK(fct_mesh_add_vertex(&m, cx[i], cy[i], 2.8, &err) == 2 * i + 1);
	}
	for (uint32_t i = 0; i < 4; i++) {
		uint32_t a = 2 * i, b = 2 * ((i + 1) % 4);
		uint32_t t1[3] = {a, b, b + 1}, t2[3] = {a, b + 1, a + 1};
		CHECK(fct_mesh_add_face(&m, t1, 3, &err) >= 0);
		CHECK(fct_mesh_add_face(&m, t2, 3, &err) >= 0);
	}
	/* The panorama pose: camera z along world +x, y down, at (0, 0, 1.4). */
	double pose[12] = {0, 0, 1, 0, -1, 0, 0, 0, 0, -1, 0, 1.4};
	struct fct_camera pc = cyl(2048, 512, 0);
	struct fct_cylview_params p;
	fct_cylview_params_default(&p);
	struct fct_cylview v[8];
	CHECK(fct_cylview_plan(&pc, &p, v, &err) == 0);

	struct fct_mesh c;
	CHECK(fct_mesh_copy(&c, &m, &err) == 0);
	struct fct_cylview_assign_params ap = {0, 0};
	struct fct_cylview_assign_stats st;
	int32_t *vo;
	CHECK(fct_cylview_assign(&c, pose, v, 8, &ap, &vo, &st, &err) == 0);
	CHECK(st.uncovered > 0);
	CHECK_INT(st.splits, 0);
	free(vo);
	fct_mesh_free(&c);

	ap.split = 1;
	CHECK(fct_cylview_assign(&m, pose, v, 8, &ap, &vo, &st, &err) == 0);
	CHECK_INT(st.uncovered, 0);
	CHECK(st.splits > 0);
	CHECK_INT(st.faces, m.nf);
	double inv[12], area = 0;
	fct_pose_invert(pose, inv);
	size_t bad = 0;
	for (size_t f = 0; f < m.nf; f++) {
		const uint32_t *t = m.fvert + m.fstart[f];
		if (vo[f] < 0) {
			bad++;
			continue;
		}
		for (int j = 0; j < 3; j++) {
			double q[3], u, w, z;
			fct_pose_apply(inv, m.xyz + 3 * t[j], q);
			if (!fct_cylview_project(&v[vo[f]], q, &u, &w, &z) || u < 0 ||
			    u > v[vo[f]].cam.width - 1 || w < 0 || w > v[vo[f]].cam.height - 1)
				bad++;
		}
		const double *a = m.xyz + 3 * t[0], *b = m.xyz + 3 * t[1], *e = m.xyz + 3 * t[2];
		double u1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
		double u2[3] = {e[0] - a[0], e[1] - a[1], e[2] - a[2]};
		double n0 = u1[1] * u2[2] - u1[2] * u2[1], n1 = u1[2] * u2[0] - u1[0] * u2[2];
		double n2 = u1[0] * u2[1] - u1[1] * u2[0];
		area += 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
	}
	CHECK_INT(bad, 0);
	/* Bisection keeps the surface: the walls' area 2 (6 + 4) 2.8. */
	CHECK_NEAR(area, 2 * 10 * 2.8, 1e-9);

	/* Texture: PLY per face and OBJ per vertex agree on texture numbers. */
	char *names[8] = {"v0.png", "v1.png", "v2.png", "v3.png", "v4.png", "v5.png", "v6.png",
	                  "v7.png"};
	CHECK(fct_mesh_copy(&c, &m, &err) == 0);
	CHECK(fct_cylview_texture(&m, pose, v, 8, vo, names, 1, &err) == 0);
	CHECK(fct_elem_find(&m.face, "texcoord") != NULL);
	CHECK(fct_elem_find(&m.vertex, "s") == NULL);
	CHECK_INT(fct_header_texture_count(&m), st.views_used);
	CHECK(fct_cylview_texture(&c, pose, v, 8, vo, names, 0, &err) == 0);
	CHECK(c.nv > m.nv);
	const struct fct_prop *tc = fct_elem_find(&m.face, "texcoord");
	const struct fct_prop *s = fct_elem_find(&c.vertex, "s"), *t = fct_elem_find(&c.vertex, "t");
	double maxd = 0;
	for (size_t f = 0; f < m.nf; f++)
		for (uint32_t i = m.fstart[f]; i < m.fstart[f + 1]; i++) {
			uint32_t cv = c.fvert[i];
			maxd = fmax(maxd, fabs(((float *)tc->data)[2 * i] - fct_prop_get(s, cv)));
			maxd = fmax(maxd, fabs(((float *)tc->data)[2 * i + 1] - fct_prop_get(t, cv)));
			CHECK(fct_prop_get(s, cv) >= 0 && fct_prop_get(s, cv) <= 1);
		}
	CHECK_NEAR(maxd, 0, 0);
	free(vo);
	fct_mesh_free(&c);
	fct_mesh_free(&m);
}

int main(void)
{
	test_seam();
	test_straight_edge();
	test_psnr();
	test_assign();
	CHECK_DONE();
}

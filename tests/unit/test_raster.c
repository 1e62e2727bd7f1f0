/* test_raster.c - the rasteriser against hand-computed answers: exact
 * pixel coverage of squares split along their diagonal (no gaps, no double
 * hits), the z-buffer whatever the drawing order, perspective-correct
 * barycentrics on a slanted triangle, near-plane clipping, line coverage,
 * colour maps, texture lookups, the font and the fitted view. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "render/raster.h"

/* An identity view: camera frame = world, focal f, principal point (cx, cy). */
static struct fct_view ident(int w, int h, double f, double cx, double cy)
{
	struct fct_view v;
	memset(&v, 0, sizeof v);
	v.R[0] = v.R[4] = v.R[8] = 1;
	v.fx = v.fy = f;
	v.cx = cx, v.cy = cy;
	v.width = w, v.height = h;
	v.near = 0.01;
	return v;
}

static size_t count_id(const struct fct_raster *r, uint32_t id)
{
	size_t n = 0;
	for (size_t i = 0; i < (size_t)r->width * (size_t)r->height; i++)
		n += r->id[i] == id;
	return n;
}

/* A square with corners on pixel centres, split into two triangles: the
 * pixel centres inside it are covered exactly once, those on its diagonal
 * by one triangle only, and of its border only two sides (the tie rule
 * makes coverage half-open, so squares side by side tile the plane). */
static void test_coverage(void)
{
	struct fct_err err;
	struct fct_raster r;
	CHECK(fct_raster_init(&r, 32, 32, &err) == 0);
	struct fct_view v = ident(32, 32, 1, 0, 0);
	/* At depth 1 with f = 1 and centre 0 a camera point (x, y, 1) is pixel (x, y). */
	double a[3] = {4, 4, 1}, b[3] = {14, 4, 1}, c[3] = {14, 14, 1}, d[3] = {4, 14, 1};
	long n1 = fct_raster_triangle(&r, &v, a, b, c, 1);
	long n2 = fct_raster_triangle(&r, &v, a, c, d, 2);
	/* 10 x 10 centres of the half-open square, each written once (the
	 * second triangle is at equal depth and could not take the first's). */
	CHECK_INT(count_id(&r, 1) + count_id(&r, 2), 100);
	CHECK_INT(n1 + n2, 100);
	/* The diagonal's centres went to one triangle: 55 + 45 one way or the other. */
	CHECK((count_id(&r, 1) == 55 && count_id(&r, 2) == 45) ||
	      (count_id(&r, 1) == 45 && count_id(&r, 2) == 55));
	/* Two squares sharing an edge (x = 14): again no pixel twice, none missed. */
	double e[3] = {24, 4, 1}, f[3] = {24, 14, 1};
	fct_raster_free(&r);
	CHECK(fct_raster_init(&r, 32, 32, &err) == 0);
	long n = fct_raster_triangle(&r, &v, a, b, c, 1) + fct_raster_triangle(&r, &v, a, c, d, 1) +
	         fct_raster_triangle(&r, &v, b, e, f, 2) + fct_raster_triangle(&r, &v, b, f, c, 2);
	CHECK_INT(n, 20 * 10);
	CHECK_INT(count_id(&r, 1) + count_id(&r, 2), 20 * 10);
	/* The shared column x = 14 belongs to one square only. */
	CHECK_INT(count_id(&r, 1), 100);
	/* A square with corners half-way between centres: exactly its pixels. */
	fct_raster_free(&r);
	CHECK(fct_raster_init(&r, 32, 32, &err) == 0);
	double g[3] = {2.5, 2.5, 1}, h[3] = {9.5, 2.5, 1}, k[3] = {9.5, 7.5, 1}, l[3] = {2.5, 7.5, 1};
	fct_raster_triangle(&r, &v, g, h, k, 3);
	fct_raster_triangle(&r, &v, g, k, l, 3);
	CHECK_INT(count_id(&r, 3), 7 * 5);
	CHECK_INT(r.id[5 * 32 + 3], 3);
	CHECK_INT(r.id[2 * 32 + 3], FCT_RASTER_EMPTY);
	/* Degenerate and non-finite triangles draw nothing. */
	double nan3[3] = {NAN, 1, 1};
	CHECK_INT(fct_raster_triangle(&r, &v, a, b, a, 4), 0);
	CHECK_INT(fct_raster_triangle(&r, &v, a, b, nan3, 4), 0);
	fct_raster_free(&r);
}

/* The nearer of two overlapping triangles wins in either order; depth is
 * stored as 1/z. */
static void test_zbuffer(void)
{
	struct fct_err err;
	for (int order = 0; order < 2; order++) {
		struct fct_raster r;
		CHECK(fct_raster_init(&r, 20, 20, &err) == 0);
		struct fct_view v = ident(20, 20, 10, 10, 10);
		double n0[3] = {-0.8, -0.8, 2}, n1[3] = {0.8, -0.8, 2}, n2[3] = {0, 0.8, 2};
		double f0[3] = {-4, -4, 4}, f1[3] = {4, -4, 4}, f2[3] = {0, 4, 4};
		if (order == 0) {
			fct_raster_triangle(&r, &v, n0, n1, n2, 1);
			fct_raster_triangle(&r, &v, f0, f1, f2, 2);
		} else {
			fct_raster_triangle(&r, &v, f0, f1, f2, 2);
			fct_raster_triangle(&r, &v, n0, n1, n2, 1);
		}
		CHECK_INT(r.id[10 * 20 + 10], 1);
		CHECK_NEAR(r.w[10 * 20 + 10], 0.5, 1e-7);
		CHECK_INT(r.id[1 * 20 + 10], 2);       /* (10, 1): only the far one */
		CHECK_NEAR(r.w[1 * 20 + 10], 0.25, 1e-7);
		fct_raster_free(&r);
	}
}

/* A triangle slanted in depth: the barycentrics at a pixel are those of the
 * 3-D point its ray hits, not the screen-space ones. */
static void test_perspective(void)
{
	struct fct_err err;
	struct fct_raster r;
	CHECK(fct_raster_init(&r, 64, 64, &err) == 0);
	struct fct_view v = ident(64, 64, 20, 32, 32);
	double a[3] = {-1, -1, 1}, b[3] = {3, -1, 3}, c[3] = {-1, 3, 3};
	fct_raster_triangle(&r, &v, a, b, c, 7);
	/* Pixel (32, 32) looks along (0, 0, 1); the plane through a b c is
	 * z = 1 + (x + 1)/2 + (y + 1)/2, hit at z = 2: the point (0, 0, 2) =
	 * a + b1 (b - a) + b2 (c - a) with b1 = b2 = 1/4. */
	/* The corners are snapped to 1/256 pixel, which moves the answer by
	 * up to a few 1e-5 here. */
	size_t i = 32 * 64 + 32;
	CHECK_INT(r.id[i], 7);
	CHECK_NEAR(r.w[i], 0.5, 1e-4);
	CHECK_NEAR(r.b[2 * i], 0.25, 1e-4);
	CHECK_NEAR(r.b[2 * i + 1], 0.25, 1e-4);
	/* Screen-space interpolation would give other weights: the projected
	 * corners are (12, 12), (52.67, 25.33), (25.33, 52.67). */
	fct_raster_free(&r);
}

/* A triangle through the near plane: the part in front is drawn, with the
 * barycentrics of the original corners. */
static void test_clip(void)
{
	struct fct_err err;
	struct fct_raster r;
	CHECK(fct_raster_init(&r, 40, 40, &err) == 0);
	struct fct_view v = ident(40, 40, 10, 20, 20);
	v.near = 0.5;
	double a[3] = {-1, 0, -1}, b[3] = {1, 0, 3}, c[3] = {-1, 2, 3};
	long n = fct_raster_triangle(&r, &v, a, b, c, 5);
	CHECK(n > 0);
	/* The ray through pixel (20, 22) has direction (0, 0.2, 1). */
	size_t i = 22 * 40 + 20;
	CHECK_INT(r.id[i], 5);
	/* The plane: x = -1 + 2 b1, y = 2 b2, z = -1 + 4 b1 + 4 b2; on the ray
	 * x = 0, y = 0.2 z: b1 = 1/2, z = 1 + 4 b2, 2 b2 = 0.2 + 0.8 b2, b2 = 1/6. */
	CHECK_NEAR(r.b[2 * i], 0.5, 1e-4);           /* snapped corners, as above */
	CHECK_NEAR(r.b[2 * i + 1], 1.0 / 6, 1e-4);
	CHECK_NEAR(1 / r.w[i], 1 + 4.0 / 6, 1e-4);
	/* Entirely behind the eye: nothing. */
	double d[3] = {0, 0, -1}, e[3] = {1, 0, -2}, f[3] = {0, 1, -2};
	CHECK_INT(fct_raster_triangle(&r, &v, d, e, f, 6), 0);
	fct_raster_free(&r);
}

static void test_lines(void)
{
	struct fct_err err;
	struct fct_image img;
	static const unsigned char black[3] = {0, 0, 0}, white[3] = {255, 255, 255};
	CHECK(fct_image_alloc(&img, 20, 10, 3, FCT_PIX_U8, &err) == 0);
	fct_draw_rect(&img, 0, 0, 20, 10, white);
	/* A 1-pixel horizontal line through the centres of row 5, x 2 .. 12:
	 * full coverage on the row, none on the rows beside it. */
	fct_draw_line2d(&img, 2, 5, 12, 5, 1, black, 1);
	const unsigned char *p = img.data;
	CHECK_INT(p[3 * (5 * 20 + 7)], 0);
	CHECK_INT(p[3 * (4 * 20 + 7)], 255);
	CHECK_INT(p[3 * (6 * 20 + 7)], 255);
	/* Half-way between rows 2 and 3 (y = 2.5): half coverage on both. */
	fct_draw_line2d(&img, 2, 2.5, 12, 2.5, 1, black, 1);
	CHECK_INT(p[3 * (2 * 20 + 7)], 128);
	CHECK_INT(p[3 * (3 * 20 + 7)], 128);
	/* Depth test: a line behind a surface is hidden, one on it shows. */
	struct fct_raster r;
	CHECK(fct_raster_init(&r, 20, 20, &err) == 0);
	struct fct_view v = ident(20, 20, 10, 10, 10);
	double a[3] = {-5, -5, 2}, b[3] = {5, -5, 2}, c[3] = {0, 5, 2};
	fct_raster_triangle(&r, &v, a, b, c, 0);
	struct fct_image im2;
	CHECK(fct_image_alloc(&im2, 20, 20, 3, FCT_PIX_U8, &err) == 0);
	fct_draw_rect(&im2, 0, 0, 20, 20, white);
	double l0[3] = {-0.4, 0, 3}, l1[3] = {0.4, 0, 3};   /* behind: pixels 8.7 .. 11.3, row 10 */
	CHECK_INT(fct_draw_line3d(&im2, &r, &v, l0, l1, 1, black, 1), 0);
	double m0[3] = {-0.4, 0, 2}, m1[3] = {0.4, 0, 2};   /* on the surface: x 8 .. 12, row 10 */
	CHECK(fct_draw_line3d(&im2, &r, &v, m0, m1, 1, black, 1) > 0);
	CHECK_INT(((unsigned char *)im2.data)[3 * (10 * 20 + 10)], 0);
	fct_image_free(&im2);
	fct_raster_free(&r);
	fct_image_free(&img);
}

static void test_colours(void)
{
	unsigned char c[3];
	fct_cmap_color(FCT_CMAP_VIRIDIS, 0, c);
	CHECK(c[0] == 68 && c[1] == 1 && c[2] == 84);
	fct_cmap_color(FCT_CMAP_VIRIDIS, 1, c);
	CHECK(c[0] == 253 && c[1] == 231 && c[2] == 37);
	fct_cmap_color(FCT_CMAP_VIRIDIS, 0.5, c);
	CHECK(c[0] == 33 && c[1] == 145 && c[2] == 140);
	fct_cmap_color(FCT_CMAP_VIRIDIS, 2, c);      /* clamped */
	CHECK(c[0] == 253);
	fct_cmap_color(FCT_CMAP_GRAY, 0.5, c);
	CHECK(c[0] == 128 && c[1] == 128 && c[2] == 128);
	fct_cmap_color(FCT_CMAP_COOLWARM, 0, c);
	CHECK(c[0] == 59 && c[1] == 76 && c[2] == 192);
	enum fct_cmap m;
	CHECK(fct_cmap_parse("coolwarm", &m) == 0 && m == FCT_CMAP_COOLWARM);
	CHECK(fct_cmap_parse("jet", &m) == -1);
	/* The palette: the same colour for the same id, different neighbours. */
	unsigned char p0[3], p1[3], p0b[3];
	fct_patch_color(0, p0);
	fct_patch_color(1, p1);
	fct_patch_color(0, p0b);
	CHECK(!memcmp(p0, p0b, 3) && memcmp(p0, p1, 3));
	fct_patch_color(-1, p0);
	CHECK(p0[0] == 200 && p0[1] == 200 && p0[2] == 200);
}

static void test_texture(void)
{
	struct fct_err err;
	struct fct_image t;
	CHECK(fct_image_alloc(&t, 2, 2, 3, FCT_PIX_U8, &err) == 0);
	unsigned char *d = t.data;
	/* Top row (t high): 0 and 100; bottom row: 200 and 40 (red channel). */
	d[0] = 0, d[3] = 100, d[6] = 200, d[9] = 40;
	double rgb[3];
	fct_texture_sample(&t, 0.25, 0.75, rgb);    /* the top-left texel's centre */
	CHECK_NEAR(rgb[0], 0, 1e-12);
	fct_texture_sample(&t, 0.75, 0.25, rgb);    /* bottom-right */
	CHECK_NEAR(rgb[0], 40, 1e-12);
	fct_texture_sample(&t, 0.5, 0.5, rgb);      /* the middle: the mean */
	CHECK_NEAR(rgb[0], 85, 1e-12);
	fct_texture_sample(&t, -3, 0.75, rgb);      /* clamped at the edge */
	CHECK_NEAR(rgb[0], 0, 1e-12);
	fct_texture_sample(&t, 0.5, 0.75, rgb);     /* half-way along the top row */
	CHECK_NEAR(rgb[0], 50, 1e-12);
	/* 16-bit grey with alpha over a background. */
	struct fct_image g, out;
	CHECK(fct_image_alloc(&g, 1, 1, 2, FCT_PIX_U16, &err) == 0);
	((uint16_t *)g.data)[0] = 65535, ((uint16_t *)g.data)[1] = 0;    /* transparent */
	static const unsigned char bg[3] = {10, 20, 30};
	CHECK(fct_image_to_rgb8(&g, bg, &out, &err) == 0);
	CHECK(((unsigned char *)out.data)[0] == 10 && ((unsigned char *)out.data)[2] == 30);
	fct_image_free(&out);
	fct_image_free(&g);
	fct_image_free(&t);
}

static void test_text(void)
{
	int w, h;
	fct_text_size("ab", 1, &w, &h);
	CHECK_INT(w, 11);
	CHECK_INT(h, 7);
	fct_text_size("abc\nd", 2, &w, &h);
	CHECK_INT(w, 34);
	CHECK_INT(h, 32);
	struct fct_err err;
	struct fct_image img;
	CHECK(fct_image_alloc(&img, 12, 9, 3, FCT_PIX_U8, &err) == 0);
	static const unsigned char ink[3] = {255, 255, 255};
	CHECK_INT(fct_draw_text(&img, 1, 1, 1, ink, "I"), 5);
	/* 'I' is a bar in column 2 with serifs in columns 1-3 on rows 0 and 6. */
	const unsigned char *p = img.data;
	size_t on = 0;
	for (size_t i = 0; i < 12 * 9; i++)
		on += p[3 * i] == 255;
	CHECK_INT(on, 3 + 5 + 3);
	CHECK_INT(p[3 * (4 * 12 + 3)], 255);       /* (x 1 + 2, y 1 + 3) */
	fct_image_free(&img);
}

/* Fitting: the points end up inside the picture with the margin, and
 * centred. */
static void test_fit(void)
{
	struct fct_err err;
	struct fct_view v;
	double eye[3] = {0, 0, -1}, target[3] = {0, 0, 0}, up[3] = {0, -1, 0};
	CHECK(fct_view_look_at(&v, eye, target, up, 60, 200, 100, &err) == 0);
	CHECK_NEAR(v.fy, 50 / tan(M_PI / 6), 1e-9);
	double pts[] = {-1, -1, 0, 3, 1, 0, -1, 1, 0.5, 3, -1, 0.5};
	fct_view_fit(&v, target, pts, 4, 0.1);
	double umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
	for (int i = 0; i < 4; i++) {
		double q[3];
		fct_view_to_camera(&v, pts + 3 * i, q);
		CHECK(q[2] > v.near);
		double u = v.fx * q[0] / q[2] + v.cx, w = v.fy * q[1] / q[2] + v.cy;
		umin = fmin(umin, u), umax = fmax(umax, u), vmin = fmin(vmin, w), vmax = fmax(vmax, w);
	}
	CHECK(umin >= -0.5 + 9.99 && umax <= 199.5 - 9.99);
	CHECK(vmin >= -0.5 + 4.99 && vmax <= 99.5 - 4.99);
	CHECK_NEAR(umin + umax, 199, 1e-6);               /* centred */
	CHECK_NEAR(vmin + vmax, 99, 1e-6);
	/* Tight on one axis at least. */
	CHECK(fabs(umax - umin - 180) < 1e-3 || fabs(vmax - vmin - 90) < 1e-3);
	CHECK(fct_view_look_at(&v, eye, eye, up, 60, 10, 10, &err) == -1);
	double along[3] = {0, 0, 1};
	CHECK(fct_view_look_at(&v, eye, target, along, 60, 10, 10, &err) == -1);
}

int main(void)
{
	test_coverage();
	test_zbuffer();
	test_perspective();
	test_clip();
	test_lines();
	test_colours();
	test_texture();
	test_text();
	test_fit();
	CHECK_DONE();
}

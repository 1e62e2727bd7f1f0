/* test_viewtex.c - texturing from photos rendered here of a plane with a
 * smooth colour pattern: the textured plane seen again from its photo's
 * camera reproduces the photo (PSNR over 40 dB); a photo darker by 0.8
 * gets a gain 1.25 times the other's, and none without levelling; faces
 * hidden from one photo by an occluder take the other photo; a planar
 * patch seen obliquely is textured at one metric density (rectified) where
 * the projection's density varies with depth; a face behind every camera
 * gets the fill colour and is counted; the same inputs give the same
 * pages; blending weighs a photo twice as far by half; a mesh without
 * faces or with a NaN vertex is refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/geom.h"
#include "io/header.h"
#include "geom/planes.h"
#include "render/raster.h"
#include "square.h"
#include "render/texmap.h"
#include "render/viewtex.h"

static const struct fct_camera cam = { FCT_CAMERA_PINHOLE, 96, 72, 70, 70, 47.5, 35.5, 0, 0 };

/* The pattern on the plane z = 2. */
static void pattern(const double p[3], double c[3])
{
	c[0] = 128 + 80 * sin(2.1 * p[0] + 0.3);
	c[1] = 128 + 80 * sin(1.7 * p[1]);
	c[2] = 100 + 50 * cos(1.3 * (p[0] + p[1]));
}

/* A camera at c looking at (0, 0, 2), x right, y down-ish. */
static void look(double pose[12], double cx, double cy, double cz)
{
	double z[3] = { -cx, -cy, 2 - cz }, up[3] = { 0, 1, 0 }, x[3], y[3];
	double n = sqrt(fct_v3_dot(z, z));
	for (int k = 0; k < 3; k++)
		z[k] /= n;
	fct_v3_cross(x, up, z);
	n = sqrt(fct_v3_dot(x, x));
	for (int k = 0; k < 3; k++)
		x[k] /= n;
	fct_v3_cross(y, z, x);
	for (int k = 0; k < 3; k++) {
		pose[4 * k] = x[k], pose[4 * k + 1] = y[k], pose[4 * k + 2] = z[k];
	}
	pose[3] = cx, pose[7] = cy, pose[11] = cz;
}

/* The photo of the plane z = 2 (and, when occ, of the square occluder
 * [-1.2, 0] x [-1.2, 1.2] at z = 1, painted black) by cam at pose, its
 * colours times gain. */
static void photo(struct fct_image *img, const double pose[12], double gain, int occ)
{
	struct fct_err err;
	fct_image_alloc(img, cam.width, cam.height, 3, FCT_PIX_U8, &err);
	unsigned char *d = img->data;
	for (int v = 0; v < cam.height; v++)
		for (int u = 0; u < cam.width; u++) {
			double r[3] = { (u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1 }, w[3], c[3] = { 0, 0, 0 };
			for (int k = 0; k < 3; k++)
				w[k] = pose[4 * k] * r[0] + pose[4 * k + 1] * r[1] + pose[4 * k + 2] * r[2];
			double t = (2 - pose[11]) / w[2], p[3];
			for (int k = 0; k < 3; k++)
				p[k] = pose[4 * k + 3] + t * w[k];
			if (t > 0)
				pattern(p, c);
			double t1 = (1 - pose[11]) / w[2];
			double x1 = pose[3] + t1 * w[0], y1 = pose[7] + t1 * w[1];
			if (occ && t1 > 0 && x1 >= -1.2 && x1 <= 0 && y1 >= -1.2 && y1 <= 1.2)
				c[0] = c[1] = c[2] = 0;
			for (int k = 0; k < 3; k++) {
				double g = floor(gain * c[k] + 0.5);
				d[3 * ((size_t)v * (size_t)cam.width + (size_t)u) + (size_t)k] =
					(unsigned char)(g < 0 ? 0 : g > 255 ? 255 : g);
			}
		}
}

/* The occluder's two triangles appended to m. */
static void add_occluder(struct fct_mesh *m)
{
	struct fct_err err;
	uint32_t b = (uint32_t)m->nv;
	fct_mesh_add_vertex(m, -1.2, -1.2, 1, &err);
	fct_mesh_add_vertex(m, 0, -1.2, 1, &err);
	fct_mesh_add_vertex(m, -1.2, 1.2, 1, &err);
	fct_mesh_add_vertex(m, 0, 1.2, 1, &err);
	uint32_t t1[3] = { b, b + 2, b + 1 }, t2[3] = { b + 1, b + 2, b + 3 };
	fct_mesh_add_face(m, t1, 3, &err);
	fct_mesh_add_face(m, t2, 3, &err);
}

/* Texture m from the photos (poses, gains); T is returned for its
 * accessors (free it), or NULL on failure. */
static struct fct_viewtex *texture(struct fct_mesh *m, const double (*poses)[12], const double *gains,
                                   size_t n, const struct fct_viewtex_params *p, int occ)
{
	struct fct_err err;
	struct fct_viewtex *T = fct_viewtex_new(m, n, p, &err);
	if (!T)
		return NULL;
	struct fct_image img[4];
	for (size_t k = 0; k < n; k++) {
		photo(&img[k], poses[k], gains[k], occ && k == 0);
		CHECK(fct_viewtex_add_view(T, k, &cam, poses[k], &img[k], NULL, &err) == 0);
	}
	CHECK(fct_viewtex_label(T, &err) == 0);
	CHECK(fct_viewtex_layout(T, &err) == 0);
	for (size_t k = 0; k < n; k++)
		if (fct_viewtex_needs_view(T, k))
			CHECK(fct_viewtex_sample_view(T, k, &img[k], &err) == 0);
	CHECK(fct_viewtex_finish(T, &err) == 0);
	for (size_t k = 0; k < n; k++)
		fct_image_free(&img[k]);
	return T;
}

/* PSNR of the textured plane (mapping applied to m, pages of T) seen from
 * pose against the photo, over the covered pixels. */
static double render_psnr(struct fct_viewtex *T, const struct fct_mesh *m, const double pose[12])
{
	struct fct_err err;
	struct fct_view v;
	struct fct_raster r;
	fct_view_from_camera(&v, &cam, pose, 0, 0, 0.01, &err);
	fct_raster_init(&r, cam.width, cam.height, &err);
	for (size_t f = 0; f < m->nf; f++) {
		double q[3][3];
		for (int j = 0; j < 3; j++)
			fct_view_to_camera(&v, m->xyz + 3 * (size_t)m->fvert[3 * f + (size_t)j], q[j]);
		fct_raster_triangle(&r, &v, q[0], q[1], q[2], (uint32_t)f);
	}
	float *st;
	int32_t *tn;
	fct_texmap_corners(m, &st, &tn, &err);
	struct fct_image ph;
	photo(&ph, pose, 1, 0);
	double sse = 0, n = 0;
	for (size_t i = 0; i < (size_t)cam.width * (size_t)cam.height; i++) {
		if (r.id[i] == FCT_RASTER_EMPTY)
			continue;
		size_t f = r.id[i];
		double b1 = r.b[2 * i], b2 = r.b[2 * i + 1], b0 = 1 - b1 - b2, c[3];
		double s = b0 * st[6 * f] + b1 * st[6 * f + 2] + b2 * st[6 * f + 4];
		double t = b0 * st[6 * f + 1] + b1 * st[6 * f + 3] + b2 * st[6 * f + 5];
		fct_texture_sample(fct_viewtex_page(T, (size_t)tn[f]), s, t, c);
		for (int k = 0; k < 3; k++) {
			double d = floor(c[k] + 0.5) - ((unsigned char *)ph.data)[3 * i + (size_t)k];
			sse += d * d;
			n++;
		}
	}
	free(st);
	free(tn);
	fct_image_free(&ph);
	fct_raster_free(&r);
	return n > 0 && sse > 0 ? 10 * log10(255.0 * 255.0 * n / sse) : 99;
}

static void test_reproduces_photo(void)
{
	struct fct_mesh m;
	struct fct_err err;
	square(&m, 8, 2);
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	p.level = 0;
	double poses[1][12], gains[1] = { 1 };
	look(poses[0], 0.1, -0.05, 0);
	struct fct_viewtex *T = texture(&m, poses, gains, 1, &p, 0);
	CHECK(T != NULL);
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	CHECK_INT(st.unseen, 0);
	CHECK_INT(st.views_used, 1);
	CHECK_INT(st.charts, 1);
	CHECK_INT(st.pages, 1);
	char *names[1] = { "a.png" };
	CHECK(fct_viewtex_apply(T, &m, names, 1, &err) == 0);
	double psnr = render_psnr(T, &m, poses[0]);
	CHECK_MSG(psnr > 40, "textured plane against its own photo: %.2f dB", psnr);
	/* A photo from elsewhere is reproduced too (the texture is on the
	 * plane, not in the picture). */
	double other[12];
	look(other, -0.3, 0.2, 0.3);
	psnr = render_psnr(T, &m, other);
	CHECK_MSG(psnr > 30, "textured plane from another camera: %.2f dB", psnr);
	CHECK_STR(fct_header_texture(&m, 0), "a.png");
	fct_viewtex_free(T);
	fct_mesh_free(&m);
}

static void test_gain(void)
{
	struct fct_mesh m;
	square(&m, 8, 2);
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	p.level = 1;
	double poses[2][12], gains[2] = { 1, 0.8 };
	look(poses[0], 0.1, 0, 0);
	look(poses[1], -0.1, 0.05, 0.05);
	struct fct_viewtex *T = texture(&m, poses, gains, 2, &p, 0);
	CHECK(T != NULL);
	/* The levelled pages: a texel of either photo's faces has the same
	 * colour for the same point, so the whole texture lies within a
	 * level or two of one photo's colour scale; read the gains through
	 * the seam RMS instead: levelling must remove the darkening. */
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	if (st.seam_edges) {
		CHECK_MSG(st.seam_rms_before > 10, "seam rms before %.2f", st.seam_rms_before);
		CHECK_MSG(st.seam_rms_after < 3, "seam rms after %.2f", st.seam_rms_after);
	}
	double g0[3], g1[3];
	fct_viewtex_photo_gain(T, 0, g0);
	fct_viewtex_photo_gain(T, 1, g1);
	for (int k = 0; k < 3; k++)
		CHECK_MSG(fabs(g1[k] / g0[k] - 1.25) < 0.03, "gain ratio %d: %.4f", k, g1[k] / g0[k]);
	fct_viewtex_free(T);
	p.level = 0;
	T = texture(&m, poses, gains, 2, &p, 0);
	fct_viewtex_photo_gain(T, 1, g1);
	CHECK(g1[0] == 1 && g1[1] == 1 && g1[2] == 1);
	fct_viewtex_free(T);
	fct_mesh_free(&m);
}

static void test_occlusion(void)
{
	struct fct_mesh m;
	square(&m, 8, 2);
	size_t nplane = m.nf;
	add_occluder(&m);
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	p.level = 0;
	/* Photo 0 from the front left sees the left half of the plane behind
	 * the occluder; photo 1 from the left looks past it. */
	double poses[2][12], gains[2] = { 1, 1 };
	look(poses[0], 0, 0, -1.5);
	look(poses[1], -2.2, 0, 0.6);
	struct fct_viewtex *T = texture(&m, poses, gains, 2, &p, 1);
	CHECK(T != NULL);
	size_t hidden = 0, wrong = 0;
	for (size_t f = 0; f < nplane; f++) {
		const double *a = m.xyz + 3 * (size_t)m.fvert[3 * f];
		if (a[0] < -0.2 && a[0] > -1 && a[1] > -1 && a[1] < 0.9) {   /* behind the occluder for photo 0 */
			hidden++;
			wrong += fct_viewtex_face_photo(T, f) == 0;
		}
	}
	CHECK(hidden > 10);
	CHECK_MSG(wrong == 0, "%zu of %zu hidden faces textured from the photo that cannot see them",
	          wrong, hidden);
	fct_viewtex_free(T);
	fct_mesh_free(&m);
}

/* Texels per metre of face f: the square root of its texture area in
 * texels over its area in square metres. */
static double density(const struct fct_mesh *m, const float *st, const struct fct_image *pg, size_t f)
{
	const double *a = m->xyz + 3 * (size_t)m->fvert[3 * f], *b = m->xyz + 3 * (size_t)m->fvert[3 * f + 1];
	const double *c = m->xyz + 3 * (size_t)m->fvert[3 * f + 2];
	double A = 0.5 * fct_triangle_area2(a, b, c);
	const float *s = st + 6 * f;
	double ta = 0.5 * fabs((s[2] - s[0]) * (s[5] - s[1]) - (s[4] - s[0]) * (s[3] - s[1])) *
	            pg->width * pg->height;
	return sqrt(ta / A);
}

static void test_rectify(void)
{
	struct fct_err err;
	double lo[2] = { INFINITY, INFINITY }, hi[2] = { 0, 0 };
	for (int rect = 1; rect >= 0; rect--) {
		struct fct_mesh m;
		square(&m, 8, 2);
		int32_t *patch = calloc(m.nf, sizeof *patch);
		fct_patches_set(&m, patch, &err);
		struct fct_plane pl = { { 0, 0, -1 }, 2, (long)m.nf, 0 };
		CHECK(fct_planes_set(&m, &pl, 1, &err) == 0);
		free(patch);
		struct fct_viewtex_params p;
		fct_viewtex_params_default(&p);
		p.level = 0;
		p.rectify = rect;
		double poses[1][12], gains[1] = { 1 };
		look(poses[0], 1.6, 0.2, 0.3);        /* obliquely, from the right */
		struct fct_viewtex *T = texture(&m, poses, gains, 1, &p, 0);
		CHECK(T != NULL);
		struct fct_viewtex_stats st;
		fct_viewtex_get_stats(T, &st);
		CHECK_INT(st.rectified, rect ? 1 : 0);
		char *names[1] = { "r.png" };
		fct_viewtex_apply(T, &m, names, 1, &err);
		float *s;
		int32_t *tn;
		fct_texmap_corners(&m, &s, &tn, &err);
		for (size_t f = 0; f < m.nf; f++) {
			double d = density(&m, s, fct_viewtex_page(T, 0), f);
			lo[rect] = fmin(lo[rect], d), hi[rect] = fmax(hi[rect], d);
		}
		/* Rectified, at the finest resolution the photo has over it. */
		if (rect)
			CHECK_MSG(hi[1] >= 0.99 * 70 / 1.9, "rectified density %.2f texels/m", hi[1]);
		free(s);
		free(tn);
		fct_viewtex_free(T);
		fct_mesh_free(&m);
	}
	CHECK_MSG(hi[1] / lo[1] < 1.01, "rectified density %.2f to %.2f texels/m", lo[1], hi[1]);
	CHECK_MSG(hi[0] / lo[0] > 1.3, "projected density %.2f to %.2f texels/m", lo[0], hi[0]);
}

static void test_unseen_and_determinism(void)
{
	struct fct_mesh m;
	struct fct_err err;
	square(&m, 4, 2);
	/* A triangle behind the camera. */
	uint32_t b = (uint32_t)m.nv;
	fct_mesh_add_vertex(&m, 0, 0, -1, &err);
	fct_mesh_add_vertex(&m, 1, 0, -1, &err);
	fct_mesh_add_vertex(&m, 0, 1, -1, &err);
	uint32_t t[3] = { b, b + 1, b + 2 };
	fct_mesh_add_face(&m, t, 3, &err);
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	p.fill[0] = 10, p.fill[1] = 200, p.fill[2] = 30;
	double poses[2][12], gains[2] = { 1, 0.9 };
	look(poses[0], 0.1, 0, 0);
	look(poses[1], -0.2, 0.1, 0.1);
	struct fct_viewtex *T = texture(&m, poses, gains, 2, &p, 0);
	struct fct_viewtex *U = texture(&m, poses, gains, 2, &p, 0);
	struct fct_viewtex_stats st;
	fct_viewtex_get_stats(T, &st);
	CHECK_INT(st.unseen, 1);
	CHECK_INT(fct_viewtex_npages(T), fct_viewtex_npages(U));
	for (size_t i = 0; i < fct_viewtex_npages(T); i++) {
		const struct fct_image *a = fct_viewtex_page(T, i), *c = fct_viewtex_page(U, i);
		CHECK(a->width == c->width && a->height == c->height &&
		      !memcmp(a->data, c->data, fct_image_samples(a)));
	}
	char *names[1] = { "u.png" };
	CHECK(fct_viewtex_apply(T, &m, names, 1, &err) == 0);
	float *s;
	int32_t *tn;
	fct_texmap_corners(&m, &s, &tn, &err);
	double c[3];
	size_t last = m.nf - 1;
	fct_texture_sample(fct_viewtex_page(T, (size_t)tn[last]), s[6 * last], s[6 * last + 1], c);
	CHECK(c[0] == 10 && c[1] == 200 && c[2] == 30);
	free(s);
	free(tn);
	fct_viewtex_free(T);
	fct_viewtex_free(U);
	fct_mesh_free(&m);
}

/* Blended, two photos of the plane straight on, one from twice as far and
 * darker by half: the far one's projected area is a quarter of the near
 * one's, its weight the square root, 1/2, so each texel is (c + 0.5 (c /
 * 2)) / 1.5 = 5/6 of the near photo's colour c (the plain mean, 3/4). */
static void test_blend_weights(void)
{
	struct fct_mesh m;
	struct fct_err err;
	square(&m, 4, 2);
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	p.blend = 1, p.level = 0;
	double poses[2][12], gains[2] = { 1, 0.5 };
	look(poses[0], 0, 0, 0);
	look(poses[1], 0, 0, -2);
	struct fct_viewtex *T = texture(&m, poses, gains, 2, &p, 0);
	CHECK(T != NULL);
	char *names[1] = { "b.png" };
	CHECK(fct_viewtex_apply(T, &m, names, 1, &err) == 0);
	float *s;
	int32_t *tn;
	CHECK(fct_texmap_corners(&m, &s, &tn, &err) == 1);
	double worst = 0;
	for (size_t f = 0; f < m.nf; f++) {
		double x[3] = { 0, 0, 0 }, st[2] = { 0, 0 }, want[3], got[3];
		for (int k = 0; k < 3; k++) {
			const double *v = &m.xyz[3 * (size_t)m.fvert[m.fstart[f] + (size_t)k]];
			for (int d = 0; d < 3; d++)
				x[d] += v[d] / 3;
			st[0] += s[6 * f + 2 * (size_t)k] / 3.0, st[1] += s[6 * f + 2 * (size_t)k + 1] / 3.0;
		}
		pattern(x, want);
		fct_texture_sample(fct_viewtex_page(T, (size_t)tn[f]), st[0], st[1], got);
		for (int k = 0; k < 3; k++)
			worst = fmax(worst, fabs(got[k] - want[k] * 5 / 6));
	}
	CHECK_MSG(worst < 2, "blended texel off 5/6 of the near photo by %.2f levels", worst);
	free(s);
	free(tn);
	fct_viewtex_free(T);
	fct_mesh_free(&m);
}

static void test_refused(void)
{
	struct fct_mesh m;
	struct fct_err err;
	struct fct_viewtex_params p;
	fct_viewtex_params_default(&p);
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0, 0, 1, &err);
	CHECK(fct_viewtex_new(&m, 1, &p, &err) == NULL);
	CHECK(strstr(err.msg, "no faces") != NULL);
	fct_mesh_free(&m);
	square(&m, 2, 2);
	m.xyz[4] = NAN;
	CHECK(fct_viewtex_new(&m, 1, &p, &err) == NULL);
	CHECK(strstr(err.msg, "vertex 1: coordinate is not finite") != NULL);
	m.xyz[4] = 0;
	p.atlas_max = 1000;
	CHECK(fct_viewtex_new(&m, 1, &p, &err) == NULL);
	fct_mesh_free(&m);
}

int main(void)
{
	test_reproduces_photo();
	test_gain();
	test_occlusion();
	test_rectify();
	test_unseen_and_determinism();
	test_blend_weights();
	test_refused();
	CHECK_DONE();
}

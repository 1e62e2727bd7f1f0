/* noise.c - sensor noise models (see noise.h). */
#include "io/noise.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/adj.h"
#include "io/camera.h"
#include "geom/geom.h"
#include "io/header.h"
#include "core/numparse.h"
#include "geom/planes.h"

static const char *const model_names[] = {
	[FCT_NOISE_NONE] = "none", [FCT_NOISE_KINECT] = "kinect", [FCT_NOISE_TOF] = "tof",
	[FCT_NOISE_POLY] = "poly", [FCT_NOISE_STEREO] = "stereo",
};

const char *fct_noise_models(void)
{
	return "none kinect tof poly stereo";
}

int fct_noise_names_model(const char *text)
{
	size_t n = strcspn(text, ":, \t");
	const char *m = fct_noise_models();
	while (*m) {
		size_t k = strcspn(m, " ");
		if (k == n && !strncmp(text, m, n))
			return 1;
		m += k + (m[k] == ' ');
	}
	return 0;
}

void fct_noise_kinect(struct fct_noise *nz)
{
	memset(nz, 0, sizeof *nz);
	nz->model = FCT_NOISE_KINECT;
	nz->focal = FCT_KINECT_FOCAL;
	nz->baseline = FCT_KINECT_BASELINE;
	nz->fb = FCT_KINECT_FOCAL * FCT_KINECT_BASELINE;
	nz->sd = FCT_KINECT_SD;
	nz->step = FCT_KINECT_STEP;
}

int fct_noise_named(const char *camera_name, struct fct_noise *nz)
{
	static const struct {
		const char *name;
		double baseline;
	} named[] = {
		{"tum", 0.0731}, {"tum1", 0.0731}, {"tum2", 0.0731}, {"tum3", 0.0731},
		{"redwood", FCT_KINECT_BASELINE}, {"primesense", FCT_KINECT_BASELINE},
		{"kinect", FCT_KINECT_BASELINE}, {"icl-nuim", 0.07506}, {"7scenes", 0.0738},
		{"nyu", 0.07506},   /* 351.3 / 8 = f b of NYU's raw codes */
	};
	for (size_t i = 0; i < sizeof named / sizeof *named; i++)
		if (!strcmp(camera_name, named[i].name)) {
			fct_noise_kinect(nz);
			nz->baseline = named[i].baseline;
			nz->fb = nz->focal * nz->baseline;
			return 0;
		}
	return -1;
}

static int is_separator(char c)
{
	return c == ' ' || c == '\t' || c == ':' || c == ',';
}

static const char *skip_separators(const char *s)
{
	while (is_separator(*s))
		s++;
	return s;
}

/* Up to max numbers after s, each followed by a separator or the end; stops
 * before the first word that is not a number.  Returns how many (or -1 for
 * something that starts like a number and is not one, or more than max),
 * *end at what follows. */
static int scan_numbers(const char *s, double *v, int max, const char **end)
{
	int n = 0;
	for (;;) {
		s = skip_separators(s);
		double x;
		const char *e = fct_parse_double(s, &x);
		if (!e) {
			*end = s;
			return *s && (*s == '-' || *s == '+' || *s == '.' || (*s >= '0' && *s <= '9')) ? -1 : n;
		}
		if ((*e && !is_separator(*e)) || !isfinite(x) || n == max)
			return -1;
		v[n++] = x;
		s = e;
	}
}

/* The number of parameters each model takes: at least, at most. */
static const struct {
	int min, max;
	const char *form;
} arity[] = {
	[FCT_NOISE_NONE] = {0, 0, "none"},
	[FCT_NOISE_KINECT] = {0, 4, "kinect[:F,B[,SD[,STEP]]]"},
	[FCT_NOISE_TOF] = {0, 2, "tof[:A,B]"},
	[FCT_NOISE_POLY] = {3, 3, "poly:A,B,C"},
	[FCT_NOISE_STEREO] = {2, 3, "stereo:FB,SD[,DOFFS]"},
};

int fct_noise_parse(struct fct_noise *nz, const char *text, struct fct_err *err)
{
	memset(nz, 0, sizeof *nz);
	const char *s = skip_separators(text);
	size_t len = 0;
	while (s[len] && !is_separator(s[len]))
		len++;
	enum fct_noise_model model = FCT_NOISE_UNKNOWN;
	for (int k = FCT_NOISE_NONE; k <= FCT_NOISE_STEREO; k++)
		if (strlen(model_names[k]) == len && !strncmp(s, model_names[k], len))
			model = (enum fct_noise_model)k;
	if (len == 5 && !strncmp(s, "exact", 5))
		model = FCT_NOISE_NONE;
	if (model == FCT_NOISE_UNKNOWN)
		return fct_fail(err, "noise: \"%.*s\" is not a model (%s)", (int)(len < 64 ? len : 64), s,
		                fct_noise_models());
	const char *form = arity[model].form;
	double v[4];
	const char *rest;
	int n = scan_numbers(s + len, v, arity[model].max, &rest);
	if (n < arity[model].min)
		return fct_fail(err, "noise: expected %s", form);
	if (*rest) {
		double u;
		if (strncmp(rest, "unit", 4) || !is_separator(rest[4]) ||
		    scan_numbers(rest + 4, &u, 1, &rest) != 1 || *rest)
			return fct_fail(err, "noise: expected %s, then optionally \"unit U\"", form);
		if (!(u >= 0 && u < 1e3))
			return fct_fail(err, "noise: unit must be in [0, 1000) metres");
		nz->unit = u;
	}
	nz->model = model;
	switch (model) {
	case FCT_NOISE_KINECT: {
		double def[4] = {FCT_KINECT_FOCAL, FCT_KINECT_BASELINE, FCT_KINECT_SD, FCT_KINECT_STEP};
		for (int k = 0; k < n; k++)
			def[k] = v[k];
		nz->focal = def[0], nz->baseline = def[1], nz->sd = def[2], nz->step = def[3];
		nz->fb = nz->focal * nz->baseline;
		if (!(nz->focal > 0 && nz->baseline > 0 && nz->fb < 1e12))
			return fct_fail(err, "noise kinect: F and B must be positive");
		if (!(nz->sd >= 0 && nz->step >= 0 && nz->sd < 1e6 && nz->step < 1e6))
			return fct_fail(err, "noise kinect: SD and STEP must be at least 0");
		break;
	}
	case FCT_NOISE_TOF:
		nz->coef[0] = n > 0 ? v[0] : FCT_TOF_A;
		nz->coef[1] = n > 1 ? v[1] : FCT_TOF_B;
		if (!(nz->coef[0] >= 0 && nz->coef[1] >= 0 && nz->coef[0] + nz->coef[1] > 0))
			return fct_fail(err, "noise tof: A and B must be at least 0, not both 0");
		break;
	case FCT_NOISE_POLY:
		memcpy(nz->coef, v, 3 * sizeof *v);
		if (!(v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && v[0] + v[1] + v[2] > 0))
			return fct_fail(err, "noise poly: A, B and C must be at least 0, not all 0");
		break;
	case FCT_NOISE_STEREO:
		nz->fb = v[0], nz->sd = v[1], nz->doffs = n > 2 ? v[2] : 0;
		if (!(nz->fb > 0 && nz->fb < 1e12 && nz->sd > 0 && nz->sd < 1e6))
			return fct_fail(err, "noise stereo: FB and SD must be positive");
		break;
	default:
		break;
	}
	return 0;
}

int fct_noise_read_file(const char *path, struct fct_noise *nz, struct fct_err *err)
{
	memset(nz, 0, sizeof *nz);
	char *text = fct_read_small_text(path, err);
	if (!text)
		return -1;
	/* One line, its line end not part of the model. */
	size_t n = strcspn(text, "\r\n");
	int rc = text[n + strspn(text + n, "\r\n")] != 0 ? fct_fail(err, "expected one line \"noise MODEL ...\"") : 0;
	text[n] = 0;
	const char *s = text + strspn(text, " \t");
	if (!rc && !strncmp(s, "comment", 7) && (s[7] == ' ' || s[7] == '\t'))
		s += 7 + strspn(s + 7, " \t");
	if (!rc && (strncmp(s, "noise", 5) || (s[5] != ' ' && s[5] != '\t')))
		rc = fct_fail(err, "expected \"noise MODEL ...\"");
	if (!rc)
		rc = fct_noise_parse(nz, s + 5, err);
	free(text);
	if (rc)
		fct_err_prefix(err, "%s", path);
	return rc;
}

void fct_noise_format(const struct fct_noise *nz, char *buf, size_t size)
{
	if (size == 0)
		return;
	buf[0] = 0;
	if (nz->model <= FCT_NOISE_UNKNOWN || nz->model > FCT_NOISE_STEREO)
		return;
	double v[5];
	int n = 0;
	switch (nz->model) {
	case FCT_NOISE_KINECT:
		v[0] = nz->focal, v[1] = nz->baseline, v[2] = nz->sd, v[3] = nz->step, n = 4;
		break;
	case FCT_NOISE_TOF:
		v[0] = nz->coef[0], v[1] = nz->coef[1], n = 2;
		break;
	case FCT_NOISE_POLY:
		v[0] = nz->coef[0], v[1] = nz->coef[1], v[2] = nz->coef[2], n = 3;
		break;
	case FCT_NOISE_STEREO:
		v[0] = nz->fb, v[1] = nz->sd, v[2] = nz->doffs, n = 3;
		break;
	default:
		break;
	}
	if (nz->unit > 0)
		v[n++] = nz->unit;
	size_t len = (size_t)snprintf(buf, size, "%s", model_names[nz->model]);
	for (int k = 0; k < n && len < size; k++) {
		char num[40];
		fct_format_double(num, sizeof num, v[k] + 0.0);
		len += (size_t)snprintf(buf + len, size - len, " %s%s", nz->unit > 0 && k == n - 1 ? "unit " : "", num);
	}
}

double fct_noise_sigma_gaussian(const struct fct_noise *nz, double z)
{
	switch (nz->model) {
	case FCT_NOISE_NONE:
		return FCT_NOISE_FLOOR * z;
	case FCT_NOISE_KINECT:
	case FCT_NOISE_STEREO:
		return z * z * nz->sd / nz->fb;
	case FCT_NOISE_TOF:
		return nz->coef[0] + nz->coef[1] * z;
	case FCT_NOISE_POLY:
		return nz->coef[0] + (nz->coef[1] + nz->coef[2] * z) * z;
	default:
		return 0;
	}
}

/* The disparity step of the kinect model as a depth step at z. */
static double disparity_step(const struct fct_noise *nz, double z)
{
	return nz->model == FCT_NOISE_KINECT ? z * z * nz->step / nz->fb : 0;
}

/* sigma^2 as a polynomial in z, c[0] + c[1] z + ... + c[4] z^4: every
 * model's Gaussian part is a polynomial of degree at most 2 and its
 * quantisation steps constant or quadratic. */
static void sigma2_polynomial(const struct fct_noise *nz, double c[5])
{
	memset(c, 0, 5 * sizeof *c);
	double a = 0, b = 0, q = 0;   /* Gaussian part a + b z + q z^2 */
	switch (nz->model) {
	case FCT_NOISE_NONE:
		b = FCT_NOISE_FLOOR;
		break;
	case FCT_NOISE_KINECT:
	case FCT_NOISE_STEREO:
		q = nz->sd / nz->fb;
		break;
	case FCT_NOISE_TOF:
	case FCT_NOISE_POLY:
		a = nz->coef[0], b = nz->coef[1], q = nz->coef[2];
		break;
	default:
		return;
	}
	double step = disparity_step(nz, 1);
	c[0] = a * a + nz->unit * nz->unit / 12;
	c[1] = 2 * a * b;
	c[2] = b * b + 2 * a * q;
	c[3] = 2 * b * q;
	c[4] = q * q + step * step / 12;
}

static double evaluate(const double c[5], double z)
{
	return (((c[4] * z + c[3]) * z + c[2]) * z + c[1]) * z + c[0];
}

double fct_noise_sigma(const struct fct_noise *nz, double z)
{
	double c[5];
	sigma2_polynomial(nz, c);
	return sqrt(evaluate(c, z));
}

void fct_noise_sigmas(const struct fct_noise *nz, const double *depth, float *sigma, size_t n)
{
	double c[5];
	sigma2_polynomial(nz, c);
	for (size_t i = 0; i < n; i++) {
		double z = depth[i] > 0 ? depth[i] : 0;
		sigma[i] = depth[i] > 0 ? (float)sqrt(evaluate(c, z)) : 0;
	}
}

int fct_noise_grows_with_depth(const struct fct_noise *nz)
{
	double c[5];
	sigma2_polynomial(nz, c);
	return c[1] != 0 || c[2] != 0 || c[3] != 0 || c[4] != 0;
}

double fct_noise_step(const struct fct_noise *nz, double z)
{
	double q = disparity_step(nz, z);
	return q > nz->unit ? q : nz->unit;
}

/* Estimating ---------------------------------------------------------------- */

/* Where the mesh was seen from: its camera and the inverse of its pose. */
struct viewpoint {
	int known;
	struct fct_camera cam;
	double inv[12];
};

static int read_viewpoint(struct viewpoint *vp, const struct fct_mesh *m, struct fct_err *err)
{
	memset(vp, 0, sizeof *vp);
	double pose[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
	int rc = fct_header_camera(m, &vp->cam, err);
	if (rc < 0 || fct_header_pose(m, pose, err) < 0)
		return -1;
	vp->known = rc == 1;
	fct_pose_invert(pose, vp->inv);
	return 0;
}

/* Depth z of world point p and the length of its ray per unit depth; 0 when
 * p has no depth (behind a pinhole camera, on a cylinder's axis). */
static int depth_of(const struct viewpoint *vp, const double p[3], double *z, double *ray_len,
                    double dir[3])
{
	double q[3], u, v;
	fct_pose_apply(vp->inv, p, q);
	if (!fct_camera_project(&vp->cam, q, &u, &v, z) || !(*z > 0))
		return 0;
	double len = sqrt(fct_v3_dot(q, q));
	*ray_len = len / *z;
	for (int k = 0; k < 3; k++)   /* the ray's direction in the world */
		dir[k] = (vp->inv[k] * q[0] + vp->inv[4 + k] * q[1] + vp->inv[8 + k] * q[2]) / len;
	return 1;
}

/* The median of v[0..n) (sorted in place; the lower middle for even n). */
static double median(double *v, size_t n)
{
	qsort(v, n, sizeof *v, fct_cmp_double);
	return v[(n - 1) / 2];
}

/* The mean length of the edges from vertex s to the other corners of its
 * faces; 0 when it has none. */
static double mean_edge(const struct fct_mesh *m, const uint32_t *vfs, const uint32_t *vf, size_t s)
{
	double sum = 0;
	size_t n = 0;
	for (uint32_t k = vfs[s]; k < vfs[s + 1]; k++) {
		uint32_t f = vf[k];
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++)
			if (m->fvert[c] != s) {
				sum += sqrt(fct_v3_dist2(m->xyz + 3 * s, m->xyz + 3 * (size_t)m->fvert[c]));
				n++;
			}
	}
	return n ? sum / (double)n : 0;
}

/* The rms of the plane fitted to the points list[0..n) (n - 3 degrees of
 * freedom) and the plane's unit normal. */
static double plane_rms(const struct fct_mesh *m, const uint32_t *list, size_t n, double normal[3],
                        double centroid[3])
{
	double c[3] = {0, 0, 0}, s[6] = {0, 0, 0, 0, 0, 0};
	for (size_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++)
			c[k] += m->xyz[3 * (size_t)list[i] + k] / (double)n;
	for (size_t i = 0; i < n; i++) {
		const double *p = m->xyz + 3 * (size_t)list[i];
		double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
		s[0] += d[0] * d[0], s[1] += d[1] * d[1], s[2] += d[2] * d[2];
		s[3] += d[0] * d[1], s[4] += d[1] * d[2], s[5] += d[0] * d[2];
	}
	struct fct_plane pl;
	double lambda = fct_plane_fit(&pl, c, s);
	memcpy(normal, pl.n, sizeof pl.n);
	memcpy(centroid, c, sizeof c);
	return sqrt((lambda > 0 ? lambda : 0) / (double)(n - 3));
}

/* The median absolute deviation of log(rms / z^p) over the seeds, for the
 * choice of p; q gets the quotients. */
static double log_spread(const double *rms, const double *z, const double *len, size_t n, int p,
                         double *q, double *work)
{
	for (size_t i = 0; i < n; i++) {
		q[i] = rms[i] / (pow(z[i], p) * len[i]);
		work[i] = log(q[i]);
	}
	double mid = median(work, n);
	for (size_t i = 0; i < n; i++)
		work[i] = fabs(log(q[i]) - mid);
	return median(work, n);
}

int fct_noise_fit(struct fct_noise_fit *fit, const struct fct_mesh *m, struct fct_err *err)
{
	memset(fit, 0, sizeof *fit);
	struct viewpoint vp;
	if (read_viewpoint(&vp, m, err))
		return -1;
	size_t nv = m->nv, stride = nv / FCT_NOISE_SEEDS + 1, nseeds = (nv + stride - 1) / stride;
	uint32_t *vfs = NULL, *vf = NULL;
	uint32_t *stamp = fct_alloc_array(nv, sizeof *stamp, err);
	uint32_t *list = fct_alloc_array(nv, sizeof *list, err);
	double *buf = fct_alloc_array(nseeds, 5 * sizeof *buf, err);
	int rc = -1;
	if (!stamp || !list || !buf || fct_vertex_faces(m, &vfs, &vf, err))
		goto out;
	double *rms = buf, *z = buf + nseeds, *len = buf + 2 * nseeds, *q = buf + 3 * nseeds, *work = buf + 4 * nseeds;
	memset(stamp, 0xff, nv * sizeof *stamp);
	size_t n = 0;
	for (size_t s = 0; s < nv; s += stride) {
		double r = FCT_NOISE_RADIUS * mean_edge(m, vfs, vf, s);
		size_t k = r > 0 ? fct_vertices_within(m, vfs, vf, s, r, stamp, (uint32_t)s, list) : 0;
		if (k < 12)
			continue;
		double normal[3], c[3], dir[3];
		double e = plane_rms(m, list, k, normal, c);
		z[n] = len[n] = 1;
		if (vp.known) {
			if (!depth_of(&vp, c, &z[n], &len[n], dir))
				continue;
			double cosine = fabs(fct_v3_dot(dir, normal));
			e /= cosine > 0.3 ? cosine : 0.3;
		}
		if (e > 0 && isfinite(e))
			rms[n++] = e;
	}
	if (n < 20) {
		rc = fct_fail(err, "noise estimate: %zu neighbourhoods with a plane, 20 needed", n);
		goto out;
	}
	/* The law whose quotients spread least; ties to the lower power. */
	int best = 0;
	if (vp.known) {
		double spread[3];
		for (int p = 0; p < 3; p++)
			spread[p] = log_spread(rms, z, len, n, p, q, work);
		for (int p = 1; p < 3; p++)
			if (spread[p] < spread[best])
				best = p;
	}
	for (size_t i = 0; i < n; i++)
		q[i] = rms[i] / (pow(z[i], best) * len[i]);
	fit->c = median(q, n);
	fit->p = best;
	fit->camera = vp.known;
	fit->seeds = n;
	for (size_t i = 0; i < n; i++)
		q[i] = fit->c * pow(z[i], best) * len[i];
	fit->sigma = median(q, n);
	rc = 0;
out:
	free(stamp);
	free(list);
	free(buf);
	free(vfs);
	free(vf);
	return rc;
}

int fct_noise_estimate(double *sigma, const struct fct_mesh *m, struct fct_err *err)
{
	struct fct_noise_fit fit;
	*sigma = 0;
	if (fct_noise_fit(&fit, m, err))
		return -1;
	*sigma = fit.sigma;
	return 0;
}

int fct_noise_estimate_vertices(float *sigma, const struct fct_mesh *m, struct fct_err *err)
{
	struct fct_noise_fit fit;
	struct viewpoint vp;
	if (fct_noise_fit(&fit, m, err) || read_viewpoint(&vp, m, err))
		return -1;
	for (size_t v = 0; v < m->nv; v++) {
		double z, len, dir[3];
		if (fit.camera && depth_of(&vp, m->xyz + 3 * v, &z, &len, dir))
			sigma[v] = (float)(fit.c * pow(z, fit.p) * len);
		else
			sigma[v] = (float)(fit.camera ? fit.sigma : fit.c);
	}
	return 0;
}

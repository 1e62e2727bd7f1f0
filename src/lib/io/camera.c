/* camera.c - camera models, camera and pose files (see camera.h). */
#include "io/camera.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/numparse.h"

void fct_camera_ray(const struct fct_camera *cam, double u, double v, double ray[3])
{
	if (cam->kind == FCT_CAMERA_CYLINDRICAL) {
		double theta = cam->theta0 + 2 * M_PI * u / cam->width;
		ray[0] = sin(theta);
		ray[1] = (v - cam->cy) / cam->f;
		ray[2] = cos(theta);
	} else {
		ray[0] = (u - cam->cx) / cam->fx;
		ray[1] = (v - cam->cy) / cam->fy;
		ray[2] = 1;
	}
}

double fct_camera_pixel_angle(const struct fct_camera *cam)
{
	if (cam->kind == FCT_CAMERA_CYLINDRICAL)
		return cam->width > 0 ? sqrt(2 * M_PI / cam->width / cam->f) : 0;
	if (cam->kind == FCT_CAMERA_PINHOLE)
		return 1 / sqrt(cam->fx * cam->fy);
	return 0;
}

int fct_camera_project(const struct fct_camera *cam, const double p[3], double *u, double *v,
                       double *depth)
{
	if (cam->kind == FCT_CAMERA_CYLINDRICAL) {
		double rho = hypot(p[0], p[2]);
		if (!(rho > 0))
			return 0;
		double a = atan2(p[0], p[2]) - cam->theta0;
		double w = cam->width;
		double x = a * w / (2 * M_PI);
		x -= w * floor((x + 0.5) / w);
		*u = x, *v = cam->cy + cam->f * p[1] / rho, *depth = rho;
		return 1;
	}
	if (!(p[2] > 0))
		return 0;
	*u = cam->cx + cam->fx * p[0] / p[2];
	*v = cam->cy + cam->fy * p[1] / p[2];
	*depth = p[2];
	return 1;
}

double fct_snap_pixel_centre(double x)
{
	if (!isfinite(x))
		return x;
	double r = floor(x) + 0.5;
	return fabs(x - r) < 1e-3 ? r : x;
}

/* Skip blanks (and, for files, line ends and commas of JSON arrays). */
static const char *skip_space(const char *s)
{
	while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
		s++;
	return s;
}

/* Up to max finite numbers separated by blanks, line ends or commas; stops at
 * the first thing that is not a number.  Returns how many, *end after them. */
static int scan_numbers(const char *s, double *v, int max, const char **end)
{
	int n = 0;
	for (;;) {
		s = skip_space(s);
		double x;
		const char *e = n < max ? fct_parse_double(s, &x) : NULL;
		if (!e || !isfinite(x))
			break;
		v[n++] = x;
		s = skip_space(e);
		if (*s == ',')
			s++;
	}
	*end = s;
	return n;
}

static int word_is(const char *s, const char *w, const char **after)
{
	size_t n = strlen(w);
	if (strncmp(s, w, n) || (s[n] && s[n] != ' ' && s[n] != '\t'))
		return 0;
	*after = s + n;
	return 1;
}

static int check_size(double w, double h, struct fct_camera *cam, struct fct_err *err)
{
	if (!(w >= 1 && h >= 1 && w <= 1e9 && h <= 1e9 && w == floor(w) && h == floor(h)))
		return fct_fail(err, "camera: bad image size %.17g x %.17g", w, h);
	cam->width = (int)w, cam->height = (int)h;
	return 0;
}

int fct_camera_parse(const char *text, struct fct_camera *cam, struct fct_err *err)
{
	memset(cam, 0, sizeof *cam);
	const char *s = skip_space(text), *rest, *end;
	double v[7];
	int n;
	if (word_is(s, "pinhole", &rest)) {
		n = scan_numbers(rest, v, 7, &end);
		if (n != 6 || *end)
			return fct_fail(err, "camera pinhole: expected W H fx fy cx cy");
		cam->kind = FCT_CAMERA_PINHOLE;
		cam->fx = v[2], cam->fy = v[3], cam->cx = v[4], cam->cy = v[5];
		if (!(cam->fx > 0 && cam->fy > 0))
			return fct_fail(err, "camera pinhole: focal lengths must be positive");
	} else if (word_is(s, "cylindrical", &rest)) {
		n = scan_numbers(rest, v, 6, &end);
		if (n != 5 || *end)
			return fct_fail(err, "camera cylindrical: expected W H f cy theta0");
		cam->kind = FCT_CAMERA_CYLINDRICAL;
		cam->f = v[2], cam->cy = v[3], cam->theta0 = v[4];
		if (!(cam->f > 0))
			return fct_fail(err, "camera cylindrical: f must be positive");
	} else {
		return fct_fail(err, "camera: expected \"pinhole W H fx fy cx cy\" or "
		                "\"cylindrical W H f cy theta0\"");
	}
	return check_size(v[0], v[1], cam, err);
}

void fct_camera_format(const struct fct_camera *cam, char *buf, size_t size)
{
	if (cam->kind == FCT_CAMERA_CYLINDRICAL)
		snprintf(buf, size, "cylindrical %d %d %.17g %.17g %.17g",
		         cam->width, cam->height, cam->f, cam->cy, cam->theta0);
	else
		snprintf(buf, size, "pinhole %d %d %.17g %.17g %.17g %.17g",
		         cam->width, cam->height, cam->fx, cam->fy, cam->cx, cam->cy);
}

/* Intrinsics of common RGB-D datasets, all 640x480.  TUM: the freiburg 1-3
 * calibrations from the dataset page and the ROS default it recommends for
 * the rest; Redwood, PrimeSense/Kinect: Open3D's PrimeSenseDefault;
 * ICL-NUIM: its published K with the y axis pointing down; 7-Scenes: the
 * dataset's approximate depth camera; NYU Depth v2: its toolbox's depth
 * camera (camera_params.m; its raw frames need depth code nyu). */
static const struct named_camera {
	const char *name;
	double fx, fy, cx, cy, scale;
} named_cameras[] = {
	{ "tum",        525.0, 525.0, 319.5, 239.5, 5000 },
	{ "tum1",       517.3, 516.5, 318.6, 255.3, 5000 },
	{ "tum2",       520.9, 521.0, 325.1, 249.7, 5000 },
	{ "tum3",       535.4, 539.2, 320.1, 247.6, 5000 },
	{ "redwood",    525.0, 525.0, 319.5, 239.5, 1000 },
	{ "primesense", 525.0, 525.0, 319.5, 239.5, 1000 },
	{ "kinect",     525.0, 525.0, 319.5, 239.5, 1000 },
	{ "icl-nuim",   481.2, 480.0, 319.5, 239.5, 5000 },
	{ "7scenes",    585.0, 585.0, 320.0, 240.0, 1000 },
	{ "nyu",        582.62448, 582.69103, 313.04476, 238.44390, 1000 },
};

int fct_camera_named(const char *name, struct fct_camera *cam, double *depth_scale)
{
	for (size_t i = 0; i < sizeof named_cameras / sizeof *named_cameras; i++) {
		const struct named_camera *c = &named_cameras[i];
		if (strcmp(name, c->name))
			continue;
		memset(cam, 0, sizeof *cam);
		cam->kind = FCT_CAMERA_PINHOLE;
		cam->width = 640, cam->height = 480;
		cam->fx = c->fx, cam->fy = c->fy, cam->cx = c->cx, cam->cy = c->cy;
		if (depth_scale)
			*depth_scale = c->scale;
		return 0;
	}
	return -1;
}

const char *fct_camera_known(const struct fct_camera *cam, double not_scale, double *depth_scale)
{
	if (cam->kind != FCT_CAMERA_PINHOLE || !((cam->width == 640 && cam->height == 480) ||
	                                         (cam->width == 0 && cam->height == 0)))
		return NULL;
	const struct named_camera *found = NULL;
	for (size_t i = 0; i < sizeof named_cameras / sizeof *named_cameras; i++) {
		const struct named_camera *c = &named_cameras[i];
		if (!(fabs(cam->fx - c->fx) <= 0.01 * c->fx && fabs(cam->fy - c->fy) <= 0.01 * c->fy &&
		      fabs(cam->cx - c->cx) <= 0.01 * c->cx && fabs(cam->cy - c->cy) <= 0.01 * c->cy))
			continue;
		if (!found || (found->scale == not_scale && c->scale != not_scale))
			found = c;
	}
	if (found && depth_scale)
		*depth_scale = found->scale;
	return found ? found->name : NULL;
}

const char *fct_camera_names(void)
{
	return "tum tum1 tum2 tum3 redwood primesense kinect icl-nuim 7scenes nyu";
}

char *fct_read_small_text(const char *path, struct fct_err *err)
{
	enum { MAX = 1 << 16 };
	FILE *f = fopen(path, "rb");
	if (!f) {
		fct_fail(err, "%s: %s", path, strerror(errno));
		return NULL;
	}
	char *buf = malloc(MAX + 1);
	size_t n = buf ? fread(buf, 1, MAX + 1, f) : 0;
	int bad = ferror(f);
	fclose(f);
	if (!buf) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	const char *why = bad ? "read error" : n > MAX ? "too large for a camera or pose file"
	                : memchr(buf, 0, n) ? "binary data in a text file" : NULL;
	if (why) {
		fct_fail(err, "%s: %s", path, why);
		free(buf);
		return NULL;
	}
	buf[n] = 0;
	return buf;
}

/* The text after "key" and a colon in a JSON object (no full JSON parser:
 * Open3D's intrinsic files are flat objects). */
static const char *json_value(const char *s, const char *key)
{
	size_t n = strlen(key);
	for (const char *p = s; (p = strchr(p, '"')); p++) {
		if (strncmp(p + 1, key, n) || p[n + 1] != '"')
			continue;
		const char *q = skip_space(p + n + 2);
		if (*q == ':')
			return skip_space(q + 1);
	}
	return NULL;
}

static int parse_open3d_json(const char *text, const char *path, struct fct_camera *cam,
                             struct fct_err *err)
{
	const char *w = json_value(text, "width"), *h = json_value(text, "height");
	const char *k = json_value(text, "intrinsic_matrix"), *end;
	double vw, vh, m[10];
	if (!w || !h || !k || *k != '[' || scan_numbers(w, &vw, 1, &end) != 1
	    || scan_numbers(h, &vh, 1, &end) != 1)
		return fct_fail(err, "%s: expected Open3D intrinsics: \"width\", \"height\" and "
		                "\"intrinsic_matrix\"", path);
	if (scan_numbers(k + 1, m, 10, &end) != 9 || *end != ']')
		return fct_fail(err, "%s: intrinsic_matrix: expected 9 numbers", path);
	/* Open3D stores K column by column: fx 0 0 0 fy 0 cx cy 1. */
	memset(cam, 0, sizeof *cam);
	cam->kind = FCT_CAMERA_PINHOLE;
	cam->fx = m[0], cam->fy = m[4], cam->cx = m[6], cam->cy = m[7];
	if (!(cam->fx > 0 && cam->fy > 0) || m[1] != 0 || m[2] != 0 || m[3] != 0 || m[5] != 0 || m[8] != 1)
		return fct_fail(err, "%s: intrinsic_matrix is not a pinhole K with positive focal lengths",
		                path);
	if (check_size(vw, vh, cam, err)) {
		fct_err_prefix(err, "%s", path);
		return -1;
	}
	return 0;
}

static int parse_k_matrix(const char *text, const char *path, struct fct_camera *cam,
                          struct fct_err *err)
{
	double k[10];
	const char *end;
	int n = scan_numbers(text, k, 10, &end);
	if (n != 9 || *end)
		return fct_fail(err, "%s: expected a camera line, Open3D JSON or a 3x3 K matrix", path);
	if (!(k[0] > 0 && k[4] > 0) || k[1] != 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1)
		return fct_fail(err, "%s: not a pinhole K matrix (fx 0 cx / 0 fy cy / 0 0 1)", path);
	memset(cam, 0, sizeof *cam);
	cam->kind = FCT_CAMERA_PINHOLE;
	cam->fx = k[0], cam->fy = k[4], cam->cx = k[2], cam->cy = k[5];
	return 0;
}

/* Skip "comment" and then the keyword; NULL when the text does not start so. */
static const char *after_keyword(const char *text, const char *key)
{
	const char *s = skip_space(text), *rest;
	if (word_is(s, "comment", &rest))
		s = skip_space(rest);
	return word_is(s, key, &rest) ? rest : NULL;
}

/* The number after "key=" at the start of a line of a Middlebury
 * calib.txt; NULL when absent. */
static const char *calib_value(const char *text, const char *key)
{
	size_t n = strlen(key);
	for (const char *p = text; p; p = strchr(p, '\n')) {
		p = skip_space(p);
		if (!strncmp(p, key, n) && p[n] == '=')
			return p + n + 1;
	}
	return NULL;
}

/* Middlebury's stereo calib.txt (2014 and later): cam0=[fx 0 cx; 0 fy cy;
 * 0 0 1], doffs=, baseline= (mm), width=, height=; the disparity images
 * are cam0's. */
static int parse_middlebury(const char *text, const char *path, struct fct_camera *cam,
                            struct fct_stereo *stereo, struct fct_err *err)
{
	const char *k = calib_value(text, "cam0"), *end;
	const char *w = calib_value(text, "width"), *h = calib_value(text, "height");
	const char *d = calib_value(text, "doffs"), *b = calib_value(text, "baseline");
	double m[10], vw, vh, doffs, base;
	if (!k || *k != '[' || !w || !h || !d || !b)
		return fct_fail(err, "%s: a Middlebury calib.txt needs cam0, width, height, doffs and "
		                "baseline", path);
	/* the rows are separated by semicolons */
	int n = 0;
	for (const char *s = k + 1; n < 9;) {
		int got = scan_numbers(s, m + n, 9 - n, &end);
		n += got;
		if (*end != ';' || got == 0)
			break;
		s = end + 1;
	}
	if (n != 9 || *end != ']')
		return fct_fail(err, "%s: cam0: expected [fx 0 cx; 0 fy cy; 0 0 1]", path);
	if (!(m[0] > 0 && m[4] > 0) || m[1] != 0 || m[3] != 0 || m[6] != 0 || m[7] != 0 || m[8] != 1)
		return fct_fail(err, "%s: cam0 is not a pinhole K with positive focal lengths", path);
	if (scan_numbers(w, &vw, 1, &end) != 1 || scan_numbers(h, &vh, 1, &end) != 1 ||
	    scan_numbers(d, &doffs, 1, &end) != 1 || scan_numbers(b, &base, 1, &end) != 1)
		return fct_fail(err, "%s: width, height, doffs and baseline must be numbers", path);
	if (!(base > 0 && base < 1e9) || !(fabs(doffs) < 1e9))
		return fct_fail(err, "%s: baseline %.17g mm, doffs %.17g: out of range", path, base, doffs);
	memset(cam, 0, sizeof *cam);
	cam->kind = FCT_CAMERA_PINHOLE;
	cam->fx = m[0], cam->fy = m[4], cam->cx = m[2], cam->cy = m[5];
	if (check_size(vw, vh, cam, err)) {
		fct_err_prefix(err, "%s", path);
		return -1;
	}
	if (stereo)
		stereo->baseline = base / 1000, stereo->doffs = doffs;
	return 0;
}

int fct_camera_read_file(const char *path, struct fct_camera *cam, struct fct_err *err)
{
	return fct_camera_read_stereo(cam, NULL, path, err);
}

int fct_camera_read_stereo(struct fct_camera *cam, struct fct_stereo *stereo, const char *path,
                           struct fct_err *err)
{
	if (stereo)
		stereo->baseline = stereo->doffs = 0;
	char *text = fct_read_small_text(path, err);
	if (!text)
		return -1;
	/* One trailing line end is part of a text file, not of the camera line. */
	size_t n = strlen(text);
	while (n && (text[n - 1] == '\n' || text[n - 1] == '\r'))
		text[--n] = 0;
	const char *s = skip_space(text), *rest;
	int rc;
	if (*s == '{') {
		rc = parse_open3d_json(s, path, cam, err);
	} else if (calib_value(s, "cam0")) {
		rc = parse_middlebury(s, path, cam, stereo, err);
	} else if ((rest = after_keyword(s, "camera"))) {
		rc = fct_camera_parse(rest, cam, err);
		if (rc)
			fct_err_prefix(err, "%s", path);
	} else {
		rc = parse_k_matrix(s, path, cam, err);
	}
	free(text);
	return rc;
}

int fct_pose_check(const double pose[12], double tol, struct fct_err *err)
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			double d = 0;
			for (int k = 0; k < 3; k++)
				d += pose[4 * k + i] * pose[4 * k + j];
			if (!(fabs(d - (i == j)) <= tol))
				return fct_fail(err, "pose: the 3x3 part is not a rotation (R^T R differs from I by %.3g)",
				                fabs(d - (i == j)));
		}
	double det = pose[0] * (pose[5] * pose[10] - pose[6] * pose[9])
	           - pose[1] * (pose[4] * pose[10] - pose[6] * pose[8])
	           + pose[2] * (pose[4] * pose[9] - pose[5] * pose[8]);
	if (!(det > 0))
		return fct_fail(err, "pose: the 3x3 part is a reflection, not a rotation");
	for (int k = 0; k < 12; k++)
		if (!isfinite(pose[k]))
			return fct_fail(err, "pose: not finite");
	return 0;
}

int fct_pose_read_file(const char *path, double pose[12], struct fct_err *err)
{
	char *text = fct_read_small_text(path, err);
	if (!text)
		return -1;
	const char *s = after_keyword(text, "pose"), *end;
	double v[17];
	int n = scan_numbers(s ? s : text, v, 17, &end);
	int rc = 0;
	if (*skip_space(end) || !(n == 12 || (n == 16 && !s)))
		rc = fct_fail(err, "%s: expected a 4x4 or 3x4 camera-to-world matrix, or a pose line", path);
	else if (n == 16 && (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1))
		rc = fct_fail(err, "%s: the last row of a 4x4 pose must be 0 0 0 1", path);
	free(text);
	if (rc)
		return -1;
	memcpy(pose, v, 12 * sizeof *pose);
	if (fct_pose_check(pose, 1e-3, err)) {
		fct_err_prefix(err, "%s", path);
		return -1;
	}
	return 0;
}

void fct_quat_pose(double x, double y, double z, double w, double pose[12])
{
	pose[0] = 1 - 2 * (y * y + z * z);
	pose[1] = 2 * (x * y - z * w);
	pose[2] = 2 * (x * z + y * w);
	pose[4] = 2 * (x * y + z * w);
	pose[5] = 1 - 2 * (x * x + z * z);
	pose[6] = 2 * (y * z - x * w);
	pose[8] = 2 * (x * z - y * w);
	pose[9] = 2 * (y * z + x * w);
	pose[10] = 1 - 2 * (x * x + y * y);
	pose[3] = pose[7] = pose[11] = 0;
}

void fct_pose_invert(const double pose[12], double inv[12])
{
	/* R^T when R is a rotation to rounding; else the inverse of the
	 * matrix itself, so that a pose whose R has drifted off a rotation
	 * (7-Scenes' are 1e-4 off) still maps its own points back onto their
	 * pixels. */
	const double *r0 = &pose[0], *r1 = &pose[4], *r2 = &pose[8];
	double off = 0;
	for (int i = 0; i < 3; i++)
		for (int j = i; j < 3; j++) {
			double d = pose[i] * pose[j] + pose[4 + i] * pose[4 + j] + pose[8 + i] * pose[8 + j] - (i == j);
			off = fabs(d) > off ? fabs(d) : off;
		}
	if (!(off > 1e-12)) {
		for (int i = 0; i < 3; i++) {
			for (int j = 0; j < 3; j++)
				inv[4 * i + j] = pose[4 * j + i];
			inv[4 * i + 3] = -(pose[i] * pose[3] + pose[4 + i] * pose[7] + pose[8 + i] * pose[11]);
		}
		return;
	}
	/* The adjugate over the determinant: rows of the inverse are the
	 * cross products of the columns' rows, divided by det. */
	double c0[3] = { r1[1] * r2[2] - r1[2] * r2[1], r1[2] * r2[0] - r1[0] * r2[2], r1[0] * r2[1] - r1[1] * r2[0] };
	double det = r0[0] * c0[0] + r0[1] * c0[1] + r0[2] * c0[2];
	double m[3][3] = {
		{ c0[0], r0[2] * r2[1] - r0[1] * r2[2], r0[1] * r1[2] - r0[2] * r1[1] },
		{ c0[1], r0[0] * r2[2] - r0[2] * r2[0], r0[2] * r1[0] - r0[0] * r1[2] },
		{ c0[2], r0[1] * r2[0] - r0[0] * r2[1], r0[0] * r1[1] - r0[1] * r1[0] },
	};
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			inv[4 * i + j] = m[i][j] / det;
		inv[4 * i + 3] = -(inv[4 * i] * pose[3] + inv[4 * i + 1] * pose[7] + inv[4 * i + 2] * pose[11]);
	}
}

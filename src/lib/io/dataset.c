/* dataset.c - a sequence's folder read as 7-Scenes, TUM or Redwood lay it out
 * (dataset.h). */
#include "io/dataset.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/path.h"
#include "io/poses.h"
#include "io/reader.h"

static int exists(const char *path)
{
	struct stat sb;
	return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

static int cmp_names(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The three path arrays for up to n frames, zeroed (fct_dataset_free
 * frees what is set). */
static int alloc_frames(struct fct_dataset *ds, size_t n, size_t nposes, struct fct_err *err)
{
	ds->depth = calloc(n, sizeof *ds->depth);
	ds->color = calloc(n, sizeof *ds->color);
	ds->poses = calloc(nposes, sizeof *ds->poses);
	ds->n = n, ds->nposes = nposes;
	return ds->depth && ds->color && ds->poses ? 0 : fct_fail(err, "out of memory");
}

/* The names of dir's entries that keep accepts, sorted. */
static int sorted_names(char ***names, size_t *n, const char *dir, int (*keep)(const char *name),
                        struct fct_err *err)
{
	DIR *d = opendir(dir);
	if (!d)
		return fct_fail(err, "%s: %s", dir, strerror(errno));
	size_t cap = 0;
	struct dirent *e;
	int rc = 0;
	*names = NULL, *n = 0;
	while (!rc && (e = readdir(d))) {
		if (!keep(e->d_name))
			continue;
		char *name = fct_strdup(e->d_name, err);
		if (!name || fct_grow((void **)names, &cap, *n + 1, sizeof **names, err)) {
			free(name);
			rc = -1;
			break;
		}
		(*names)[(*n)++] = name;
	}
	closedir(d);
	if (*n)
		qsort(*names, *n, sizeof **names, cmp_names);
	return rc;
}

static void free_names(char **names, size_t n)
{
	for (size_t i = 0; i < n; i++)
		free(names[i]);
	free(names);
}

static int ends_with(const char *s, const char *end)
{
	size_t ls = strlen(s), le = strlen(end);
	return ls >= le && !strcmp(s + ls - le, end);
}

static int is_seven_scenes_depth(const char *name)
{
	return !strncmp(name, "frame-", 6) && ends_with(name, ".depth.png");
}

/* The stems "frame-NNNNNN" of the *.depth.png files of dir, sorted. */
static int seven_scenes_stems(char ***stems, size_t *n, const char *dir, struct fct_err *err)
{
	if (sorted_names(stems, n, dir, is_seven_scenes_depth, err))
		return -1;
	for (size_t i = 0; i < *n; i++)
		(*stems)[i][strlen((*stems)[i]) - 10] = '\0';
	return 0;
}

static int read_seven_scenes(struct fct_dataset *ds, const char *dir, char **stems, size_t n,
                             struct fct_err *err)
{
	char name[600];
	ds->layout = "7-Scenes", ds->camera = "7scenes";
	if (alloc_frames(ds, n, n, err))
		return -1;
	for (size_t i = 0; i < n; i++) {
		snprintf(name, sizeof name, "%s.depth.png", stems[i]);
		if (!(ds->depth[i] = fct_path_join(dir, name, err)))
			return -1;
		static const char *const colour[] = { ".color.png", ".color.jpg" };
		for (int k = 0; k < 2 && !ds->color[i]; k++) {
			snprintf(name, sizeof name, "%s%s", stems[i], colour[k]);
			if (!(ds->color[i] = fct_path_join(dir, name, err)))
				return -1;
			if (!exists(ds->color[i])) {
				free(ds->color[i]);
				ds->color[i] = NULL;
			}
		}
		if (!ds->color[i])
			return fct_fail(err, "%s: %s has no colour image (%s.color.png or .color.jpg)", dir,
			                stems[i], stems[i]);
		snprintf(name, sizeof name, "%s.pose.txt", stems[i]);
		if (!(ds->poses[i] = fct_path_join(dir, name, err)))
			return -1;
		if (!exists(ds->poses[i]))
			return fct_fail(err, "%s: %s has no pose (%s)", dir, stems[i], name);
	}
	return 0;
}

/* A TUM list (rgb.txt, depth.txt): "timestamp file" per line, '#' lines
 * and blank lines aside; stamps and names (relative to the folder). */
struct stamped {
	size_t n;
	double *stamp;
	char **file;
};

static void stamped_free(struct stamped *s)
{
	for (size_t i = 0; i < s->n; i++)
		free(s->file[i]);
	free(s->file);
	free(s->stamp);
	memset(s, 0, sizeof *s);
}

static int read_stamped(struct stamped *s, const char *path, struct fct_err *err)
{
	memset(s, 0, sizeof *s);
	struct fct_reader r;
	if (fct_reader_open(&r, path, err))
		return -1;
	size_t cap_s = 0, cap_f = 0, len;
	int rc = 0;
	char *line;
	while (!rc && (line = fct_reader_line(&r, &len, err))) {
		unsigned long long no = (unsigned long long)r.line;
		if (memchr(line, '\0', len)) {
			rc = fct_fail(err, "%s:%llu: a NUL byte: binary data, not a TUM list", path, no);
			break;
		}
		char *p = line + strspn(line, " \t\r");
		if (*p == '#' || *p == '\0')
			continue;
		char *end, *name;
		double t = strtod(p, &end);
		size_t n = 0;
		name = end + strspn(end, " \t");
		n = strcspn(name, " \t\r");
		if (end == p || !isfinite(t) || end == name || n == 0) {
			rc = fct_fail(err, "%s:%llu: expected \"timestamp file\"", path, no);
			break;
		}
		name[n] = '\0';
		if (fct_grow((void **)&s->stamp, &cap_s, s->n + 1, sizeof *s->stamp, err) ||
		    fct_grow((void **)&s->file, &cap_f, s->n + 1, sizeof *s->file, err) ||
		    !(s->file[s->n] = fct_strdup(name, err))) {
			rc = -1;
			break;
		}
		s->stamp[s->n++] = t;
	}
	if (!rc && err->msg[0])
		rc = -1;
	fct_reader_close(&r);
	if (rc)
		stamped_free(s);
	return rc;
}

/* The index of the stamp of s nearest to t within max_diff, or -1. */
static long nearest(const struct stamped *s, double t, double max_diff)
{
	long best = -1;
	double bd = max_diff;
	for (size_t i = 0; i < s->n; i++) {
		double d = fabs(s->stamp[i] - t);
		if (d <= bd && (best < 0 || d < bd))
			best = (long)i, bd = d;
	}
	return best;
}

/* The freiburg camera a TUM folder's name tells (rgbd_dataset_freiburg1_desk). */
static const char *tum_camera(const char *dir)
{
	if (strstr(dir, "freiburg1"))
		return "tum1";
	if (strstr(dir, "freiburg2"))
		return "tum2";
	if (strstr(dir, "freiburg3"))
		return "tum3";
	return "tum";
}

static int read_tum(struct fct_dataset *ds, const char *dir, double max_diff, struct fct_err *err)
{
	struct stamped depth = { 0 }, rgb = { 0 };
	struct fct_trajectory tr = { 0 };
	size_t n = 0;
	char *gt = fct_path_join(dir, "groundtruth.txt", err), *dl = fct_path_join(dir, "depth.txt", err),
	     *rl = fct_path_join(dir, "rgb.txt", err);
	int rc = -1;
	ds->layout = "TUM", ds->camera = tum_camera(dir);
	if (!gt || !dl || !rl || read_stamped(&depth, dl, err) || read_stamped(&rgb, rl, err) ||
	    fct_trajectory_read(&tr, gt, err))
		goto out;
	if (tr.format != FCT_TRAJ_TUM || !tr.stamp) {
		fct_fail(err, "%s: not a TUM trajectory (%s)", gt, fct_traj_format_name(tr.format));
		goto out;
	}
	if (alloc_frames(ds, depth.n ? depth.n : 1, 1, err))
		goto out;
	for (size_t i = 0; i < depth.n; i++) {
		long c = nearest(&rgb, depth.stamp[i], max_diff);
		size_t pose;
		double d = fct_trajectory_associate(&pose, &tr, &depth.stamp[i], 1, max_diff);
		if (c < 0 || pose == (size_t)-1)
			continue;
		ds->max_diff = fmax(ds->max_diff, fmax(d, fabs(rgb.stamp[c] - depth.stamp[i])));
		if (!(ds->depth[n] = fct_path_join(dir, depth.file[i], err)) ||
		    !(ds->color[n] = fct_path_join(dir, rgb.file[c], err)))
			goto out;
		n++;
	}
	ds->n = n;
	if (!n) {
		fct_fail(err, "%s: no depth frame has a colour image and a pose within %g s", dir, max_diff);
		goto out;
	}
	ds->poses[0] = gt;
	gt = NULL;
	rc = 0;
out:
	free(gt), free(dl), free(rl);
	stamped_free(&depth);
	stamped_free(&rgb);
	fct_trajectory_free(&tr);
	return rc;
}

/* Redwood and Open3D's reconstruction system: depth/ and color/ (or image/
 * or rgb/) holding one image per frame, paired in the order of their
 * names, and the trajectory in a .log file. */
static int is_image_name(const char *name)
{
	const char *dot = strrchr(name, '.');
	return name[0] != '.' && dot &&
	       (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".jpeg"));
}

static int is_log_name(const char *name)
{
	return name[0] != '.' && ends_with(name, ".log");
}

static int is_dir(const char *path)
{
	struct stat sb;
	return stat(path, &sb) == 0 && S_ISDIR(sb.st_mode);
}

/* dir joined to the first of names that exists (test: exists or is_dir),
 * or NULL (err set only when out of memory). */
static char *first_of(const char *dir, const char *const *names, int (*test)(const char *),
                      struct fct_err *err)
{
	for (; *names; names++) {
		char *p = fct_path_join(dir, *names, err);
		if (!p || test(p))
			return p;
		free(p);
	}
	return NULL;
}

/* The folder's trajectory: trajectory.log or scene/trajectory.log (where
 * Open3D's reconstruction system writes it), else its one .log file. */
static char *redwood_trajectory(const char *dir, struct fct_err *err)
{
	static const char *const known[] = { "trajectory.log", "scene/trajectory.log", NULL };
	err->msg[0] = '\0';
	char *path = first_of(dir, known, exists, err);
	if (path || err->msg[0])
		return path;
	char **logs;
	size_t n;
	if (sorted_names(&logs, &n, dir, is_log_name, err))
		return NULL;
	if (n == 1)
		path = fct_path_join(dir, logs[0], err);
	else if (n == 0)
		fct_fail(err, "%s: no trajectory (trajectory.log, scene/trajectory.log or one .log file)", dir);
	else
		fct_fail(err, "%s: %zu .log files (%s, %s, ...): which is the trajectory? name it "
		         "trajectory.log", dir, n, logs[0], logs[1]);
	free_names(logs, n);
	return path;
}

static int read_redwood(struct fct_dataset *ds, const char *dir, const char *depth_dir,
                        struct fct_err *err)
{
	static const char *const colour_names[] = { "color", "image", "rgb" };
	static const char *const intrinsics[] = { "camera_intrinsic.json", NULL };
	char **depth = NULL, **colour = NULL, *colour_dir = NULL;
	size_t nd = 0, nc = 0, k;
	int rc = -1;
	ds->layout = "Redwood", ds->camera = "redwood";
	for (k = 0; k < 3 && !colour_dir; k++) {
		if (!(colour_dir = fct_path_join(dir, colour_names[k], err)))
			goto out;
		if (!is_dir(colour_dir)) {
			free(colour_dir);
			colour_dir = NULL;
		}
	}
	if (!colour_dir) {
		fct_fail(err, "%s: depth/ but no colour images beside it (color/, image/ or rgb/)", dir);
		goto out;
	}
	if (sorted_names(&depth, &nd, depth_dir, is_image_name, err) ||
	    sorted_names(&colour, &nc, colour_dir, is_image_name, err))
		goto out;
	if (nd == 0 || nd != nc) {
		fct_fail(err, "%s: %zu depth images in depth/ but %zu colour images in %s/ (a Redwood "
		         "folder pairs them in the order of their names)", dir, nd, nc, colour_names[k - 1]);
		goto out;
	}
	if (alloc_frames(ds, nd, 1, err))
		goto out;
	for (size_t i = 0; i < nd; i++)
		if (!(ds->depth[i] = fct_path_join(depth_dir, depth[i], err)) ||
		    !(ds->color[i] = fct_path_join(colour_dir, colour[i], err)))
			goto out;
	if (!(ds->poses[0] = redwood_trajectory(dir, err)))
		goto out;
	err->msg[0] = '\0';
	ds->intrinsics = first_of(dir, intrinsics, exists, err);
	rc = err->msg[0] ? -1 : 0;
out:
	free_names(depth, nd);
	free_names(colour, nc);
	free(colour_dir);
	return rc;
}

int fct_dataset_read(struct fct_dataset *ds, const char *dir, double max_diff, struct fct_err *err)
{
	memset(ds, 0, sizeof *ds);
	char **stems = NULL, *depth_dir = NULL;
	size_t n = 0;
	char *probe = fct_path_join(dir, "depth.txt", err);
	if (!probe || !(depth_dir = fct_path_join(dir, "depth", err))) {
		free(probe);
		return -1;
	}
	int rc;
	if (exists(probe))
		rc = read_tum(ds, dir, max_diff, err);
	else if (is_dir(depth_dir))
		rc = read_redwood(ds, dir, depth_dir, err);
	else if ((rc = seven_scenes_stems(&stems, &n, dir, err)) == 0) {
		rc = n ? read_seven_scenes(ds, dir, stems, n, err)
		       : fct_fail(err, "%s: not a 7-Scenes, TUM or Redwood sequence folder (no "
		                  "frame-*.depth.png, no depth.txt, no depth/)", dir);
		free_names(stems, n);
	}
	free(probe);
	free(depth_dir);
	if (rc)
		fct_dataset_free(ds);
	return rc;
}

void fct_dataset_free(struct fct_dataset *ds)
{
	for (size_t i = 0; i < ds->n; i++) {
		free(ds->depth ? ds->depth[i] : NULL);
		free(ds->color ? ds->color[i] : NULL);
	}
	for (size_t i = 0; ds->poses && i < ds->nposes; i++)
		free(ds->poses[i]);
	free(ds->depth), free(ds->color), free(ds->poses);
	free(ds->intrinsics);
	memset(ds, 0, sizeof *ds);
}

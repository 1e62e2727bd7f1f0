/* poses.c - camera trajectories and their frames (see poses.h). */
#include "io/poses.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/camera.h"
#include "core/numparse.h"
#include "io/reader.h"

const char *fct_traj_format_name(enum fct_traj_format f)
{
	switch (f) {
	case FCT_TRAJ_TUM: return "a TUM trajectory";
	case FCT_TRAJ_LOG: return "a Redwood .log trajectory";
	case FCT_TRAJ_KITTI: return "KITTI poses";
	case FCT_TRAJ_STACKED: return "stacked 4x4 matrices";
	case FCT_TRAJ_POSE: break;
	}
	return "a pose";
}

void fct_trajectory_free(struct fct_trajectory *tr)
{
	if (!tr)
		return;
	free(tr->pose);
	free(tr->stamp);
	memset(tr, 0, sizeof *tr);
}

/* The numbers of a file, line by line: line k (of those holding numbers)
 * is number[at[k] .. at[k] + count[k]) and came from line no[k]. */
struct numbers {
	double *v;
	size_t n, cap;
	size_t *at;
	long *no;
	unsigned char *count;
	size_t lines, at_cap, no_cap, count_cap;
};

static void numbers_free(struct numbers *s)
{
	free(s->v), free(s->at), free(s->no), free(s->count);
}

/* The most numbers a line of any of the formats holds. */
#define MAX_PER_LINE 16

/* Split one line into numbers.  Returns 1 for a line of numbers, 0 for a
 * blank or comment line, 2 when its first word is not a number (a pose
 * line, or not a pose file), -1 on error. */
static int parse_line(struct numbers *s, const char *path, long no, const char *line, size_t len,
                      struct fct_err *err)
{
	if (memchr(line, 0, len))
		return fct_fail(err, "%s:%ld: binary data (a NUL byte): not a pose file", path, no);
	const char *p = line;
	while (*p == ' ' || *p == '\t')
		p++;
	if (!*p || *p == '#')
		return 0;
	size_t first = s->n;
	for (int k = 0; *p; k++) {
		double x;
		const char *e = fct_parse_double(p, &x);
		if (!e || (*e && *e != ' ' && *e != '\t')) {
			if (k == 0)
				return 2;
			const char *w = p;
			while (*w && *w != ' ' && *w != '\t')
				w++;
			char q[64];
			return fct_fail(err, "%s:%ld: \"%s\": not a number", path, no,
			                fct_escape(q, sizeof q, p, (size_t)(w - p)));
		}
		if (!isfinite(x))
			return fct_fail(err, "%s:%ld: number %d is not finite", path, no, k + 1);
		if (k == MAX_PER_LINE)
			return fct_fail(err, "%s:%ld: more than %d numbers: not a pose file", path, no,
			                MAX_PER_LINE);
		if (fct_grow((void **)&s->v, &s->cap, s->n + 1, sizeof *s->v, err))
			return -1;
		s->v[s->n++] = x;
		p = e;
		while (*p == ' ' || *p == '\t')
			p++;
	}
	size_t l = s->lines;
	if (fct_grow((void **)&s->at, &s->at_cap, l + 1, sizeof *s->at, err) ||
	    fct_grow((void **)&s->no, &s->no_cap, l + 1, sizeof *s->no, err) ||
	    fct_grow((void **)&s->count, &s->count_cap, l + 1, sizeof *s->count, err))
		return -1;
	s->at[l] = first, s->no[l] = no, s->count[l] = (unsigned char)(s->n - first);
	s->lines++;
	return 1;
}

/* Read every line of path.  Returns 1 when the first line with a word is
 * not numbers, 0 when all are, -1 on error. */
static int read_numbers(struct numbers *s, const char *path, struct fct_err *err)
{
	memset(s, 0, sizeof *s);
	struct fct_reader r;
	if (fct_reader_open(&r, path, err))
		return -1;
	int rc = 0;
	char *line;
	size_t len;
	while ((line = fct_reader_line(&r, &len, err))) {
		int k = parse_line(s, path, (long)r.line, line, len, err);
		if (k < 0) {
			rc = -1;
			break;
		}
		if (k == 2) {
			if (s->lines == 0) {
				rc = 1;
			} else {
				char q[64];
				rc = fct_fail(err, "%s:%llu: \"%s\": not a number", path,
				              (unsigned long long)r.line, fct_escape(q, sizeof q, line, len));
			}
			break;
		}
	}
	if (!line && err->msg[0])
		rc = -1;
	fct_reader_close(&r);
	return rc;
}

/* Does every line hold `count` numbers? */
static int all_lines(const struct numbers *s, int count)
{
	for (size_t l = 0; l < s->lines; l++)
		if (s->count[l] != count)
			return 0;
	return 1;
}

/* Redwood .log: (3 integers, then 4 lines of 4) per pose. */
static int is_log(const struct numbers *s)
{
	if (s->lines == 0 || s->lines % 5)
		return 0;
	for (size_t l = 0; l < s->lines; l++) {
		if (s->count[l] != (l % 5 ? 4 : 3))
			return 0;
		if (l % 5 == 0)
			for (int k = 0; k < 3; k++) {
				double x = s->v[s->at[l] + k];
				if (x != floor(x))
					return 0;
			}
	}
	return 1;
}

static int add_pose(struct fct_trajectory *tr, size_t *cap, const double pose[12], struct fct_err *err)
{
	if (fct_grow((void **)&tr->pose, cap, 12 * (tr->n + 1), sizeof *tr->pose, err))
		return -1;
	memcpy(&tr->pose[12 * tr->n++], pose, 12 * sizeof *pose);
	return 0;
}

/* A 4x4 from 16 numbers (row-major): its last row must be 0 0 0 1. */
static int pose_4x4(double pose[12], const double *v, const char *path, long no, struct fct_err *err)
{
	if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
		return fct_fail(err, "%s:%ld: the last row of a 4x4 pose must be 0 0 0 1", path, no);
	memcpy(pose, v, 12 * sizeof *pose);
	return 0;
}

static int tum_pose(double pose[12], double *stamp, const double *v, const char *path, long no,
                    struct fct_err *err)
{
	double qn = sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
	if (!(fabs(qn - 1) < 1e-2))
		return fct_fail(err, "%s:%ld: not a unit quaternion (norm %g)", path, no, qn);
	fct_quat_pose(v[4] / qn, v[5] / qn, v[6] / qn, v[7] / qn, pose);
	pose[3] = v[1], pose[7] = v[2], pose[11] = v[3];
	*stamp = v[0];
	return 0;
}

/* The poses of s: one every `per` lines, its numbers (8: TUM, 12: a 3x4,
 * 16: a 4x4) from its line `skip` on. */
static int build(struct fct_trajectory *tr, const struct numbers *s, enum fct_traj_format f,
                 size_t per, size_t skip, const char *path, struct fct_err *err)
{
	size_t cap = 0, scap = 0;
	for (size_t l = 0; l + per <= s->lines; l += per) {
		const double *v = &s->v[s->at[l + skip]];
		size_t count = (l + per < s->lines ? s->at[l + per] : s->n) - s->at[l + skip];
		long no = s->no[l + skip];
		double pose[12], stamp = 0;
		if (count == 8 ? tum_pose(pose, &stamp, v, path, no, err)
		    : count == 16 ? pose_4x4(pose, v, path, no, err)
		    : (memcpy(pose, v, sizeof pose), 0))
			return -1;
		if (fct_pose_check(pose, 1e-3, err)) {
			fct_err_prefix(err, "%s:%ld", path, no);
			return -1;
		}
		if (f == FCT_TRAJ_TUM) {
			if (tr->n && stamp < tr->stamp[tr->n - 1])
				return fct_fail(err, "%s:%ld: timestamp %.17g before the line above's: a "
				                "trajectory goes forward in time", path, no, stamp);
			if (fct_grow((void **)&tr->stamp, &scap, tr->n + 1, sizeof *tr->stamp, err))
				return -1;
			tr->stamp[tr->n] = stamp;
		}
		if (add_pose(tr, &cap, pose, err))
			return -1;
	}
	return 0;
}

/* One pose in fct_pose_read_file's words (any layout of 12 or 16 numbers,
 * or a pose line) as a trajectory of one. */
static int read_one_pose(struct fct_trajectory *tr, const char *path, struct fct_err *err)
{
	double pose[12];
	size_t cap = 0;
	return fct_pose_read_file(path, pose, err) || add_pose(tr, &cap, pose, err) ? -1 : 0;
}

static int not_a_trajectory(const struct numbers *s, const char *path, struct fct_err *err)
{
	static const char formats[] = "TUM: 8 a line; KITTI: 12; Redwood .log: 3, then a 4x4 on 4 "
	                              "lines; 4x4 matrices";
	size_t l = 1;
	while (l < s->lines && s->count[l] == s->count[0])
		l++;
	if (l < s->lines)
		return fct_fail(err, "%s:%ld: %d numbers where line %ld has %d: not a trajectory (%s)",
		                path, s->no[l], s->count[l], s->no[0], s->count[0], formats);
	return fct_fail(err, "%s: %zu line%s of %d numbers: not a pose or trajectory (%s)", path,
	                s->lines, s->lines == 1 ? "" : "s", s->count[0], formats);
}

int fct_trajectory_read(struct fct_trajectory *tr, const char *path, struct fct_err *err)
{
	memset(tr, 0, sizeof *tr);
	struct numbers s;
	int k = read_numbers(&s, path, err), rc;
	if (k < 0) {
		rc = -1;
	} else if (k == 1) {
		rc = read_one_pose(tr, path, err);       /* "pose r11 ... t3" */
	} else if (s.lines == 0) {
		rc = fct_fail(err, "%s: no poses", path);
	} else if (all_lines(&s, 8)) {
		rc = build(tr, &s, FCT_TRAJ_TUM, 1, 0, path, err);
		tr->format = FCT_TRAJ_TUM;
	} else if (is_log(&s)) {
		rc = build(tr, &s, FCT_TRAJ_LOG, 5, 1, path, err);
		tr->format = FCT_TRAJ_LOG;
	} else if (all_lines(&s, 12) || all_lines(&s, 16)) {
		rc = build(tr, &s, FCT_TRAJ_KITTI, 1, 0, path, err);
		tr->format = s.count[0] == 12 ? FCT_TRAJ_KITTI : FCT_TRAJ_STACKED;
	} else if (all_lines(&s, 4) && s.lines % 4 == 0) {
		rc = build(tr, &s, FCT_TRAJ_STACKED, 4, 0, path, err);
		tr->format = FCT_TRAJ_STACKED;
	} else if (s.n == 12 || s.n == 16) {
		rc = read_one_pose(tr, path, err);       /* one matrix in another layout */
	} else {
		rc = not_a_trajectory(&s, path, err);
	}
	if (!rc && tr->n == 1 && tr->format != FCT_TRAJ_TUM && tr->format != FCT_TRAJ_LOG)
		tr->format = FCT_TRAJ_POSE;
	numbers_free(&s);
	if (rc)
		fct_trajectory_free(tr);
	return rc;
}

int fct_path_stamp(const char *path, double *stamp)
{
	const char *base = strrchr(path, '/');
	base = base ? base + 1 : path;
	if (*base < '0' || *base > '9')
		return 0;
	double x;
	const char *end = fct_parse_double(base, &x);
	/* "1305031105.png": the number takes the dot before the extension */
	if (end && end[-1] == '.')
		end--;
	if (!end || *end != '.' || !end[1] || (end[1] >= '0' && end[1] <= '9') || !isfinite(x))
		return 0;
	*stamp = x;
	return 1;
}

int fct_path_frame_number(const char *path, size_t *number)
{
	const char *base = strrchr(path, '/');
	base = base ? base + 1 : path;
	const char *last = NULL;
	for (const char *p = base; *p; p++)
		if (*p >= '0' && *p <= '9' && (p == base || p[-1] < '0' || p[-1] > '9'))
			last = p;
	if (!last)
		return 0;
	uint64_t k = 0;
	for (const char *p = last; *p >= '0' && *p <= '9'; p++) {
		k = 10 * k + (uint64_t)(*p - '0');
		if (k > ((uint64_t)1 << 53))
			return 0;
	}
	*number = (size_t)k;
	return 1;
}

/* The first pose whose stamp is at least t (tr->n when none). */
static size_t first_at_least(const struct fct_trajectory *tr, double t)
{
	size_t lo = 0, hi = tr->n;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (tr->stamp[mid] < t)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

/* The pose nearest t in time (the earlier line on a tie); *diff its
 * distance.  tr->n > 0. */
static size_t nearest(const struct fct_trajectory *tr, double t, double *diff)
{
	size_t j = first_at_least(tr, t);
	if (j == tr->n || (j > 0 && t - tr->stamp[j - 1] <= tr->stamp[j] - t))
		j = first_at_least(tr, tr->stamp[j - 1]);
	*diff = fabs(tr->stamp[j] - t);
	return j;
}

double fct_trajectory_associate(size_t *index, const struct fct_trajectory *tr,
                                const double *stamps, size_t n, double max_diff)
{
	double most = 0;
	for (size_t i = 0; i < n; i++) {
		double d;
		index[i] = (size_t)-1;
		if (!tr->stamp || tr->n == 0)
			continue;
		size_t j = nearest(tr, stamps[i], &d);
		if (d < max_diff) {
			index[i] = j;
			most = d > most ? d : most;
		}
	}
	return most;
}

/* One pose per file, in the frames' order. */
static int poses_per_file(double *poses, struct fct_frame_poses_stats *st,
                          const char *const *files, size_t nfiles, size_t nframes,
                          struct fct_err *err)
{
	if (nfiles != nframes)
		return fct_fail(err, "%zu depth frames but %zu pose files (give one per frame, or one "
		                "trajectory)", nframes, nfiles);
	for (size_t i = 0; i < nfiles; i++) {
		struct fct_trajectory tr;
		if (fct_trajectory_read(&tr, files[i], err))
			return -1;
		if (tr.n != 1) {
			fct_fail(err, "%s holds %zu poses (%s): with a pose file per frame each holds one",
			         files[i], tr.n, fct_traj_format_name(tr.format));
			fct_trajectory_free(&tr);
			return -1;
		}
		memcpy(&poses[12 * i], tr.pose, 12 * sizeof *poses);
		fct_trajectory_free(&tr);
	}
	st->format = FCT_TRAJ_POSE;
	st->poses = nfiles;
	st->match = FCT_MATCH_FILES;
	return 0;
}

/* Frames named by their timestamps, matched in a TUM trajectory; 1 when
 * no frame's name has a timestamp (so the caller goes by order). */
static int match_stamps(size_t *index, struct fct_frame_poses_stats *st,
                        const struct fct_trajectory *tr, const char *file,
                        const char *const *frames, size_t nframes, double max_diff,
                        struct fct_err *err)
{
	size_t stamped = 0;
	for (size_t i = 0; i < nframes; i++) {
		double t;
		stamped += (size_t)fct_path_stamp(frames[i], &t);
	}
	if (stamped == 0)
		return 1;
	for (size_t i = 0; i < nframes; i++) {
		double t, d;
		if (!fct_path_stamp(frames[i], &t))
			return fct_fail(err, "%s: no timestamp in its name to find its pose in %s by "
			                "(as TUM's depth/1305031102.160407.png)", frames[i], file);
		d = fct_trajectory_associate(&index[i], tr, &t, 1, max_diff);
		st->max_diff = d > st->max_diff ? d : st->max_diff;
		if (index[i] == (size_t)-1) {
			nearest(tr, t, &d);
			return fct_fail(err, "%s: no pose in %s within %g s of its timestamp %.6f (the "
			                "nearest is %.3g s away)", frames[i], file, max_diff, t, d);
		}
	}
	st->match = FCT_MATCH_STAMP;
	return 0;
}

/* Frames named by their numbers, in a trajectory of more poses. */
static int match_numbers(size_t *index, struct fct_frame_poses_stats *st,
                         const struct fct_trajectory *tr, const char *file,
                         const char *const *frames, size_t nframes, struct fct_err *err)
{
	for (size_t i = 0; i < nframes; i++) {
		size_t k;
		if (!fct_path_frame_number(frames[i], &k))
			return fct_fail(err, "%zu depth frame%s but %s holds %zu poses (%s), and %s has no "
			                "frame number in its name to pick its pose by", nframes,
			                nframes == 1 ? "" : "s", file, tr->n,
			                fct_traj_format_name(tr->format), frames[i]);
		if (k >= tr->n)
			return fct_fail(err, "%s: frame %zu, but %s holds %zu poses (%s)", frames[i], k,
			                file, tr->n, fct_traj_format_name(tr->format));
		index[i] = k;
	}
	st->match = FCT_MATCH_NUMBER;
	return 0;
}

int fct_frame_poses(double *poses, struct fct_frame_poses_stats *stats,
                    const char *const *files, size_t nfiles,
                    const char *const *frames, size_t nframes, double max_diff,
                    struct fct_err *err)
{
	struct fct_frame_poses_stats st0, *st = stats ? stats : &st0;
	memset(st, 0, sizeof *st);
	if (nfiles == 0)
		return fct_fail(err, "no pose files");
	if (nfiles > 1 || nframes == 0)
		return poses_per_file(poses, st, files, nfiles, nframes, err);
	struct fct_trajectory tr;
	if (fct_trajectory_read(&tr, files[0], err))
		return -1;
	st->format = tr.format;
	st->poses = tr.n;
	size_t *index = fct_alloc_array(nframes, sizeof *index, err);
	int rc = index ? 1 : -1;
	if (rc > 0 && tr.format == FCT_TRAJ_TUM)
		rc = match_stamps(index, st, &tr, files[0], frames, nframes, max_diff, err);
	if (rc > 0 && tr.n == nframes) {
		for (size_t i = 0; i < nframes; i++)
			index[i] = i;
		st->match = FCT_MATCH_ORDER;
		rc = 0;
	}
	if (rc > 0 && tr.n > nframes && tr.format != FCT_TRAJ_TUM)
		rc = match_numbers(index, st, &tr, files[0], frames, nframes, err);
	if (rc > 0)
		rc = fct_fail(err, "%zu depth frame%s but %s holds %zu pose%s (%s)%s", nframes,
		              nframes == 1 ? "" : "s", files[0], tr.n, tr.n == 1 ? "" : "s",
		              fct_traj_format_name(tr.format),
		              tr.format == FCT_TRAJ_TUM ? ", and the frames' names carry no timestamps "
		              "to match them by (as TUM's depth/1305031102.160407.png)" : "");
	if (rc == 0)
		for (size_t i = 0; i < nframes; i++)
			memcpy(&poses[12 * i], &tr.pose[12 * index[i]], 12 * sizeof *poses);
	free(index);
	fct_trajectory_free(&tr);
	return rc ? -1 : 0;
}

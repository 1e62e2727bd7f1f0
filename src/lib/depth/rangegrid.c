/* rangegrid.c - Stanford .conf files and range_grid scans (see rangegrid.h). */
#include "depth/rangegrid.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "depth/depthmesh.h"
#include "geom/geom.h"
#include "core/path.h"
#include "io/reader.h"

void fct_conf_free(struct fct_conf *c)
{
	if (!c)
		return;
	for (size_t i = 0; i < c->n; i++)
		free(c->scans[i].path);
	for (size_t i = 0; i < c->nskipped; i++)
		free(c->skipped[i].text);
	free(c->scans);
	free(c->skipped);
	memset(c, 0, sizeof *c);
}

#define CONF_MAX (1L << 20)
#define CONF_LINE 4096

/* Keep line no (len bytes) among the skipped ones. */
static int conf_skip(struct fct_conf *c, size_t *cap, long no, const char *line, size_t len,
                     struct fct_err *err)
{
	char q[80];
	if (fct_grow((void **)&c->skipped, cap, c->nskipped + 1, sizeof *c->skipped, err))
		return -1;
	struct fct_conf_skip *k = &c->skipped[c->nskipped];
	if (!(k->text = fct_strdup(fct_escape(q, sizeof q, line, len), err)))
		return -1;
	k->line = no;
	c->nskipped++;
	return 0;
}

/* One line of a .conf: 0 (a scan added or the line skipped) or -1. */
static int conf_line(struct fct_conf *c, size_t *cap, size_t *skip_cap, const char *dir,
                     const char *path, long no, const char *line, size_t len, struct fct_err *err)
{
	char kw[32], name[CONF_LINE], q[64];
	double v[7];
	char extra[2];
	if (memchr(line, 0, len))
		return fct_fail(err, "%s:%ld: binary data (a NUL byte): not a .conf file", path, no);
	if (len >= CONF_LINE)
		return fct_fail(err, "%s:%ld: line too long (%zu bytes): not a .conf file", path, no, len);
	int n = sscanf(line, "%31s %4095s %lf %lf %lf %lf %lf %lf %lf %1s", kw, name,
	               &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], extra);
	if (n <= 0 || kw[0] == '#' || !strcmp(kw, "camera"))
		return 0;
	if (!strcmp(kw, "mesh"))
		return conf_skip(c, skip_cap, no, line, len, err);
	if (strcmp(kw, "bmesh"))
		return fct_fail(err, "%s:%ld: \"%s\": expected camera, bmesh or mesh", path, no,
		                fct_escape(q, sizeof q, kw, strlen(kw)));
	if (n != 9)
		return fct_fail(err, "%s:%ld: expected bmesh FILE tx ty tz qx qy qz qw", path, no);
	int finite = 1;
	for (int k = 0; k < 7; k++)
		finite &= isfinite(v[k]);
	double qn = sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
	if (!finite || !(fabs(qn - 1) <= 1e-3))
		return fct_fail(err, "%s:%ld: the quaternion is not a unit quaternion (norm %g)", path, no, qn);
	if (fct_grow((void **)&c->scans, cap, c->n + 1, sizeof *c->scans, err))
		return -1;
	struct fct_conf_scan *s = &c->scans[c->n];
	if (!(s->path = fct_path_join(dir, name, err)))
		return -1;
	c->n++;
	s->line = no;
	/* The scanalyze/VRIP quaternion is applied conjugated (checked on
	 * the bunny: the other way round puts bun045 40 mm off). */
	fct_quat_pose(-v[3] / qn, -v[4] / qn, -v[5] / qn, v[6] / qn, s->pose);
	s->pose[3] = v[0], s->pose[7] = v[1], s->pose[11] = v[2];
	return 0;
}

int fct_conf_read(struct fct_conf *c, const char *path, struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	size_t cap = 0, skip_cap = 0;
	FILE *f = fopen(path, "rb");
	if (!f)
		return fct_fail(err, "%s: %s", path, strerror(errno));
	char *dir = fct_path_dir(path, err);
	struct fct_reader r;
	if (!dir || fct_reader_init(&r, f, path, err)) {
		free(dir);
		fclose(f);
		return -1;
	}
	int rc = 0;
	char *line;
	size_t len;
	/* lines are read whole (up to the reader's 16 MB) before their length
	 * is judged: an endless line, as /dev/zero, ends there */
	while (!rc && (line = fct_reader_line(&r, &len, err))) {
		if (fct_reader_offset(&r) > CONF_MAX)
			rc = fct_fail(err, "%s:%llu: longer than %ld bytes: not a .conf file", path,
			              (unsigned long long)r.line, CONF_MAX);
		else
			rc = conf_line(c, &cap, &skip_cap, dir, path, (long)r.line, line, len, err);
	}
	if (!rc && err->msg[0])
		rc = -1;
	if (!rc && c->n == 0)
		rc = c->nskipped ? fct_fail(err, "%s: no bmesh line, only mesh lines, which are not fused "
		                            "(as vrip fuses bmesh lines only)", path)
		                 : fct_fail(err, "%s: no bmesh line: not a .conf file", path);
	fct_reader_free(&r);
	fclose(f);
	free(dir);
	if (rc)
		fct_conf_free(c);
	return rc;
}

/* obj_info NAME VALUE as a positive integer, or -1. */
static long obj_info_long(const struct fct_mesh *m, const char *name)
{
	size_t n = strlen(name);
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *t = m->comments[i].text;
		if (m->comments[i].obj_info && !strncmp(t, name, n) && (t[n] == ' ' || t[n] == '\t')) {
			char *end;
			long v = strtol(t + n, &end, 10);
			return v > 0 ? v : -1;
		}
	}
	return -1;
}

/* Depth along the scanner's ray is D0 - z: an offset large against the scan
 * so that the relative jump test of gridmesh.h becomes an absolute one in z
 * with footprint step / D0. */
#define DEPTH_OFFSET 1e4

int fct_range_grid_mesh(struct fct_mesh *out, const struct fct_mesh *m,
                        const struct fct_grid_params *p, double *step, struct fct_err *err)
{
	static const struct fct_grid_params defaults = { FCT_RANGE_GRID_MAX_JUMP, FCT_DEFAULT_MIN_FACES };
	fct_mesh_init(out);
	if (!p)
		p = &defaults;
	const struct fct_elem *e = fct_mesh_find_elem(m, "range_grid");
	const struct fct_prop *ix = e ? fct_elem_find(e, "vertex_indices") : NULL;
	if (!e || !ix || ix->count_type == FCT_NONE)
		return fct_fail(err, "no range_grid element with a vertex_indices list");
	if (m->nf)
		return fct_fail(err, "a range_grid element beside %zu faces: already meshed", m->nf);
	long w = obj_info_long(m, "num_cols"), h = obj_info_long(m, "num_rows");
	if (w < 1 || h < 1)
		return fct_fail(err, "range_grid without obj_info num_cols and num_rows");
	if ((size_t)w * (size_t)h != e->count)
		return fct_fail(err, "range_grid has %zu cells, num_cols * num_rows = %ld", e->count, w * h);
	size_t nc = e->count;
	double *xyz = fct_alloc_array(nc, 3 * sizeof *xyz, err);
	double *depth = fct_alloc_array(nc, sizeof *depth, err);
	double *gaps = fct_alloc_array(nc, sizeof *gaps, err);
	size_t *vert = fct_alloc_array(nc, sizeof *vert, err);
	uint32_t *cell_of = NULL;
	struct fct_mesh grid;
	fct_mesh_init(&grid);
	int rc = -1;
	if (!xyz || !depth || !gaps || !vert)
		goto done;
	for (size_t c = 0; c < nc; c++) {
		size_t k = ix->off[c + 1] - ix->off[c];
		depth[c] = 0;
		vert[c] = 0;
		xyz[3 * c] = xyz[3 * c + 1] = xyz[3 * c + 2] = 0;
		if (k == 0)
			continue;
		double v = fct_prop_get(ix, ix->off[c]);
		if (k > 1 || !(v >= 0 && v < (double)m->nv)) {
			fct_fail(err, "range_grid cell %zu: %s", c,
			         k > 1 ? "more than one vertex" : "vertex index out of range");
			goto done;
		}
		vert[c] = (size_t)v;
		const double *q = &m->xyz[3 * (size_t)v];
		if (!(isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2])))
			continue;
		memcpy(&xyz[3 * c], q, 3 * sizeof *q);
		depth[c] = DEPTH_OFFSET - q[2];
	}
	/* The grid step: the median distance between neighbouring cells. */
	size_t ng = 0;
	for (size_t c = 0; c < nc; c++) {
		size_t i = c % (size_t)w;
		if (!(depth[c] > 0))
			continue;
		if (i + 1 < (size_t)w && depth[c + 1] > 0)
			gaps[ng++] = sqrt(fct_v3_dist2(&xyz[3 * c], &xyz[3 * c + 3]));
		else if (c + (size_t)w < nc && depth[c + (size_t)w] > 0)
			gaps[ng++] = sqrt(fct_v3_dist2(&xyz[3 * c], &xyz[3 * (c + (size_t)w)]));
	}
	if (ng == 0) {
		fct_fail(err, "range_grid: no two neighbouring cells with data");
		goto done;
	}
	qsort(gaps, ng, sizeof *gaps, fct_cmp_double);
	double st = gaps[ng / 2];
	if (step)
		*step = st;
	struct fct_range_grid g = { (int)w, (int)h, xyz, NULL, NULL, depth, st / DEPTH_OFFSET, 0, NULL, 0 };
	if (fct_grid_mesh(&grid, &g, p, &cell_of, NULL, err))
		goto done;
	/* The scan's own vertices, in the order of the grid's, with all their
	 * properties; every other element and comment but range_grid. */
	for (size_t v = 0; v < grid.nv; v++)
		vert[v] = vert[cell_of[v]];     /* cell_of[v] >= v: read before written */
	if (fct_mesh_copy(out, m, err))
		goto done;
	fct_mesh_remove_elem(out, "range_grid");
	if (fct_mesh_gather_vertices(out, vert, grid.nv, err) ||
	    fct_mesh_set_triangle_count(out, grid.nf, err))
		goto done;
	/* Orient towards the scanner at +z. */
	double nz = 0;
	for (size_t f = 0; f < grid.nf; f++) {
		const uint32_t *t = &grid.fvert[grid.fstart[f]];
		double a[3], b[3], n[3];
		fct_v3_sub(a, &grid.xyz[3 * t[1]], &grid.xyz[3 * t[0]]);
		fct_v3_sub(b, &grid.xyz[3 * t[2]], &grid.xyz[3 * t[0]]);
		fct_v3_cross(n, a, b);
		nz += n[2];
	}
	for (size_t f = 0; f < grid.nf; f++) {
		const uint32_t *t = &grid.fvert[grid.fstart[f]];
		uint32_t *o = &out->fvert[3 * f];
		o[0] = t[0];
		o[1] = nz < 0 ? t[2] : t[1];
		o[2] = nz < 0 ? t[1] : t[2];
	}
	rc = 0;
done:
	free(xyz);
	free(depth);
	free(gaps);
	free(vert);
	free(cell_of);
	fct_mesh_free(&grid);
	if (rc)
		fct_mesh_free(out);
	return rc;
}

/* sparsemesh.c - sparse points with image coordinates to a mesh (see
 * sparsemesh.h). */
#include "depth/sparsemesh.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/delaunay.h"
#include "geom/geom.h"
#include "depth/gridmesh.h"
#include "core/numparse.h"
#include "core/path.h"
#include "io/ply.h"
#include "io/reader.h"

void fct_image_points_free(struct fct_image_points *pts)
{
	free(pts->uv);
	free(pts->xyz);
	memset(pts, 0, sizeof *pts);
}

static int points_from_ply(struct fct_image_points *pts, struct fct_reader *r, struct fct_err *err)
{
	struct fct_mesh m;
	fct_mesh_init(&m);
	if (fct_ply_read(&m, r, NULL, err))
		return -1;
	const struct fct_prop *u = fct_elem_find(&m.vertex, "u"), *v = fct_elem_find(&m.vertex, "v");
	int rc = -1;
	if (!u || !v || u->count_type != FCT_NONE || v->count_type != FCT_NONE) {
		fct_fail(err, "%s: the vertex element needs scalar properties u and v (image coordinates)",
		         r->name);
		goto out;
	}
	if (!(pts->uv = fct_alloc_array(m.nv, 2 * sizeof *pts->uv, err)) ||
	    !(pts->xyz = fct_alloc_array(m.nv, 3 * sizeof *pts->xyz, err)))
		goto out;
	for (size_t i = 0; i < m.nv; i++) {
		pts->uv[2 * i] = fct_prop_get(u, i);
		pts->uv[2 * i + 1] = fct_prop_get(v, i);
	}
	memcpy(pts->xyz, m.xyz, m.nv * 3 * sizeof *pts->xyz);
	pts->n = m.nv;
	rc = 0;
out:
	fct_mesh_free(&m);
	return rc;
}

static int points_from_text(struct fct_image_points *pts, struct fct_reader *r, struct fct_err *err)
{
	size_t cap_uv = 0, cap_xyz = 0, len;
	char *line;
	err->msg[0] = 0;
	while ((line = fct_reader_line(r, &len, err))) {
		const char *s = line;
		while (*s == ' ' || *s == '\t')
			s++;
		if (!*s || *s == '#')
			continue;
		double v[5];
		for (int k = 0; k < 5; k++) {
			const char *e = fct_parse_double(s, &v[k]);
			if (!e || (*e && *e != ' ' && *e != '\t'))
				return fct_fail(err, "%s:%llu: expected five numbers \"u v x y z\"", r->name,
				                (unsigned long long)r->line);
			s = e;
			while (*s == ' ' || *s == '\t')
				s++;
		}
		if (*s)
			return fct_fail(err, "%s:%llu: more than five numbers", r->name,
			                (unsigned long long)r->line);
		if (fct_grow((void **)&pts->uv, &cap_uv, 2 * (pts->n + 1), sizeof *pts->uv, err) ||
		    fct_grow((void **)&pts->xyz, &cap_xyz, 3 * (pts->n + 1), sizeof *pts->xyz, err))
			return -1;
		memcpy(pts->uv + 2 * pts->n, v, 2 * sizeof *v);
		memcpy(pts->xyz + 3 * pts->n, v + 2, 3 * sizeof *v);
		pts->n++;
	}
	return err->msg[0] ? -1 : 0;
}

int fct_image_points_read_stream(struct fct_image_points *pts, FILE *f, const char *name,
                                 struct fct_err *err)
{
	memset(pts, 0, sizeof *pts);
	struct fct_reader r;
	if (fct_reader_init(&r, f, name, err))
		return -1;
	int rc = fct_ply_detect(&r) ? points_from_ply(pts, &r, err) : points_from_text(pts, &r, err);
	fct_reader_free(&r);
	for (size_t i = 0; !rc && i < pts->n; i++)
		for (int k = 0; k < 5; k++)
			if (!isfinite(k < 2 ? pts->uv[2 * i + k] : pts->xyz[3 * i + k - 2]))
				rc = fct_fail(err, "%s: point %zu: not finite", name, i);
	if (!rc && pts->n == 0)
		rc = fct_fail(err, "%s: no points", name);
	if (rc)
		fct_image_points_free(pts);
	return rc;
}

int fct_image_points_read_file(struct fct_image_points *pts, const char *path, struct fct_err *err)
{
	memset(pts, 0, sizeof *pts);
	if (fct_path_is_std(path))
		return fct_image_points_read_stream(pts, stdin, "<stdin>", err);
	FILE *f = fopen(path, "rb");
	if (!f)
		return fct_fail(err, "%s: %s", path, strerror(errno));
	int rc = fct_image_points_read_stream(pts, f, path, err);
	fclose(f);
	return rc;
}

/* Depth along the camera's ray (what the footprint scales with). */
static double point_depth(const struct fct_camera *cam, const double p[3])
{
	return cam->kind == FCT_CAMERA_CYLINDRICAL ? hypot(p[0], p[2]) : p[2];
}

/* The edge a-b is one surface: its depth change is within max_jump times the
 * footprint of its image length at the nearer depth. */
static int edge_joined(const struct fct_image_points *pts, const struct fct_camera *cam,
                       double limit, uint32_t a, uint32_t b)
{
	double da = point_depth(cam, &pts->xyz[3 * a]), db = point_depth(cam, &pts->xyz[3 * b]);
	if (!(da > 0 && db > 0))
		return 0;
	double du = pts->uv[2 * a] - pts->uv[2 * b], dv = pts->uv[2 * a + 1] - pts->uv[2 * b + 1];
	if (cam->kind == FCT_CAMERA_CYLINDRICAL && fabs(du) > cam->width / 2.0)
		du = cam->width - fabs(du);
	return fct_depth_joined(da, db, limit, hypot(du, dv), 0);
}

int fct_sparse_mesh(struct fct_mesh *m, const struct fct_image_points *pts,
                    const struct fct_camera *cam, const struct fct_sparse_params *p,
                    struct fct_sparse_stats *stats, struct fct_err *err)
{
	struct fct_sparse_stats st = { 0, 0, 0 };
	uint32_t *tri = NULL;
	size_t ntri = 0;
	fct_mesh_init(m);
	if (pts->n > UINT32_MAX)
		return fct_fail(err, "%zu points are more than 2^32", pts->n);
	if (fct_delaunay(&tri, &ntri, &st.duplicates, pts->uv, pts->n, err))
		return -1;
	double limit = p->max_jump * fct_camera_pixel_angle(cam);
	double max_e2 = p->max_edge * p->max_edge;
	size_t nf = 0;
	for (size_t f = 0; f < ntri; f++) {
		uint32_t *t = &tri[3 * f];
		int ok = 1;
		for (int k = 0; k < 3 && ok; k++)
			if (limit > 0 && !edge_joined(pts, cam, limit, t[k], t[(k + 1) % 3])) {
				st.jump_faces++;
				ok = 0;
			}
		for (int k = 0; k < 3 && ok; k++)
			if (fct_v3_dist2(&pts->xyz[3 * t[k]], &pts->xyz[3 * t[(k + 1) % 3]]) > max_e2) {
				st.long_faces++;
				ok = 0;
			}
		if (ok) {
			/* Delaunay triangles turn counter-clockwise in (u, v); with v
			 * down that faces away from the camera, so swap two corners. */
			uint32_t a = t[0], b = t[1], c = t[2];
			tri[3 * nf] = a, tri[3 * nf + 1] = c, tri[3 * nf + 2] = b;
			nf++;
		}
	}
	int rc = -1;
	if (fct_mesh_set_vertex_count(m, pts->n, err) || fct_mesh_set_triangle_count(m, nf, err))
		goto out;
	memcpy(m->xyz, pts->xyz, pts->n * 3 * sizeof *m->xyz);
	if (nf)
		memcpy(m->fvert, tri, nf * 3 * sizeof *tri);
	if (cam->kind != FCT_CAMERA_NONE && cam->width > 0 && cam->height > 0) {
		if (!fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, err) ||
		    !fct_elem_add_scalar(&m->vertex, "t", FCT_FLOAT32, err))
			goto out;
		float *s = fct_elem_find(&m->vertex, "s")->data, *t = fct_elem_find(&m->vertex, "t")->data;
		for (size_t i = 0; i < pts->n; i++) {
			s[i] = (float)((pts->uv[2 * i] + 0.5) / cam->width);
			t[i] = (float)(1 - (pts->uv[2 * i + 1] + 0.5) / cam->height);
		}
	}
	rc = 0;
	if (stats)
		*stats = st;
out:
	free(tri);
	if (rc)
		fct_mesh_free(m);
	return rc;
}

/* test_planemodel - fct_planes_meet tearing a vertex off a plane with a
 * viewpoint and not without; fct_planes_project at a crease seen at a grazing angle,
 * a crease move beyond its bound in sigma, one that would hide its sample
 * (an occlusion), and a floor vertex alone whose ray meets a wall first;
 * fct_planes_meet's copy of a vertex for a plane before it along its ray,
 * all the way when a plane behind holds the vertex, 4 sigma beside the
 * free-form surface;
 * fct_patches_tidy's specks near and far from the plane around them; fct_patches_unfacet on a patch ringed by four patches
 * at shallow creases, of about its size (a facet) and much smaller (a floor
 * with tilted pieces beside it); fct_fill_plane_holes on a flat grid with
 * missing vertices, as missing depth pixels leave them: one hole, two holes that
 * touch at a corner (which a walk that gives up at a shared vertex leaves
 * open), holes too long for max_edges, a hole along two patches, and a
 * piece's outer boundary, which is no hole; fct_fill_free_holes on the
 * same holes of the free-form surface and between two patches.  Each fill is checked by what
 * it must give: the square's whole area back, its four sides as the only
 * border, every new triangle turned as the faces around it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/adj.h"
#include "planar/planemodel.h"
#include "square.h"

#define N 8 /* cells a side of the square [-1,1]^2 at z = 1 (square.h: faces turned to -z) */

static uint32_t vertex_at(int i, int j)
{
	return (uint32_t)(j * (N + 1) + i);
}

/* The square with every face through the listed vertices removed. */
static void square_without(struct fct_mesh *m, const uint32_t *gone, size_t ngone)
{
	struct fct_err err;
	square(m, N, 1);
	size_t *keep = malloc(m->nf * sizeof *keep), n = 0;
	for (size_t f = 0; f < m->nf; f++) {
		int hit = 0;
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++)
			for (size_t g = 0; g < ngone; g++)
				hit |= m->fvert[c] == gone[g];
		if (!hit)
			keep[n++] = f;
	}
	CHECK_INT(fct_mesh_gather_faces(m, keep, n, &err), 0);
	free(keep);
}

/* The faces' total area and the count of those turned towards +z. */
static double area(const struct fct_mesh *m, size_t *up)
{
	double sum = 0;
	*up = 0;
	for (size_t f = 0; f < m->nf; f++) {
		const double *a = m->xyz + 3 * (size_t)m->fvert[m->fstart[f]];
		const double *b = m->xyz + 3 * (size_t)m->fvert[m->fstart[f] + 1];
		const double *c = m->xyz + 3 * (size_t)m->fvert[m->fstart[f] + 2];
		double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
		sum += fabs(z) / 2;
		*up += z > 0;
	}
	return sum;
}

static size_t border_edges(const struct fct_mesh *m)
{
	struct fct_adj adj;
	struct fct_err err;
	if (fct_adj_build(&adj, m, &err))
		return SIZE_MAX;
	size_t n = adj.nborder;
	fct_adj_free(&adj);
	return n;
}

/* The labels of fill's square: every face in patch 0, split at x = 0 into
 * patches 0 and 1, or every face free-form. */
enum labels { ONE_PATCH, TWO_PATCHES, ALL_FREE };

/* Fill the holes of the square without gone[] labelled as lab says, the
 * plane z = 1 facing -z as the faces do: fct_fill_plane_holes, or
 * fct_fill_free_holes (every sigma 0.01, within 4 of them) when free_holes,
 * with the vertices at x > 0 moved by step along z.  The holes filled; the
 * area, border and turned-over faces after, and the faces and free-form
 * faces. */
static size_t fill_as(const uint32_t *gone, size_t ngone, size_t max_edges, enum labels lab,
                      int free_holes, double step, double *a, size_t *border, size_t *up,
                      size_t *faces, size_t *free_faces)
{
	struct fct_mesh m;
	struct fct_err err;
	square_without(&m, gone, ngone);
	double *sigma = malloc(m.nv * sizeof *sigma);
	for (size_t v = 0; v < m.nv; v++) {
		sigma[v] = 0.01;
		if (m.xyz[3 * v] > 1e-9)
			m.xyz[3 * v + 2] += step;
	}
	int32_t *patch = malloc((m.nf ? m.nf : 1) * sizeof *patch);
	for (size_t f = 0; f < m.nf; f++) {
		const double *p = m.xyz + 3 * (size_t)m.fvert[m.fstart[f]];
		patch[f] = lab == ALL_FREE ? -1 : lab == TWO_PATCHES && p[0] >= -1e-9 ? 1 : 0;
	}
	struct fct_plane pl[2] = { { { 0, 0, -1 }, 1, 0, 0 }, { { 0, 0, -1 }, 1, 0, 0 } };
	size_t filled = 99;
	if (free_holes)
		CHECK_INT(fct_fill_free_holes(&m, &patch, pl, 2, max_edges, sigma, 4, &filled, &err), 0);
	else
		CHECK_INT(fct_fill_plane_holes(&m, &patch, pl, 2, max_edges, &filled, &err), 0);
	*faces = m.nf, *free_faces = 0;
	for (size_t f = 0; f < m.nf; f++) {
		CHECK(patch[f] >= -1 && patch[f] <= 1);
		*free_faces += patch[f] == -1;
	}
	*a = area(&m, up);
	*border = border_edges(&m);
	free(patch), free(sigma);
	fct_mesh_free(&m);
	return filled;
}

static size_t fill(const uint32_t *gone, size_t ngone, size_t max_edges, int two_patches, double *a,
                   size_t *border, size_t *up)
{
	size_t faces, free_faces;
	return fill_as(gone, ngone, max_edges, two_patches ? TWO_PATCHES : ONE_PATCH, 0, 0, a, border,
	               up, &faces, &free_faces);
}

/* fct_patches_unfacet on an n x n square whose cells [a,b)^2 are patch 0
 * (plane z = 1) and the rest four bands, left, right, above and below it
 * (patches 1-4), each tilted tilt degrees against it about its own axis.
 * Whether patch 0 became free-form; *facets gets the count. */
static int centre_unfaceted(int n, int a, int b, double tilt, size_t *facets)
{
	struct fct_mesh m;
	struct fct_err err;
	square(&m, n, 1);
	int32_t *patch = malloc(m.nf * sizeof *patch);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++) {
			int32_t l = i < a ? 1 : i >= b ? 2 : j < a ? 3 : j >= b ? 4 : 0;
			patch[2 * (j * n + i)] = patch[2 * (j * n + i) + 1] = l;
		}
	double t = tilt * M_PI / 180, c = cos(t), s = sin(t);
	struct fct_plane pl[5] = {
		{ { 0, 0, -1 }, 1, 0, 0 }, { { -s, 0, -c }, 1, 0, 0 }, { { s, 0, -c }, 1, 0, 0 },
		{ { 0, -s, -c }, 1, 0, 0 }, { { 0, s, -c }, 1, 0, 0 },
	};
	struct fct_adj adj;
	CHECK_INT(fct_adj_build(&adj, &m, &err), 0);
	CHECK_INT(fct_patches_unfacet(patch, &m, &adj, pl, 5, 20, 0.5, facets, &err), 0);
	fct_adj_free(&adj);
	int gone = patch[2 * (a * n + a)] == -1;
	for (int j = a; j < b; j++)
		for (int i = a; i < b; i++)
			CHECK_INT(patch[2 * (j * n + i)] == -1, gone);
	free(patch);
	fct_mesh_free(&m);
	return gone;
}

/* fct_patches_tidy on a 16 x 16 square (plane z = 1, patch 0) with a free-form
 * speck of 4 x 6 cells (48 faces) whose inner vertices of its first rows
 * rows (of 5; 3 vertices a row, each 6 faces' corner) are off the plane by
 * off, every sigma 0.01 (or no sigma given): the speck's faces left
 * free-form; *joined gets the faces given to the patch. */
static size_t speck_left(double off, int rows, int with_sigma, size_t *joined)
{
	struct fct_mesh m;
	struct fct_err err;
	const int n = 16;
	square(&m, n, 1);
	int32_t *patch = malloc(m.nf * sizeof *patch);
	double *sigma = malloc(m.nv * sizeof *sigma);
	for (int j = 0; j < n; j++)
		for (int i = 0; i < n; i++)
			patch[2 * (j * n + i)] = patch[2 * (j * n + i) + 1] = i >= 3 && i < 7 && j >= 2 && j < 8 ? -1 : 0;
	for (size_t v = 0; v < m.nv; v++)
		sigma[v] = 0.01;
	for (int j = 3; j < 3 + rows; j++)
		for (int i = 4; i < 7; i++)
			m.xyz[3 * (size_t)(j * (n + 1) + i) + 2] += off;
	struct fct_plane pl = { { 0, 0, -1 }, 1, 0, 0 };
	struct fct_tidy_stats st;
	struct fct_adj adj;
	CHECK_INT(fct_adj_build(&adj, &m, &err), 0);
	CHECK_INT(fct_patches_tidy(patch, &m, &adj, &pl, 1, 0, with_sigma ? sigma : NULL, 4, 1, 64, &st, &err), 0);
	fct_adj_free(&adj);
	size_t left = 0;
	for (size_t f = 0; f < m.nf; f++)
		left += patch[f] < 0;
	CHECK_INT(st.off_plane_faces, left);
	*joined = st.speck_faces;
	free(patch), free(sigma);
	fct_mesh_free(&m);
	return left;
}

/* m: the five vertices pos and the triangles a (face 0) and b (face 1). */
static void two_faces(struct fct_mesh *m, const double pos[5][3], const uint32_t a[3], const uint32_t b[3])
{
	struct fct_err err;
	fct_mesh_init(m);
	for (int v = 0; v < 5; v++)
		CHECK(fct_mesh_add_vertex(m, pos[v][0], pos[v][1], pos[v][2], &err) >= 0);
	CHECK(fct_mesh_add_face(m, a, 3, &err) >= 0);
	CHECK(fct_mesh_add_face(m, b, 3, &err) >= 0);
}

/* fct_planes_project on m (freed after) with the floor y = 0 as plane 0
 * and the wall z = 5 as plane 1, seen from (0, 1.5, 0), every sigma sg[v]
 * (NULL: none): *out gets where vertex 0 goes, *off where the nearer plane
 * alone would have put it (NaN when it did not go onto a line), and no
 * other vertex goes onto one; returns the count of vertices put on one. */
static size_t floor_wall_project(struct fct_mesh *m, const int32_t *patch, const double *sg, double out[3],
                                 double off[3])
{
	struct fct_err err;
	const struct fct_plane planes[2] = { { { 0, 1, 0 }, 0, 0, 0 }, { { 0, 0, -1 }, 5, 0, 0 } };
	const double vp[3] = { 0, 1.5, 0 };
	double *off_crease = malloc(3 * m->nv * sizeof *off_crease);
	size_t moved, creased;
	struct fct_adj adj;
	CHECK_INT(fct_adj_build(&adj, m, &err), 0);
	CHECK_INT(fct_planes_project(m, &adj, patch, planes, vp, sg, 0, 4, off_crease, NULL, &moved, &creased, &err), 0);
	fct_adj_free(&adj);
	memcpy(out, m->xyz, 3 * sizeof *out);
	memcpy(off, off_crease, 3 * sizeof *off);
	for (size_t v = 1; v < m->nv; v++)
		CHECK(isnan(off_crease[3 * v]));
	free(off_crease);
	fct_mesh_free(m);
	return creased;
}

/* fct_planes_project on a vertex p = (0, y, z) of two faces, one of the
 * floor y = 0 (patch 0) and one of a wall z = 5 (patch 1), seen from
 * (0, 1.5, 0): *out gets where p goes, *off where the nearer plane alone
 * would have put it (NaN when p did not go onto the crease line); returns
 * the count of vertices put on the line. */
static size_t crease_move(double y, double z, double out[3], double off[3])
{
	struct fct_mesh m;
	const double pos[5][3] = { { 0, y, z }, { -0.1, 0, 4.9 }, { 0.1, 0, 4.9 }, { -0.1, 0.1, 5 }, { 0.1, 0.1, 5 } };
	const uint32_t floor_face[3] = { 1, 2, 0 }, wall_face[3] = { 0, 4, 3 };
	two_faces(&m, pos, floor_face, wall_face);
	const int32_t patch[2] = { 0, 1 };
	return floor_wall_project(&m, patch, NULL, out, off);
}

/* fct_planes_project on a vertex p = (x, y, 0) of two faces, one of the
 * side y = 0 of a box (patch 0) whose data end at its edge x = 0, one of a
 * wall x = -0.5 behind it (patch 1), seen from (3, -2, 0) with every sigma
 * sigma and a bound of 4 sigma, occluded (5 entries) NULL or marked: *out
 * gets where p goes; returns the count of vertices put on the line x =
 * -0.5, y = 0. */
static size_t bounded_crease(double x, double y, double sigma, unsigned char *occluded, double out[3])
{
	struct fct_mesh m;
	struct fct_err err;
	const double pos[5][3] = { { x, y, 0 }, { 0, 0, -0.1 }, { 0, 0, 0.1 }, { -0.5, 0.5, -0.1 }, { -0.5, 0.5, 0.1 } };
	const uint32_t side_face[3] = { 0, 1, 2 }, wall_face[3] = { 0, 4, 3 };
	two_faces(&m, pos, side_face, wall_face);
	const int32_t patch[2] = { 0, 1 };
	const struct fct_plane planes[2] = { { { 0, -1, 0 }, 0, 0, 0 }, { { 1, 0, 0 }, 0.5, 0, 0 } };
	const double vp[3] = { 3, -2, 0 }, sg[5] = { sigma, sigma, sigma, sigma, sigma };
	size_t moved, creased;
	struct fct_adj adj;
	CHECK_INT(fct_adj_build(&adj, &m, &err), 0);
	CHECK_INT(fct_planes_project(&m, &adj, patch, planes, vp, sg, 0, 4, NULL, occluded, &moved, &creased, &err), 0);
	fct_adj_free(&adj);
	memcpy(out, m.xyz, 3 * sizeof *out);
	fct_mesh_free(&m);
	return creased;
}

/* fct_planes_project on p = (0, 0.03, 5.02), a vertex of one face of the
 * floor y = 0 (patch 0) and of a free-form face (-1) whose other corners
 * (+-0.05, 0.06 side, 5) are corners of a face of the wall z = 5 (patch 1)
 * with (0, 0.1 side, 5): the wall rises from the floor (side 1) or hangs
 * below it, the front of a box whose top the floor then is (side -1).
 * Seen from (0, 1.5, 0), every sigma sigma: *out gets where p goes, *off
 * where along its ray alone it would have gone (NaN when it did not go
 * onto the two planes' line); returns the count of vertices put on it. */
static size_t hidden_floor(double sigma, double side, double out[3], double off[3])
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	const double pos[6][3] = { { 0, 0.03, 5.02 }, { -0.1, 0, 4.9 }, { 0.1, 0, 4.9 },
	                           { -0.05, 0.06 * side, 5 }, { 0.05, 0.06 * side, 5 }, { 0, 0.1 * side, 5 } };
	const uint32_t faces[3][3] = { { 1, 2, 0 }, { 0, 4, 3 }, { 3, 4, 5 } };
	for (int v = 0; v < 6; v++)
		CHECK(fct_mesh_add_vertex(&m, pos[v][0], pos[v][1], pos[v][2], &err) >= 0);
	for (int f = 0; f < 3; f++)
		CHECK(fct_mesh_add_face(&m, faces[f], 3, &err) >= 0);
	const int32_t patch[3] = { 0, -1, 1 };
	const double sg[6] = { sigma, sigma, sigma, sigma, sigma, sigma };
	return floor_wall_project(&m, patch, sg, out, off);
}

/* fct_planes_meet on a vertex (0, 0, 4.8) of two faces, one of the floor
 * y = 0 (patch 0) and one of the wall z = 5 (patch 1), every sigma 0.01:
 * their line, 0.2 away, is beyond 4 sigma, and the vertex stays on the
 * floor, 0.2 off the wall.  Seen from (0, 1.5, 0) (one view's mesh) it is
 * torn: the wall's face gets a copy on its plane (vertex 5), a crack where
 * the sensor saw an occlusion.  Without a viewpoint (a fused scan) no
 * sensor saw one, and a crack would open a closed surface: it stays
 * shared.  Returns the vertices torn; *nv gets the mesh's vertices, *wall0
 * the wall face's first corner. */
static size_t meet_far(int with_viewpoint, size_t *nv, uint32_t *wall0)
{
	struct fct_mesh m;
	struct fct_err err;
	const double pos[5][3] = { { 0, 0, 4.8 }, { -0.1, 0, 4.7 }, { 0.1, 0, 4.7 }, { -0.1, 0.1, 5 }, { 0.1, 0.1, 5 } };
	const uint32_t floor_face[3] = { 1, 2, 0 }, wall_face[3] = { 0, 4, 3 };
	two_faces(&m, pos, floor_face, wall_face);
	const int32_t patch[2] = { 0, 1 };
	const struct fct_plane planes[2] = { { { 0, 1, 0 }, 0, 0, 0 }, { { 0, 0, -1 }, 5, 0, 0 } };
	const double vp[3] = { 0, 1.5, 0 }, sg[5] = { 0.01, 0.01, 0.01, 0.01, 0.01 };
	struct fct_meet_stats st;
	CHECK_INT(fct_planes_meet(&m, patch, planes, sg, NULL, 4, with_viewpoint ? vp : NULL, &st, &err), 0);
	CHECK_INT(st.stayed, 1);
	CHECK_NEAR(m.xyz[2], 4.8, 0);
	*nv = m.nv;
	*wall0 = m.fvert[m.fstart[1]];
	fct_mesh_free(&m);
	return st.torn;
}

/* fct_planes_meet on a vertex p = (0, 0.5, 5.1) of two faces: one of the
 * wall z = 5 (patch 1), which lies 0.1 before p, and one beside it, of the
 * plane z = 5.1 (patch 2: a wall behind, seen past the first's edge) or
 * free-form (-1), every sigma 0.01, seen from (0, 1.5, 0).  p's ray meets
 * the first wall 0.102 before it, beyond 4 sigma.  With a plane behind
 * holding p, the ray passes the first wall's edge: the wall's copy goes all
 * the way onto it, as a box's side ends before the wall.  Beside the
 * free-form surface p is the first wall's own sample, seen along a grazing
 * ray: its copy goes 4 sigma along the ray, no farther.  *copy gets the
 * copy (vertex 5); returns the vertices torn. */
static size_t meet_before(int behind_is_plane, double copy[3])
{
	struct fct_mesh m;
	struct fct_err err;
	const double pos[5][3] = { { 0, 0.5, 5.1 }, { -0.1, 0.4, 5.1 }, { 0.1, 0.4, 5.1 }, { -0.1, 0.6, 5 },
	                           { 0.1, 0.6, 5 } };
	const uint32_t behind_face[3] = { 1, 2, 0 }, wall_face[3] = { 0, 4, 3 };
	two_faces(&m, pos, behind_face, wall_face);
	const int32_t patch[2] = { behind_is_plane ? 2 : -1, 1 };
	const struct fct_plane planes[3] = { { { 0, 1, 0 }, 0, 0, 0 }, { { 0, 0, -1 }, 5, 0, 0 },
	                                     { { 0, 0, -1 }, 5.1, 0, 0 } };
	const double vp[3] = { 0, 1.5, 0 }, sg[5] = { 0.01, 0.01, 0.01, 0.01, 0.01 };
	struct fct_meet_stats st;
	CHECK_INT(fct_planes_meet(&m, patch, planes, sg, NULL, 4, vp, &st, &err), 0);
	CHECK_INT(m.nv, 5 + st.torn);
	if (st.torn) {
		memcpy(copy, m.xyz + 15, 3 * sizeof *copy);
		CHECK_INT(m.fvert[m.fstart[1]], 5);   /* the wall's face took the copy */
	}
	CHECK_NEAR(m.xyz[2], 5.1, 0);            /* the sample stays for the other face */
	fct_mesh_free(&m);
	return st.torn;
}

int main(void)
{
	size_t nv;
	uint32_t wall0;
	CHECK_INT(meet_far(1, &nv, &wall0), 1);
	CHECK_INT(nv, 6);
	CHECK_INT(wall0, 5);
	CHECK_INT(meet_far(0, &nv, &wall0), 0);
	CHECK_INT(nv, 5);
	CHECK_INT(wall0, 0);
	double copy[3];
	/* The ray from (0, 1.5, 0) through (0, 0.5, 5.1) meets z = 5 at
	 * (0, 1.5 - 5 / 5.1, 5). */
	CHECK_INT(meet_before(1, copy), 1);
	CHECK_NEAR(copy[0], 0, 1e-12);
	CHECK_NEAR(copy[1], 1.5 - 5 / 5.1, 1e-12);
	CHECK_NEAR(copy[2], 5, 1e-12);
	/* 0.04 (4 sigma) of the 0.102 towards the viewpoint, along the unit
	 * (0, 1, -5.1) / |(0, 1, -5.1)|. */
	CHECK_INT(meet_before(0, copy), 1);
	double ray = sqrt(1 + 5.1 * 5.1);
	CHECK_NEAR(copy[0], 0, 1e-12);
	CHECK_NEAR(copy[1], 0.5 + 0.04 / ray, 1e-12);
	CHECK_NEAR(copy[2], 5.1 - 0.04 * 5.1 / ray, 1e-12);

	size_t facets, joined;
	double at[3], off[3];
	/* 9 mm above the floor, 10 mm before the wall: along its ray onto the
	 * floor (the nearer plane) it would land 20 mm beyond the wall, farther
	 * from the crease than it was; it goes onto the crease line instead,
	 * beside its ray (which passes 1.5 m above the floor 5 m away). */
	CHECK_INT(crease_move(0.009, 4.99, at, off), 1);
	CHECK_NEAR(at[1], 0, 1e-12);
	CHECK_NEAR(at[2], 5, 1e-12);
	CHECK_NEAR(at[0], 0, 1e-12);
	CHECK_NEAR(off[1], 0, 1e-12);
	CHECK_NEAR(off[2], 4.99 * 1.5 / (1.5 - 0.009), 1e-12);
	/* 100 mm before the wall, the floor along its ray takes it nearer the
	 * crease: it stays on the floor, on its ray. */
	CHECK_INT(crease_move(0.009, 4.9, at, off), 0);
	CHECK_NEAR(at[1], 0, 1e-12);
	CHECK_NEAR(at[2], 4.9 * 1.5 / (1.5 - 0.009), 1e-12);
	CHECK(isnan(off[0]));
	/* On the ray past the box's edge (0, 0, 0), 0.1 m before the wall and
	 * 0.285 m from the crease line: onto the line with sigma 0.1 (within 4
	 * sigma), onto the wall along its ray with sigma 0.05. */
	CHECK_INT(bounded_crease(-0.4, 0.8 / 3, 0.1, NULL, at), 1);
	CHECK_NEAR(at[0], -0.5, 1e-12);
	CHECK_NEAR(at[1], 0, 1e-12);
	CHECK_INT(bounded_crease(-0.4, 0.8 / 3, 0.05, NULL, at), 0);
	CHECK_NEAR(at[0], -0.5, 1e-12);
	CHECK_NEAR(at[1], 1.0 / 3, 1e-12);
	/* Asked for occlusions, the crease within 4 sigma is refused: there
	 * the box's side would span the gap to the wall and hide p's sample
	 * (its ray meets the side's plane 0.48 m before it, at the box's
	 * edge); p goes onto the wall along its ray, marked occluded.  Near
	 * the line, 30 mm before the side's plane (its ray meets the plane 40
	 * mm before it, within the bound), a crease. */
	unsigned char occ[5];
	CHECK_INT(bounded_crease(-0.4, 0.8 / 3, 0.1, occ, at), 0);
	CHECK_NEAR(at[0], -0.5, 1e-12);
	CHECK_NEAR(at[1], 1.0 / 3, 1e-12);
	CHECK_INT(occ[0], 1);
	CHECK_INT(occ[1] + occ[2] + occ[3] + occ[4], 0);
	CHECK_INT(bounded_crease(-0.49, 0.03, 0.1, occ, at), 1);
	CHECK_NEAR(at[0], -0.5, 1e-12);
	CHECK_NEAR(at[1], 0, 1e-12);
	CHECK_INT(occ[0], 0);
	/* A floor vertex alone (no crease), its sample 20 mm behind the wall
	 * and 30 mm above the floor: along its ray it would go onto the floor
	 * at z = 5.02 * 1.5 / 1.47 = 5.1224, 0.107 m (3.6 times straight
	 * across) and 0.12 m past the wall, beyond a bound of 4 sigma (0.08
	 * with sigma 0.02): the floor alone leaves it at its sample.  Its ray
	 * meets the wall 20.8 mm from it, at y = 0.0359 (the wall's side of
	 * the line), 0.128 m before the floor: within that bound (margin 0.02)
	 * it goes onto the line y = 0, z = 5 where it passes nearest its ray,
	 * (0, 0, 5), off the sample where the floor left it. */
	CHECK_INT(hidden_floor(0.02, 1, at, off), 1);
	CHECK_NEAR(at[0], 0, 1e-12);
	CHECK_NEAR(at[1], 0, 1e-12);
	CHECK_NEAR(at[2], 5, 1e-12);
	CHECK_NEAR(off[1], 0.03, 1e-12);
	CHECK_NEAR(off[2], 5.02, 1e-12);
	/* The wall met 20.8 mm away is beyond a bound of 4 sigma = 16 mm with
	 * sigma 0.004; the front of a box below its top is met above the top,
	 * where it does not reach: at its sample both times, the move along
	 * its ray onto the floor (0.107 m) beyond the bound. */
	CHECK_INT(hidden_floor(0.004, 1, at, off), 0);
	CHECK_NEAR(at[1], 0.03, 1e-12);
	CHECK_NEAR(at[2], 5.02, 1e-12);
	CHECK_INT(hidden_floor(0.02, -1, at, off), 0);
	CHECK_NEAR(at[1], 0.03, 1e-12);
	CHECK_NEAR(at[2], 5.02, 1e-12);
	CHECK(isnan(off[0]));
	/* With a bound of 4 sigma: a speck mostly 2 sigma off the plane around
	 * it joins it; one mostly 5 sigma off (a strip of floor seen between a
	 * pillar and the wall) stays free-form, and without sigma it would
	 * join. */
	CHECK_INT(speck_left(0.02, 5, 1, &joined), 0);
	CHECK_INT(joined, 48);
	CHECK_INT(speck_left(0.05, 5, 1, &joined), 48);
	CHECK_INT(joined, 0);
	CHECK_INT(speck_left(-0.05, 5, 1, &joined), 48);
	CHECK_INT(speck_left(0.05, 5, 0, &joined), 0);
	CHECK_INT(joined, 48);
	/* Three rows 5 sigma off (54 of its 144 corners, more than a third):
	 * the speck stays free-form (a piece at the foot of a wall, 39% of its
	 * corners on the floor, joined the wall and hung its floor 0.21 m
	 * below the floor); two rows off (36 corners, a quarter) join. */
	CHECK_INT(speck_left(0.05, 3, 1, &joined), 48);
	CHECK_INT(joined, 0);
	CHECK_INT(speck_left(0.05, 2, 1, &joined), 0);
	CHECK_INT(joined, 48);

	/* A facet: its whole outline at 10-degree creases with four patches
	 * larger than itself (18 faces against 54 and 18). */
	CHECK(centre_unfaceted(9, 3, 6, 10, &facets));
	/* Creases of 30 degrees are edges between planes, not facets. */
	CHECK(!centre_unfaceted(9, 3, 6, 30, &facets));
	CHECK_INT(facets, 0);
	/* Within 3 degrees of parallel is no crease. */
	CHECK(!centre_unfaceted(9, 3, 6, 2, &facets));
	/* A plane of 200 faces ringed by bands of at most 24 (more than four
	 * times its largest shallow neighbour) stays a plane: the 7-Scenes
	 * kitchen's floor (140159 faces) has pieces of 14931 faces and less
	 * tilted 4-8 degrees against it, and whether it became free-form
	 * turned on a share of its outline of 0.4958 or 0.5025. */
	CHECK(!centre_unfaceted(12, 1, 11, 10, &facets));
	/* 32 faces against 12, within four times: a facet. */
	CHECK(centre_unfaceted(6, 1, 5, 10, &facets));

	double a;
	size_t border, up;

	/* Nothing missing: nothing to fill, and the outer boundary is no hole. */
	CHECK_INT(fill(NULL, 0, 64, 0, &a, &border, &up), 0);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);

	/* One missing vertex: a hexagon of 6 edges, 4 triangles. */
	uint32_t one[] = { vertex_at(2, 2) };
	CHECK_INT(fill(one, 1, 64, 0, &a, &border, &up), 1);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);
	CHECK_INT(up, 0);
	/* ... but not with loops of at most 5 edges. */
	CHECK_INT(fill(one, 1, 5, 0, &a, &border, &up), 0);
	CHECK_NEAR(a, 4 - 6 * 0.25 * 0.25 / 2, 1e-12);

	/* Two missing vertices two apart on a row: their hexagons touch at
	 * (3, 2), which is on both loops; each is filled. */
	uint32_t two[] = { vertex_at(2, 2), vertex_at(4, 2) };
	CHECK_INT(fill(two, 2, 64, 0, &a, &border, &up), 2);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);
	CHECK_INT(up, 0);
	/* Six missing vertices making four holes (faces joined across
	 * edges: (4,2) with (3,4), (5,4) with (6,4)) in a chain, each touching
	 * the next at one corner, (3,2), (4,4) and (6,5): all four filled. */
	uint32_t many[] = { vertex_at(2, 2), vertex_at(4, 2), vertex_at(3, 4), vertex_at(5, 4), vertex_at(6, 6),
	                    vertex_at(6, 4) };
	CHECK_INT(fill(many, 6, 64, 0, &a, &border, &up), 4);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);
	CHECK_INT(up, 0);

	/* A hole on the line between two patches is in neither: left open. */
	uint32_t mid[] = { vertex_at(N / 2, 3) };
	CHECK_INT(fill(mid, 1, 64, 1, &a, &border, &up), 0);
	CHECK_INT(border, 4 * N + 6);
	/* ... while one inside patch 1 beside it is filled. */
	uint32_t side[] = { vertex_at(N / 2, 3), vertex_at(N / 2 + 2, 3) };
	CHECK_INT(fill(side, 2, 64, 1, &a, &border, &up), 1);
	CHECK_INT(border, 4 * N + 6);

	/* The square's whole border walked as a loop is the outer boundary of
	 * the piece, not a hole, however many edges max_edges allows. */
	CHECK_INT(fill(NULL, 0, 1000, 0, &a, &border, &up), 0);
	CHECK_INT(border, 4 * N);

	/* fct_fill_free_holes: the hole between two patches, which no plane
	 * fill takes, is filled with free-form faces (4 triangles of the
	 * hexagon) ... */
	size_t faces, free_faces, plane_faces;
	CHECK_INT(fill_as(mid, 1, 64, TWO_PATCHES, 1, 0, &a, &border, &up, &faces, &free_faces), 1);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);
	CHECK_INT(up, 0);
	CHECK_INT(free_faces, 4);
	CHECK_INT(faces, 2 * N * N - 6 + 4);
	/* ... and so are holes in the free-form surface, touching ones too,
	 * as the plane fill does inside a patch ... */
	CHECK_INT(fill_as(many, 6, 64, ONE_PATCH, 0, 0, &a, &border, &up, &plane_faces, &free_faces), 4);
	CHECK_INT(fill_as(many, 6, 64, ALL_FREE, 1, 0, &a, &border, &up, &faces, &free_faces), 4);
	CHECK_NEAR(a, 4, 1e-12);
	CHECK_INT(border, 4 * N);
	CHECK_INT(up, 0);
	CHECK_INT(faces, plane_faces);
	CHECK_INT(free_faces, faces);
	/* ... up to max_edges only ... */
	CHECK_INT(fill_as(one, 1, 5, ALL_FREE, 1, 0, &a, &border, &up, &faces, &free_faces), 0);
	CHECK_INT(border, 4 * N + 6);
	/* ... but not a hole inside one patch (the plane fill's, after the
	 * projection), nor the outer boundary. */
	CHECK_INT(fill_as(side, 2, 64, TWO_PATCHES, 1, 0, &a, &border, &up, &faces, &free_faces), 1);
	CHECK_INT(border, 4 * N + 6);
	CHECK_INT(fill_as(NULL, 0, 1000, ALL_FREE, 1, 0, &a, &border, &up, &faces, &free_faces), 0);
	CHECK_INT(border, 4 * N);
	/* A hole on a ramp of 0.02 over the quarter to its right (the loop two
	 * sigma off a plane at most) is filled; on one of 0.5 it is a depth
	 * jump: left open. */
	CHECK_INT(fill_as(mid, 1, 64, ALL_FREE, 1, 0.02, &a, &border, &up, &faces, &free_faces), 1);
	CHECK_INT(border, 4 * N);
	CHECK_INT(fill_as(mid, 1, 64, ALL_FREE, 1, 0.5, &a, &border, &up, &faces, &free_faces), 0);
	CHECK_INT(border, 4 * N + 6);
	CHECK_DONE();
}

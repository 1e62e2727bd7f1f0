/* planemodel.c - the planar model's preparation of a segmentation (see
 * planemodel.h). */
#include "planar/planemodel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/unionfind.h"
#include "geom/adj.h"
#include "io/camera.h"
#include "io/header.h"
#include "io/noise.h"
#include "planar/freedecim.h"
#include "planar/project.h"
#include "geom/geom.h"
#include "geom/polytri.h"
#include "planar/segment.h"

/* A patch of at least 1 / LARGE_PATCH of the faces is worth keeping a plane
 * with its outline as sampled rather than made free-form. */
#define LARGE_PATCH 50
/* Narrower than this many samples, a piece of faces is a sliver. */
#define SLIVER_WIDTH 3

/* far[2 r], far[2 r + 1]: of the corners of the faces of each piece (root
 * r) that would join a patch, those farther than max_dev times their sigma
 * from that patch's plane, and all. */
static void speck_far_corners(uint32_t *far, const struct fct_mesh *m, int32_t *root,
                              const int32_t *host,
                              const struct fct_plane *planes, size_t np, const double *sigma,
                              double max_dev)
{
	memset(far, 0, 2 * m->nf * sizeof *far);
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t r = fct_uf_root(root, (uint32_t)f);
		int32_t h = host[r];
		if (h < 0 || (size_t)h >= np)
			continue;
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
			uint32_t v = m->fvert[c];
			double d = fabs(fct_v3_dot(planes[h].n, m->xyz + 3 * (size_t)v) + planes[h].d);
			far[2 * r] += !(d <= max_dev * sigma[v]);
			far[2 * r + 1]++;
		}
	}
}

int fct_patches_tidy(int32_t *patch, const struct fct_mesh *m, const struct fct_adj *adj,
                     const struct fct_plane *planes,
                     size_t np, int two_sided, const double *sigma, double max_dev,
                     size_t min_plane, size_t min_free, struct fct_tidy_stats *st,
                     struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	size_t nf = m->nf;
	int32_t *root = fct_alloc_array(nf ? nf : 1, sizeof *root, err);
	int32_t *host = fct_alloc_array(nf ? nf : 1, sizeof *host, err);
	uint32_t *count = fct_alloc_array(nf ? nf : 1, sizeof *count, err);
	if (!root || !host || !count) {
		free(root), free(host), free(count);
		return -1;
	}
	/* Patches of fewer than min_plane faces are free-form. */
	memset(count, 0, nf * sizeof *count);
	for (size_t f = 0; f < nf; f++)
		if (patch[f] >= 0 && (size_t)patch[f] < nf)
			count[patch[f]]++;
	for (size_t f = 0; f < nf; f++)
		if (patch[f] >= 0 && (size_t)patch[f] < nf && count[patch[f]] < min_plane) {
			patch[f] = -1;
			st->small_faces++;
		}
	/* Pieces of faces of one label (joined across edges), their size and
	 * the one other label around them (-2: none yet, -3: more than one). */
	for (size_t f = 0; f < nf; f++)
		root[f] = -1, host[f] = -2;
	for (size_t e = 0; e < adj->ne; e++) {
		const uint32_t *fs = &adj->edge_f[adj->edge_fstart[e]];
		uint32_t k = fct_adj_edge_nfaces(adj, e);
		for (uint32_t i = 0; i < k; i++)
			for (uint32_t j = i + 1; j < k; j++)
				if (patch[fs[i]] == patch[fs[j]]) {
					uint32_t a = fct_uf_root(root, fs[i]), b = fct_uf_root(root, fs[j]);
					if (a != b) {
						if (root[a] > root[b] || (root[a] == root[b] && a > b)) {
							uint32_t t = a;
							a = b, b = t;
						}
						root[a] += root[b];
						root[b] = (int32_t)a;
					}
				}
	}
	/* count: each piece's boundary edges (to another label or none). */
	memset(count, 0, nf * sizeof *count);
	for (size_t e = 0; e < adj->ne; e++) {
		const uint32_t *fs = &adj->edge_f[adj->edge_fstart[e]];
		uint32_t k = fct_adj_edge_nfaces(adj, e);
		if (k == 1)
			count[fct_uf_root(root, fs[0])]++;
		for (uint32_t i = 0; i < k; i++)
			for (uint32_t j = 0; j < k; j++) {
				if (patch[fs[i]] == patch[fs[j]])
					continue;
				uint32_t r = fct_uf_root(root, fs[i]);
				if (j == (i + 1) % k)
					count[r]++;
				if (host[r] == -2)
					host[r] = patch[fs[j]];
				else if (host[r] != patch[fs[j]])
					host[r] = -3;
			}
	}
	/* A piece with one label around it joins it when small, or narrow: a
	 * strip w samples wide and L long has about 2 w L faces and 2 L
	 * boundary edges, so faces < SLIVER_WIDTH boundary edges is a strip
	 * narrower than that.  Such slivers between two parts of one patch
	 * would close up when decimated, and the patch's outline would run
	 * both ways along them.  But a piece joins a patch only when two
	 * thirds of its faces' corners or more lie within max_dev sigma of
	 * the patch's plane: a patch's vertices are moved onto its plane, and
	 * a strip of floor seen between a pillar and the wall behind, joined
	 * to the wall, was thrown along its rays to hang 0.2 m below the
	 * floor; with half, a piece at the foot of a wall 5 m away, 39% of its
	 * corners on the floor, joined the wall and hung its floor 0.21 m
	 * below the floor (mkscene's Kinect room with pixels missing).  Not
	 * all: a speck of outliers is one.  (Leaving only a joining piece's
	 * faces that are all off the plane apart left scattered specks in the
	 * kitchen's frames, whose crossing outlines took 7 rounds.) */
	uint32_t *far = sigma && planes ? fct_alloc_array(nf ? nf : 1, 2 * sizeof *far, err) : NULL;
	if (sigma && planes && !far) {
		free(root), free(host), free(count);
		return -1;
	}
	if (far)
		speck_far_corners(far, m, root, host, planes, np, sigma, max_dev);
	for (size_t f = 0; f < nf; f++) {
		uint32_t r = fct_uf_root(root, (uint32_t)f);
		size_t size = (size_t)(-root[r]);
		if (host[r] >= -1 && (size < min_free || size < SLIVER_WIDTH * (size_t)count[r])) {
			if (far && 3 * far[2 * r] > far[2 * r + 1]) {
				st->off_plane_faces++;
				continue;
			}
			patch[f] = host[r];
			st->speck_faces++;
		}
	}
	free(far);
	/* Two patches turned away from each other (normals more than 120
	 * degrees apart: the two sides of a board thinner than the noise)
	 * that meet along an edge have no rim between them: their polygons
	 * would span the same outline, in the same triangles, and one copy of
	 * each be dropped as a duplicate, leaving the board open.  The faces
	 * along such a seam become free-form: a rim of their own. */
	if (two_sided && planes)
		for (size_t e = 0; e < adj->ne; e++) {
			const uint32_t *fs = &adj->edge_f[adj->edge_fstart[e]];
			if (fct_adj_edge_nfaces(adj, e) != 2)
				continue;
			int32_t a = patch[fs[0]], b = patch[fs[1]];
			if (a < 0 || b < 0 || a == b || (size_t)a >= np || (size_t)b >= np ||
			    !(fct_v3_dot(planes[a].n, planes[b].n) < -0.5))
				continue;
			patch[fs[0]] = patch[fs[1]] = -1;
			st->seam_faces += 2;
		}
	/* A patch with no edge to another label or the mesh's border is a
	 * whole closed piece (a blob whose top was a patch, its rest a speck
	 * that joined it): no outline bounds it, and its polygon would be
	 * nothing.  Free-form. */
	unsigned char *bounded = calloc(nf ? nf : 1, 1);
	if (!bounded) {
		free(root), free(host), free(count);
		return fct_fail(err, "out of memory");
	}
	for (size_t e = 0; e < adj->ne; e++) {
		const uint32_t *fs = &adj->edge_f[adj->edge_fstart[e]];
		uint32_t k = fct_adj_edge_nfaces(adj, e);
		for (uint32_t i = 0; i < k; i++)
			if (patch[fs[i]] >= 0 && (size_t)patch[fs[i]] < nf && (k != 2 || patch[fs[0]] != patch[fs[1]]))
				bounded[patch[fs[i]]] = 1;
	}
	for (size_t f = 0; f < nf; f++)
		if (patch[f] >= 0 && (size_t)patch[f] < nf && !bounded[patch[f]]) {
			patch[f] = -1;
			st->closed_faces++;
		}
	free(bounded);
	free(root), free(host), free(count);
	return 0;
}

/* A facet of a curved surface has at least this many neighbours at shallow
 * creases; a plane that noise or a sensor's distortion split has one or
 * two. */
#define SHALLOW_NEIGHBOURS 3
/* Planes within 3 degrees of parallel make no crease: a sheet of paper on a
 * table, a door in its frame. */
#define COS_PARALLEL 0.99862953475457383
/* A facet is about as large as the facets around it (the curvature and
 * the noise bound them all alike); a patch more than this many times the
 * faces of its largest shallow neighbour is a plane with small pieces
 * tilted against it: a floor beside a rug, a wall beside a picture. */
#define FACET_SIZE_RATIO 4

int fct_patches_unfacet(int32_t *patch, const struct fct_mesh *m, const struct fct_adj *adj,
                        const struct fct_plane *planes,
                        size_t nplanes, double max_angle, double min_share, size_t *facets,
                        struct fct_err *err)
{
	*facets = 0;
	if (nplanes == 0)
		return 0;
	double *shared = calloc(2 * nplanes, sizeof *shared);   /* shallow, all */
	unsigned char *facet = calloc(nplanes, 1);
	/* Each patch's first shallow neighbours (up to SHALLOW_NEIGHBOURS). */
	int32_t *nb = malloc(nplanes * SHALLOW_NEIGHBOURS * sizeof *nb);
	/* Each patch's faces, and the faces of its largest shallow neighbour. */
	size_t *faces = calloc(2 * nplanes, sizeof *faces);
	if (!shared || !facet || !nb || !faces) {
		free(shared), free(facet), free(nb), free(faces);
		return fct_fail(err, "out of memory");
	}
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0)
			faces[2 * (size_t)patch[f]]++;
	double cos_max = cos(max_angle * M_PI / 180);
	for (size_t i = 0; i < nplanes * SHALLOW_NEIGHBOURS; i++)
		nb[i] = -1;
	for (size_t e = 0; e < adj->ne; e++) {
		/* Every edge of a patch's outline counts: to another patch, to the
		 * free-form surface, to the outside. */
		uint32_t k = fct_adj_edge_nfaces(adj, e);
		int32_t a = patch[adj->edge_f[adj->edge_fstart[e]]];
		int32_t b = k == 2 ? patch[adj->edge_f[adj->edge_fstart[e] + 1]] : -1;
		if (k > 2 || a == b)
			continue;
		double len = sqrt(fct_v3_dist2(m->xyz + 3 * (size_t)adj->edge_v[2 * e],
		                               m->xyz + 3 * (size_t)adj->edge_v[2 * e + 1]));
		if (a < 0 || b < 0) {
			int32_t l = a >= 0 ? a : b;
			if (l >= 0)
				shared[2 * l + 1] += len;
			continue;
		}
		double c = fct_v3_dot(planes[a].n, planes[b].n);
		int shallow = c >= cos_max && c <= COS_PARALLEL;
		for (int k = 0; k < 2; k++) {
			int32_t l = k ? b : a, o = k ? a : b;
			shared[2 * l] += shallow ? len : 0;
			shared[2 * l + 1] += len;
			if (shallow && faces[2 * o] > faces[2 * l + 1])
				faces[2 * l + 1] = faces[2 * o];
			int32_t *list = nb + (size_t)l * SHALLOW_NEIGHBOURS;
			for (int i = 0; shallow && i < SHALLOW_NEIGHBOURS; i++) {
				if (list[i] == o)
					break;
				if (list[i] < 0) {
					list[i] = o;
					break;
				}
			}
		}
	}
	for (size_t l = 0; l < nplanes; l++)
		if (shared[2 * l + 1] > 0 && shared[2 * l] >= min_share * shared[2 * l + 1] &&
		    nb[l * SHALLOW_NEIGHBOURS + SHALLOW_NEIGHBOURS - 1] >= 0 &&
		    faces[2 * l] <= FACET_SIZE_RATIO * faces[2 * l + 1])
			facet[l] = 1, ++*facets;
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0 && facet[patch[f]])
			patch[f] = -1;
	free(shared), free(facet), free(nb), free(faces);
	return 0;
}

/* A unit frame (u, v) of the plane with normal n, u x v = n. */
static void plane_frame(const double n[3], double u[3], double v[3])
{
	double a[3] = {0, 0, 0};
	int k = fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2) : (fabs(n[1]) < fabs(n[2]) ? 1 : 2);
	a[k] = 1;
	fct_v3_cross(u, a, n);
	double l = sqrt(fct_v3_dot(u, u));
	u[0] /= l, u[1] /= l, u[2] /= l;
	fct_v3_cross(v, n, u);
}

/* Edges as 64-bit keys (lower vertex high), in an open-addressing set. */
struct edge_set {
	uint64_t *key;   /* 0: empty (no edge joins vertex 0 to itself) */
	size_t mask;
};

static uint64_t edge_key(uint32_t a, uint32_t b)
{
	return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

static size_t edge_slot(const struct edge_set *h, uint64_t k)
{
	size_t i = (size_t)((k * 0x9e3779b97f4a7c15u) >> 17) & h->mask;
	while (h->key[i] && h->key[i] != k)
		i = (i + 1) & h->mask;
	return i;
}

/* Does edge (a, b) exist: in the mesh's adjacency, or added by a fill? */
static int edge_exists(const struct fct_adj *adj, const struct edge_set *h, uint32_t a, uint32_t b)
{
	uint64_t k = edge_key(a, b);
	if (h->key[edge_slot(h, k)] == k)
		return 1;
	size_t lo = 0, hi = adj->ne;
	uint32_t x = a < b ? a : b, y = a < b ? b : a;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		const uint32_t *e = adj->edge_v + 2 * mid;
		if (e[0] < x || (e[0] == x && e[1] < y))
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < adj->ne && adj->edge_v[2 * lo] == x && adj->edge_v[2 * lo + 1] == y;
}

/* Fill one hole: loop[0..k) in border order (faces on its left), in the
 * plane of the given normal, its triangles faces of label p; not when a
 * new triangle's inner edge exists already (the hole's corners are joined
 * elsewhere, across a fold or a thin wall, and the fill would make that
 * edge non-manifold). */
static int fill_loop(struct fct_mesh *m, int32_t **patch, const double normal[3], int32_t p,
                     const uint32_t *loop, size_t k, const struct fct_adj *adj, struct edge_set *h,
                     size_t *filled, struct fct_err *err)
{
	double u[3], v[3], *xy = fct_alloc_array(2 * k, sizeof *xy, err);
	uint32_t *lv = fct_alloc_array(k, sizeof *lv, err), lstart[2] = {0, (uint32_t)k};
	uint32_t *tri = NULL;
	size_t ntri = 0;
	int rc = -1;
	if (!xy || !lv)
		goto out;
	plane_frame(normal, u, v);
	for (size_t i = 0; i < k; i++) {
		/* Reversed, so that the hole is on the left. */
		const double *x = m->xyz + 3 * (size_t)loop[k - 1 - i];
		xy[2 * i] = fct_v3_dot(x, u);
		xy[2 * i + 1] = fct_v3_dot(x, v);
		lv[i] = (uint32_t)i;
	}
	if (!(fct_polytri_loop_area2(xy, lv, k) > 0)) {
		rc = 0;   /* the outer boundary of a piece, not a hole */
		goto out;
	}
	struct fct_err local;
	int r = fct_polytri(&tri, &ntri, xy, k, lstart, 1, lv, FCT_POLYTRI_GREEDY, NULL, &local);
	if (r != 0) {
		rc = r > 0 ? 0 : fct_fail(err, "%s", local.msg);
		goto out;
	}
	for (size_t t = 0; t < ntri; t++)
		for (int c = 0; c < 3; c++) {
			uint32_t i = tri[3 * t + (size_t)c], j = tri[3 * t + (size_t)(c + 1) % 3];
			if ((i + 1) % k == j || (j + 1) % k == i)
				continue;   /* a loop edge */
			if (edge_exists(adj, h, loop[k - 1 - i], loop[k - 1 - j])) {
				rc = 0;
				goto out;
			}
		}
	for (size_t t = 0; t < ntri; t++)
		for (int c = 0; c < 3; c++) {
			uint64_t key = edge_key(loop[k - 1 - tri[3 * t + (size_t)c]],
			                        loop[k - 1 - tri[3 * t + (size_t)(c + 1) % 3]]);
			h->key[edge_slot(h, key)] = key;
		}
	int32_t *np = realloc(*patch, (m->nf + ntri) * sizeof *np);
	if (!np) {
		fct_fail(err, "out of memory");
		goto out;
	}
	*patch = np;
	for (size_t t = 0; t < ntri; t++) {
		uint32_t f[3];
		for (int c = 0; c < 3; c++)
			f[c] = loop[k - 1 - tri[3 * t + (size_t)c]];
		long idx = fct_mesh_add_face(m, f, 3, err);
		if (idx < 0)
			goto out;
		np[idx] = p;
	}
	++*filled;
	rc = 0;
out:
	free(xy), free(lv), free(tri);
	return rc;
}

/* The border half-edges of a mesh, each as its face walks it (a -> to,
 * the face on its left), grouped by a: those from vertex a are
 * start[a] .. start[a + 1). */
struct border {
	uint32_t *start, *to, *face, *from;
};

static void border_free(struct border *b)
{
	free(b->start), free(b->to), free(b->face), free(b->from);
}

static int border_build(struct border *b, const struct fct_mesh *m, const struct fct_adj *adj,
                        struct fct_err *err)
{
	memset(b, 0, sizeof *b);
	size_t nb = adj->nborder ? adj->nborder : 1;
	b->start = fct_alloc_array(m->nv + 1, sizeof *b->start, err);
	b->to = fct_alloc_array(nb, sizeof *b->to, err);
	b->face = fct_alloc_array(nb, sizeof *b->face, err);
	b->from = fct_alloc_array(nb, sizeof *b->from, err);
	if (!b->start || !b->to || !b->face || !b->from)
		return -1;
	memset(b->start, 0, (m->nv + 1) * sizeof *b->start);
	for (int pass = 0; pass < 2; pass++) {
		for (size_t f = 0; f < m->nf; f++) {
			uint32_t s = m->fstart[f], n = m->fstart[f + 1] - s;
			for (uint32_t c = 0; c < n; c++) {
				uint32_t e = adj->face_e[s + c];
				if (e == FCT_ADJ_NONE || fct_adj_edge_nfaces(adj, e) != 1)
					continue;
				uint32_t a = m->fvert[s + c];
				if (!pass) {
					b->start[a + 1]++;
					continue;
				}
				uint32_t h = b->start[a]++;
				b->to[h] = m->fvert[s + (c + 1) % n], b->face[h] = (uint32_t)f, b->from[h] = a;
			}
		}
		if (!pass)
			for (size_t v = 0; v < m->nv; v++)
				b->start[v + 1] += b->start[v];
		else
			for (size_t v = m->nv; v > 0; v--)
				b->start[v] = b->start[v - 1];
	}
	b->start[0] = 0;
	return 0;
}

/* The unit normal of the faces fs[0..n) of m, each weighted by its area;
 * 0 when they have none. */
static int faces_normal(const struct fct_mesh *m, const uint32_t *fs, size_t n, double normal[3])
{
	double sum[3] = { 0, 0, 0 };
	for (size_t i = 0; i < n; i++) {
		const uint32_t *v = m->fvert + m->fstart[fs[i]];
		uint32_t k = fct_face_size(m, fs[i]);
		const double *o = m->xyz + 3 * (size_t)v[0];
		for (uint32_t c = 1; c + 1 < k; c++) {   /* twice the fan's areas */
			double a[3], b[3], x[3];
			fct_v3_sub(a, m->xyz + 3 * (size_t)v[c], o);
			fct_v3_sub(b, m->xyz + 3 * (size_t)v[c + 1], o);
			fct_v3_cross(x, a, b);
			fct_v3_add(sum, sum, x);
		}
	}
	double len = sqrt(fct_v3_dot(sum, sum));
	if (!(len > 0) || !isfinite(len))
		return 0;
	for (int i = 0; i < 3; i++)
		normal[i] = sum[i] / len;
	return 1;
}

/* The border half-edge that goes on around the hole after h (x -> a):
 * a's only one, or at a vertex several holes touch (two missing depth
 * pixels a pixel apart) the first met turning from a's edge back to x
 * counterclockwise about normal n (NULL: about the normal of h's face,
 * on the free-form surface), across the hole, on h's right.
 * UINT32_MAX: none. */
static uint32_t border_next(const struct border *b, const struct fct_mesh *m, uint32_t h, const double n[3])
{
	uint32_t a = b->to[h], lo = b->start[a], hi = b->start[a + 1];
	if (hi - lo == 1)
		return lo;
	double face_n[3];
	if (!n && faces_normal(m, &b->face[h], 1, face_n))
		n = face_n;
	if (hi == lo || !n)
		return UINT32_MAX;
	const double *pa = m->xyz + 3 * (size_t)a;
	double back[3];
	fct_v3_sub(back, m->xyz + 3 * (size_t)b->from[h], pa);
	uint32_t best = UINT32_MAX;
	double best_angle = INFINITY;
	for (uint32_t o = lo; o < hi; o++) {
		double d[3], c[3];
		fct_v3_sub(d, m->xyz + 3 * (size_t)b->to[o], pa);
		fct_v3_cross(c, back, d);
		double angle = atan2(fct_v3_dot(c, n), fct_v3_dot(back, d));
		if (!(angle > 0))
			angle += 2 * M_PI;
		if (angle < best_angle)
			best_angle = angle, best = o;
	}
	return best;
}

/* Whether every vertex of loop[0..k) lies within max_dev times its sigma
 * of the plane through the loop's centroid with the given normal. */
static int loop_flat(const struct fct_mesh *m, const uint32_t *loop, size_t k, const double normal[3],
                     const double *sigma, double max_dev)
{
	double c[3] = { 0, 0, 0 };
	for (size_t i = 0; i < k; i++)
		fct_v3_add(c, c, m->xyz + 3 * (size_t)loop[i]);
	for (int i = 0; i < 3; i++)
		c[i] /= (double)k;
	for (size_t i = 0; i < k; i++) {
		double d[3];
		fct_v3_sub(d, m->xyz + 3 * (size_t)loop[i], c);
		if (!(fabs(fct_v3_dot(d, normal)) <= max_dev * sigma[loop[i]]))
			return 0;
	}
	return 1;
}

/* fct_fill_plane_holes (sigma NULL) or fct_fill_free_holes. */
static int fill_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                      size_t nplanes, size_t max_edges, const double *sigma, double max_dev,
                      size_t *filled, struct fct_err *err)
{
	int free_form = sigma != NULL;
	*filled = 0;
	struct fct_adj adj;
	if (fct_adj_build(&adj, m, err))
		return -1;
	struct border b;
	uint32_t *loop = fct_alloc_array(max_edges + 1, sizeof *loop, err);
	uint32_t *loopface = fct_alloc_array(max_edges + 1, sizeof *loopface, err);
	uint32_t *stamp = fct_alloc_array(m->nv ? m->nv : 1, sizeof *stamp, err);
	struct edge_set h = {NULL, 0};
	int rc = -1;
	if (border_build(&b, m, &adj, err) || !loop || !loopface || !stamp)
		goto out;
	memset(stamp, 0, (m->nv ? m->nv : 1) * sizeof *stamp);
	/* Room for every edge the fills can add: at most three per border edge. */
	size_t cap = 64;
	while (cap < 8 * (adj.nborder + 8))
		cap *= 2;
	if (!(h.key = calloc(cap, sizeof *h.key))) {
		fct_fail(err, "out of memory");
		goto out;
	}
	h.mask = cap - 1;
	size_t nf0 = m->nf;
	for (size_t a = 0; a < m->nv; a++)
		for (uint32_t h0 = b.start[a]; h0 < b.start[a + 1]; h0++) {
			/* Walk each loop from its lowest vertex only, once; a loop
			 * through a vertex twice is no simple hole. */
			int32_t p = (*patch)[b.face[h0]];
			const double *n = p >= 0 && (size_t)p < nplanes ? planes[p].n : NULL;
			size_t k = 0;
			uint32_t e = h0;
			int ok = 1;
			do {
				uint32_t x = b.from[e];
				if (x < a || k == max_edges || stamp[x] == h0 + 1) {
					ok = 0;
					break;
				}
				stamp[x] = h0 + 1;
				loopface[k] = b.face[e];
				loop[k++] = x;
				e = border_next(&b, m, e, n);
			} while (e != UINT32_MAX && e != h0);
			if (!ok || e == UINT32_MAX || k < 3 || (!n && !free_form))
				continue;
			int one_patch = n != NULL;
			for (size_t i = 0; i < k && one_patch; i++)
				one_patch = loopface[i] < nf0 && (*patch)[loopface[i]] == p;
			double normal[3];
			if (one_patch && !free_form) {
				if (fill_loop(m, patch, n, p, loop, k, &adj, &h, filled, err))
					goto out;
			} else if (!one_patch && free_form && faces_normal(m, loopface, k, normal) &&
			           loop_flat(m, loop, k, normal, sigma, max_dev)) {
				if (fill_loop(m, patch, normal, -1, loop, k, &adj, &h, filled, err))
					goto out;
			}
		}
	rc = 0;
out:
	border_free(&b);
	free(loop), free(loopface), free(stamp), free(h.key);
	fct_adj_free(&adj);
	return rc;
}

int fct_fill_plane_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                         size_t nplanes, size_t max_edges, size_t *filled, struct fct_err *err)
{
	return fill_holes(m, patch, planes, nplanes, max_edges, NULL, 0, filled, err);
}

int fct_fill_free_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                        size_t nplanes, size_t max_edges, const double *sigma, double max_dev,
                        size_t *filled, struct fct_err *err)
{
	return fill_holes(m, patch, planes, nplanes, max_edges, sigma, max_dev, filled, err);
}

/* Drop the vertices no face uses, keeping the others in order. */
static int drop_unused_vertices(struct fct_mesh *m, struct fct_err *err)
{
	unsigned char *used = calloc(m->nv ? m->nv : 1, 1);
	size_t *keep = fct_alloc_array(m->nv ? m->nv : 1, sizeof *keep, err);
	if (!used || !keep) {
		free(used), free(keep);
		return used ? -1 : fct_fail(err, "out of memory");
	}
	for (size_t c = 0; c < (m->nf ? m->fstart[m->nf] : 0); c++)
		used[m->fvert[c]] = 1;
	size_t n = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (used[v])
			keep[n++] = v;
	int rc = n == m->nv ? 0 : fct_mesh_gather_vertices(m, keep, n, err);
	free(used), free(keep);
	return rc;
}

/* Planes closer than this to parallel (the sine of their angle, squared)
 * have no line worth moving a vertex to: 10 degrees. */
#define MIN_SIN2 0.0301536896
/* Three or more planes whose normals' scatter has a least eigenvalue below
 * this meet at no point worth moving a vertex to. */
#define MIN_SPREAD 0.1
/* A move may not leave a triangle thinner than this (twice its area over
 * its longest edge squared) and thinner than it was: next to nothing. */
#define MIN_QUALITY 1e-6

/* The distinct patches (>= 0) of the faces fs[0..n), up to 8, into ls. */
static int face_labels(const int32_t *patch, const uint32_t *fs, size_t n, int32_t ls[8])
{
	int k = 0;
	for (size_t i = 0; i < n; i++) {
		int32_t lab = patch[fs[i]];
		int seen = lab < 0;
		for (int j = 0; j < k && !seen; j++)
			seen = ls[j] == lab;
		if (!seen && k < 8)
			ls[k++] = lab;
	}
	return k;
}

/* The point nearest p on the planes ls[0..n): x = p - N^T (N N^T)^-1
 * (N p + d) for one or two, the least-squares point of three or more.
 * 0 when they meet nowhere useful (MIN_SIN2, MIN_SPREAD). */
static int onto_planes(const struct fct_plane *P, const int32_t *ls, int n, const double p[3],
                       double x[3])
{
	if (n == 1) {
		double r = fct_v3_dot(P[ls[0]].n, p) + P[ls[0]].d;
		fct_v3_axpy(x, p, -r, P[ls[0]].n);
		return 1;
	}
	if (n == 2) {
		const double *n1 = P[ls[0]].n, *n2 = P[ls[1]].n;
		double c = fct_v3_dot(n1, n2), det = 1 - c * c;
		if (!(det >= MIN_SIN2))
			return 0;
		double r1 = fct_v3_dot(n1, p) + P[ls[0]].d, r2 = fct_v3_dot(n2, p) + P[ls[1]].d;
		double l1 = (r1 - c * r2) / det, l2 = (r2 - c * r1) / det;
		for (int i = 0; i < 3; i++)
			x[i] = p[i] - l1 * n1[i] - l2 * n2[i];
		return 1;
	}
	/* Least squares relative to p, for precision: A y = -sum r n, x = p + y. */
	double a[3][3] = {{0}}, b[3] = {0, 0, 0};
	for (int k = 0; k < n; k++) {
		const double *m = P[ls[k]].n;
		double r = fct_v3_dot(m, p) + P[ls[k]].d;
		for (int i = 0; i < 3; i++) {
			b[i] -= r * m[i];
			for (int j = 0; j < 3; j++)
				a[i][j] += m[i] * m[j];
		}
	}
	double s6[6] = {a[0][0], a[1][1], a[2][2], a[0][1], a[1][2], a[0][2]};
	if (!(fct_sym3_min_eigenvalue(s6) >= MIN_SPREAD))
		return 0;
	double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
	             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
	             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
	double y[3];
	for (int c = 0; c < 3; c++) {
		double m[3][3];
		memcpy(m, a, sizeof m);
		for (int i = 0; i < 3; i++)
			m[i][c] = b[i];
		y[c] = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
		        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
		        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) / det;
	}
	for (int i = 0; i < 3; i++)
		x[i] = p[i] + y[i];
	return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]);
}

/* With a viewpoint vp: the point where the ray through p meets the plane
 * (n == 1), or the point of the two planes' line nearest that ray (n == 2,
 * x holding onto_planes' point of the line); 0 (x kept) when the ray runs
 * within a milliradian of the plane or the line, or meets the plane behind
 * vp.  A sensor measures along its rays: this keeps a vertex on the ray of
 * its pixel. */
static int along_ray(const struct fct_plane *P, const int32_t *ls, int n, const double vp[3],
                     const double p[3], double x[3])
{
	double r[3];
	fct_v3_sub(r, p, vp);
	double rl = sqrt(fct_v3_dot(r, r));
	if (!(rl > 0))
		return 0;
	if (n == 1) {
		const double *m = P[ls[0]].n;
		double nr = fct_v3_dot(m, r);
		if (!(fabs(nr) > 1e-3 * rl))
			return 0;
		double t = -(fct_v3_dot(m, vp) + P[ls[0]].d) / nr;
		if (!(t > 0))
			return 0;
		fct_v3_axpy(x, vp, t, r);
		return 1;
	}
	double u[3];
	fct_v3_cross(u, P[ls[0]].n, P[ls[1]].n);
	double ul = sqrt(fct_v3_dot(u, u));
	if (!(ul > 0))
		return 0;
	u[0] /= ul, u[1] /= ul, u[2] /= ul;
	r[0] /= rl, r[1] /= rl, r[2] /= rl;
	double w[3];
	fct_v3_sub(w, x, vp);
	double c = fct_v3_dot(u, r), den = 1 - c * c;
	if (!(den > 1e-6))
		return 0;
	fct_v3_axpy(x, x, (c * fct_v3_dot(w, r) - fct_v3_dot(w, u)) / den, u);
	return 1;
}

/* The mean of the other corners of v's faces fs[0..n) of patch lab: where
 * that patch's data lie around v.  0 when v has none. */
static int patch_side(const struct fct_mesh *m, const int32_t *patch, const uint32_t *fs, size_t n,
                      int32_t lab, uint32_t v, double out[3])
{
	double sum[3] = {0, 0, 0};
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		if (patch[fs[i]] != lab)
			continue;
		for (uint32_t c = m->fstart[fs[i]]; c < m->fstart[fs[i] + 1]; c++)
			if (m->fvert[c] != v) {
				fct_v3_add(sum, sum, m->xyz + 3 * (size_t)m->fvert[c]);
				k++;
			}
	}
	if (!k)
		return 0;
	for (int i = 0; i < 3; i++)
		out[i] = sum[i] / (double)k;
	return 1;
}

/* Vertex v's uncertainty at p: the root of sigma^2 (none when NULL) plus
 * its sample spacing squared, the span of pixel_angle at its distance from
 * vp. */
static double uncertainty(const double *sigma, double pixel_angle, const double vp[3], size_t v,
                          const double p[3])
{
	double sp = pixel_angle * sqrt(fct_v3_dist2(p, vp)), sg = sigma ? sigma[v] : 0;
	return sqrt(sg * sg + sp * sp);
}

/* Would a crease through x of patches ls[0], ls[1] hide the vertex's own
 * sample p from vp?  It does when p's ray meets one of the two planes more
 * than margin before p, on that patch's side of the crease line (toward
 * the other corners of the vertex's faces of it): a box's side put onto
 * the line where its plane meets the wall behind it, across the gap
 * between them, would hide the wall seen through that gap. */
static int crease_hides(const struct fct_mesh *m, const int32_t *patch, const uint32_t *fs, size_t n,
                        uint32_t v, const struct fct_plane *P, const int32_t ls[2],
                        const double vp[3], const double p[3], const double x[3], double margin)
{
	double u[3], r[3];
	fct_v3_cross(u, P[ls[0]].n, P[ls[1]].n);
	double ul = sqrt(fct_v3_dot(u, u));
	fct_v3_sub(r, p, vp);
	double rl = sqrt(fct_v3_dot(r, r));
	if (!(ul > 0) || !(rl > margin))
		return 0;
	for (int i = 0; i < 3; i++)
		u[i] /= ul;
	for (int k = 0; k < 2; k++) {
		const struct fct_plane *Q = &P[ls[k]];
		double nr = fct_v3_dot(Q->n, r);
		if (!(fabs(nr) > 1e-3 * rl))
			continue;
		double t = -(fct_v3_dot(Q->n, vp) + Q->d) / nr, side[3];
		if (!(t > 0 && (1 - t) * rl > margin) || !patch_side(m, patch, fs, n, ls[k], v, side))
			continue;
		double c[3], a[3], b[3];
		fct_v3_axpy(c, vp, t, r);
		fct_v3_sub(a, c, x);
		fct_v3_sub(b, side, x);
		/* across the line, in the plane */
		double au = fct_v3_dot(a, u), bu = fct_v3_dot(b, u);
		if (fct_v3_dot(a, b) - au * bu > 0)
			return 1;
	}
	return 0;
}

/* Is vertex v inside its faces fs[0..n), all of one patch, and not on
 * the border of the mesh (each edge from v shared by two of them)? */
static int inside_patch(const struct fct_mesh *m, const int32_t *patch, const uint32_t *fs, size_t n,
                        uint32_t v)
{
	uint32_t e[64];
	size_t k = 0;
	if (!n || 2 * n > sizeof e / sizeof *e)
		return 0;
	for (size_t i = 0; i < n; i++) {
		uint32_t s = m->fstart[fs[i]], c = m->fstart[fs[i] + 1] - s, j = 0;
		if (patch[fs[i]] != patch[fs[0]])
			return 0;
		while (j < c && m->fvert[s + j] != v)
			j++;
		if (j == c)
			return 0;
		e[k++] = m->fvert[s + (j + 1) % c];
		e[k++] = m->fvert[s + (j + c - 1) % c];
	}
	for (size_t i = 0; i < k; i++) {
		size_t same = 0;
		for (size_t j = 0; j < k; j++)
			same += e[j] == e[i];
		if (same != 2)
			return 0;
	}
	return 1;
}

/* The mean of the corners within r of vertex v of the faces of patch b
 * around the vertices within r of it (fct_vertices_within), in mean: where
 * b's data lie near v.  0 when there are none.  stamp (m->nv entries,
 * none yet above *mark) and list (m->nv) are scratch; *mark counts the
 * calls. */
static int patch_near(const struct fct_mesh *m, const int32_t *patch, const uint32_t *vstart,
                      const uint32_t *vf, uint32_t v, int32_t b, double r, uint32_t *stamp,
                      uint32_t *list, uint32_t *mark, double mean[3])
{
	const double *p = m->xyz + 3 * (size_t)v;
	size_t n = fct_vertices_within(m, vstart, vf, v, r, stamp, ++*mark, list), k = 0;
	double sum[3] = {0, 0, 0};
	for (size_t i = 0; i < n; i++)
		for (uint32_t j = vstart[list[i]]; j < vstart[list[i] + 1]; j++) {
			uint32_t f = vf[j];
			for (uint32_t c = m->fstart[f]; patch[f] == b && c < m->fstart[f + 1]; c++) {
				const double *q = m->xyz + 3 * (size_t)m->fvert[c];
				if (fct_v3_dist2(q, p) <= r * r)
					fct_v3_add(sum, sum, q), k++;
			}
		}
	if (!k)
		return 0;
	for (int i = 0; i < 3; i++)
		mean[i] = sum[i] / (double)k;
	return 1;
}

/* The patch b (of np) whose plane the ray from vp through vertex v's p
 * meets first, more than margin nearer vp than far (where it meets patch
 * a's plane; INFINITY: nowhere), within bound of p, and on the side of a
 * and b's line where the corners of b's faces within bound of p lie
 * (patch_near): the ray meets b's surface before a's plane, which b hides
 * there.  box: each patch's bounding box (least x y z, then greatest).
 * -1 when none. */
static int32_t ray_blocked(const struct fct_mesh *m, const int32_t *patch, const uint32_t *vstart,
                           const uint32_t *vf, uint32_t v, const struct fct_plane *P, size_t np,
                           int32_t a, const double vp[3], const double p[3], double far,
                           double margin, double bound, const double *box, uint32_t *stamp,
                           uint32_t *queue, uint32_t *mark)
{
	int32_t hit = -1;
	double near = INFINITY;
	for (size_t q = 0; q < np; q++) {
		int32_t ab[2] = {a, (int32_t)q};
		double xb[3], o[3], u[3], w[3], side[3], d;
		const double *bx = box + 6 * q;
		if (ab[1] == a || !(p[0] >= bx[0] - bound && p[0] <= bx[3] + bound && p[1] >= bx[1] - bound &&
		                    p[1] <= bx[4] + bound && p[2] >= bx[2] - bound && p[2] <= bx[5] + bound) ||
		    !along_ray(P, &ab[1], 1, vp, p, xb) || !(fct_v3_dist2(xb, p) <= bound * bound) ||
		    !((d = sqrt(fct_v3_dist2(xb, vp))) + margin < far && d < near) || !onto_planes(P, ab, 2, p, o) ||
		    !patch_near(m, patch, vstart, vf, v, ab[1], bound, stamp, queue, mark, side))
			continue;
		/* across the line, in b's plane */
		fct_v3_cross(u, P[a].n, P[q].n);
		fct_v3_cross(w, P[q].n, u);
		if ((fct_v3_dot(xb, w) - fct_v3_dot(o, w)) * (fct_v3_dot(side, w) - fct_v3_dot(o, w)) > 0)
			near = d, hit = ab[1];
	}
	return hit;
}

/* The bounding box of each patch's corners (least x y z, then greatest;
 * *np patches, the largest label plus one), or NULL out of memory. */
static double *patch_boxes(const struct fct_mesh *m, const int32_t *patch, size_t *np)
{
	size_t n = 0;
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0 && (size_t)patch[f] + 1 > n)
			n = (size_t)patch[f] + 1;
	double *box = malloc((n ? n : 1) * 6 * sizeof *box);
	if (!box)
		return NULL;
	for (size_t l = 0; l < n; l++)
		for (int i = 0; i < 3; i++)
			box[6 * l + i] = INFINITY, box[6 * l + 3 + i] = -INFINITY;
	for (size_t f = 0; f < m->nf; f++)
		for (uint32_t c = m->fstart[f]; patch[f] >= 0 && c < m->fstart[f + 1]; c++)
			for (int i = 0; i < 3; i++) {
				double *bx = box + 6 * (size_t)patch[f], q = m->xyz[3 * (size_t)m->fvert[c] + i];
				bx[i] = q < bx[i] ? q : bx[i];
				bx[3 + i] = q > bx[3 + i] ? q : bx[3 + i];
			}
	*np = n;
	return box;
}

/* fct_planes_project on the vertices with only[v] set (NULL: all); vstart,
 * vf: m's faces of each vertex. */
static int project_vertices(struct fct_mesh *m, const uint32_t *vstart, const uint32_t *vf,
                            const int32_t *patch, const struct fct_plane *planes,
                            const double *viewpoint, const double *sigma, double pixel_angle,
                            double max_move, double *off_crease, unsigned char *occluded,
                            const unsigned char *only, size_t *moved, size_t *creased,
                            struct fct_err *err)
{
	*moved = 0, *creased = 0;
	/* The grazing-ray rule's patch boxes and scratch (ray_blocked): only
	 * with a viewpoint, the rule's ray. */
	size_t nplanes = 0;
	uint32_t mark = 0, *stamp = NULL, *queue = NULL;
	double *box = NULL;
	if (viewpoint) {
		stamp = calloc(m->nv ? m->nv : 1, sizeof *stamp);
		queue = malloc((m->nv ? m->nv : 1) * sizeof *queue);
		box = patch_boxes(m, patch, &nplanes);
		if (!stamp || !queue || !box) {
			free(stamp), free(queue), free(box);
			return fct_fail(err, "out of memory");
		}
	}
	for (size_t v = 0; v < m->nv; v++) {
		if (only && !only[v])
			continue;
		int32_t ls[8];
		int n = face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls);
		double *p = m->xyz + 3 * v, best[3] = { p[0], p[1], p[2] }, x[3], bd = INFINITY;
		double unc = viewpoint ? uncertainty(sigma, pixel_angle, viewpoint, v, p) : 0,
		       bound = max_move * unc;
		for (int i = 0; i < n; i++) {
			double r = fabs(fct_v3_dot(planes[ls[i]].n, p) + planes[ls[i]].d);
			if (!(r < bd))
				continue;
			bd = r;
			onto_planes(planes, &ls[i], 1, p, best);
			/* Along the ray, unless that is far longer than across;
			 * not at all when that is beyond the bound (issue 23:
			 * no vertex moved farther than max_move times its
			 * uncertainty).  Straight across instead would slide
			 * it off its pixel: on 7-Scenes frame 000950 a face
			 * 0.11 m from the data where along its ray it was
			 * 58 mm; left at its sample, 57 mm. */
			if (viewpoint && along_ray(planes, &ls[i], 1, viewpoint, p, x) &&
			    fct_v3_dist2(x, p) <= 16 * fct_v3_dist2(best, p)) {
				if (!(bound > 0) || fct_v3_dist2(x, p) <= bound * bound)
					memcpy(best, x, sizeof x);
				else
					memcpy(best, p, sizeof best);
			}
		}
		/* A vertex of two patches that the nearer plane alone would put
		 * farther from their crease than it is goes onto the crease line
		 * instead (see planemodel.h): a floor vertex at a far wall, its
		 * ray grazing the floor, slid on past the wall by more than
		 * planes_meet moves a vertex back (0.13 m in mkscene's Kinect
		 * room). */
		if (off_crease)
			off_crease[3 * v] = NAN;
		double y[3];
		if (occluded)
			occluded[v] = 0;
		if (n == 2 && viewpoint && onto_planes(planes, ls, 2, p, x) &&
		    onto_planes(planes, ls, 2, best, y) && fct_v3_dist2(best, y) > fct_v3_dist2(p, x) &&
		    along_ray(planes, ls, 2, viewpoint, p, x) && fct_v3_dist2(x, p) <= 16 * bd * bd &&
		    (!(bound > 0) || fct_v3_dist2(x, p) <= bound * bound) &&
		    !(occluded && crease_hides(m, patch, vf + vstart[v], vstart[v + 1] - vstart[v], (uint32_t)v,
		                               planes, ls, viewpoint, p, x, bound) && (occluded[v] = 1))) {
			if (off_crease)
				memcpy(off_crease + 3 * v, best, sizeof best);
			memcpy(best, x, sizeof x);
			++*creased;
		}
		/* A vertex on the border of its one patch, its ray grazing the
		 * plane (along it more than twice as far as straight across),
		 * whose ray meets another patch's surface more than its
		 * uncertainty before its plane and within bound of its sample
		 * would lie on its plane hidden behind that surface: it goes
		 * onto the two planes' line where that passes nearest its ray,
		 * when within bound.  A floor vertex next to a far wall, its
		 * sample 4.7 cm behind the wall (noise), slid along its ray onto
		 * the floor 0.16 m past the wall in mkscene's Kinect room. */
		int32_t ab[2] = {ls[0], -1};
		double st[3];
		int on_border = n == 1 && bound > 0 &&
		                !inside_patch(m, patch, vf + vstart[v], vstart[v + 1] - vstart[v], (uint32_t)v);
		int hit = on_border && along_ray(planes, ls, 1, viewpoint, p, x);
		if (on_border && onto_planes(planes, ls, 1, p, st) &&
		    (!hit || fct_v3_dist2(x, p) > 4 * fct_v3_dist2(st, p)) &&
		    (ab[1] = ray_blocked(m, patch, vstart, vf, (uint32_t)v, planes, nplanes, ls[0], viewpoint, p,
		                         hit ? sqrt(fct_v3_dist2(x, viewpoint)) : INFINITY, unc, bound, box,
		                         stamp, queue, &mark)) >= 0 &&
		    onto_planes(planes, ab, 2, p, y) && along_ray(planes, ab, 2, viewpoint, p, y) &&
		    fct_v3_dist2(y, p) <= bound * bound) {
			if (off_crease)
				memcpy(off_crease + 3 * v, best, sizeof best);
			memcpy(best, y, sizeof y);
			++*creased;
		}
		if (n && (best[0] != p[0] || best[1] != p[1] || best[2] != p[2])) {
			memcpy(p, best, sizeof best);
			++*moved;
		}
	}
	free(stamp), free(queue), free(box);
	return 0;
}

int fct_planes_project(struct fct_mesh *m, const struct fct_adj *adj, const int32_t *patch,
                       const struct fct_plane *planes, const double *viewpoint, const double *sigma,
                       double pixel_angle, double max_move, double *off_crease,
                       unsigned char *occluded, size_t *moved, size_t *creased, struct fct_err *err)
{
	return project_vertices(m, adj->vert_fstart, adj->vert_f, patch, planes, viewpoint, sigma,
	                        pixel_angle, max_move, off_crease, occluded, NULL, moved, creased, err);
}

/* Triangle (a, b, c)'s thickness, twice its area over its longest edge
 * squared (0 when it has no extent), and its area vector in n. */
static double thickness(const double a[3], const double b[3], const double c[3], double n[3])
{
	double e1[3], e2[3], e3[3];
	fct_v3_sub(e1, b, a);
	fct_v3_sub(e2, c, a);
	fct_v3_sub(e3, c, b);
	fct_v3_cross(n, e1, e2);
	double l2 = fct_v3_dot(e1, e1), m2 = fct_v3_dot(e2, e2), k2 = fct_v3_dot(e3, e3);
	l2 = m2 > l2 ? m2 : l2;
	l2 = k2 > l2 ? k2 : l2;
	return l2 > 0 ? sqrt(fct_v3_dot(n, n)) / l2 : 0;
}

/* Is face f turned over or thinned (positions m->xyz against before)?
 * Turned: against its patch's plane normal, or its own normal before when
 * free-form; thinned: below MIN_QUALITY and below what it was.  Faces are
 * taken as fans from their first corner. */
static int spoilt(const struct fct_mesh *m, size_t f, int32_t lab, const struct fct_plane *planes,
                  const double *before)
{
	uint32_t s = m->fstart[f], k = m->fstart[f + 1] - s;
	for (uint32_t i = 1; i + 1 < k; i++) {
		uint32_t tv[3] = {m->fvert[s], m->fvert[s + i], m->fvert[s + i + 1]};
		double n0[3], n1[3], q[2];
		for (int pass = 0; pass < 2; pass++) {
			const double *P = pass ? m->xyz : before;
			q[pass] = thickness(P + 3 * (size_t)tv[0], P + 3 * (size_t)tv[1], P + 3 * (size_t)tv[2],
			                    pass ? n1 : n0);
		}
		const double *ref = lab >= 0 ? planes[lab].n : n0;
		if (fct_v3_dot(ref, n1) <= 0 || (q[1] < MIN_QUALITY && q[1] < q[0]))
			return 1;
	}
	return 0;
}

/* A plane seen this obliquely (the sine of the angle between ray and
 * plane) or more is taken as seen at this angle. */
#define MIN_GRAZING 0.3

/* Vertex c (new) becomes a copy of v at x, every property of v with it,
 * and the faces of patch label around v (fs[0..n)) take c for v. */
static void copy_vertex_for(struct fct_mesh *m, const int32_t *patch, const uint32_t *fs, size_t n,
                            uint32_t v, size_t c, int32_t label, const double x[3])
{
	for (size_t j = 0; j < m->vertex.nprops; j++) {
		struct fct_prop *pr = &m->vertex.props[j];
		if (pr->count_type == FCT_NONE)
			fct_prop_set(pr, c, fct_prop_get(pr, v));
	}
	memcpy(m->xyz + 3 * c, x, 3 * sizeof *x);
	for (size_t k = 0; k < n; k++) {
		uint32_t f = fs[k];
		if (patch[f] != label)
			continue;
		for (uint32_t q = m->fstart[f]; q < m->fstart[f + 1]; q++)
			if (m->fvert[q] == v)
				m->fvert[q] = (uint32_t)c;
	}
}

/* Is x, where p's ray from vp meets a plane p lies r from, before p and
 * met at a sine of MIN_GRAZING or more?  Then the ray passes the edge of a
 * surface in front, which ends there. */
static int met_before(const double vp[3], const double p[3], const double x[3], double r)
{
	return fct_v3_dist2(x, vp) < fct_v3_dist2(p, vp) && fabs(r) >= MIN_GRAZING * sqrt(fct_v3_dist2(x, p));
}

/* Is the sample p on one of the planes ls[0..k) other than ls[skip],
 * within its uncertainty (e2 its square)? */
static int on_other_plane(const struct fct_plane *planes, const int32_t *ls, int k, int skip,
                          const double p[3], double e2)
{
	for (int j = 0; j < k; j++) {
		double r = fct_v3_dot(planes[ls[j]].n, p) + planes[ls[j]].d;
		if (j != skip && r * r <= e2)
			return 1;
	}
	return 0;
}

/* A vertex still off the plane of one of its patches by more than its
 * uncertainty (sigma along its ray, across it its sample spacing) is torn:
 * that patch's faces get a copy of it on their plane, where its ray meets
 * the plane (when that is within max_move of its uncertainty, or when the
 * plane lies before the sample, the ray meets it at MIN_GRAZING or more
 * and another plane of the vertex holds the sample; else, or without a
 * viewpoint, straight across).  Before the sample, the ray passes the edge
 * of a surface in front, which ends there: straight across, a wall
 * vertex's copy for the side of a box in front of it would go out through
 * the gap between them.  But where no other plane holds the sample, it is
 * this plane's own, seen along a grazing ray: the copy goes along the ray
 * by max_move uncertainties only, towards its plane (the TUM frame's
 * wall behind a monitor had copies thrown 55 mm on, up to 140, into the
 * empty space between the two; a frame's 418 such copies).  Behind the
 * sample, along a grazing ray, a floor vertex's copy would slide on past
 * the wall that hides it.  Where no line or point of the
 * planes lies near (an occlusion: a box's edge in front of the wall, the
 * noise's own folds), a shared vertex would tilt every face of the patch
 * that is not its own; the tear leaves a crack there instead, which is
 * what the sensor saw.  The copy has every property of the vertex.  Only
 * with a viewpoint. */
static int tear_off_plane(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                          const double *sigma, const double *spacing, double max_move,
                          const double *viewpoint, const uint32_t *vstart, const uint32_t *vf,
                          struct fct_meet_stats *st, struct fct_err *err)
{
	/* Without a viewpoint (a fused scan, another tool's mesh) no sensor
	 * saw an occlusion: a crack would open a closed surface (a cut of
	 * the carved 7-Scenes kitchen fusion, closed again: 5 crease
	 * vertices whose moves onto their line were taken back, torn, 20
	 * border edges).  The vertex stays shared, on the nearer plane. */
	if (!viewpoint)
		return 0;
	struct tear {
		uint32_t v;
		int32_t label;
		double x[3];
	} *tears = NULL;
	size_t n = 0, cap = 0, nv0 = m->nv;
	for (size_t v = 0; v < nv0; v++) {
		int32_t ls[8];
		int k = face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls), other = k >= 2;
		for (uint32_t j = vstart[v]; j < vstart[v + 1] && !other; j++)
			other = patch[vf[j]] < 0;   /* beside the free-form surface */
		double e2 = (sigma ? sigma[v] * sigma[v] : 0) + (spacing ? spacing[v] * spacing[v] : 0);
		if (k < 1 || !other || !(e2 > 0))
			continue;
		for (int i = 0; i < k; i++) {
			const struct fct_plane *pl = &planes[ls[i]];
			const double *p = m->xyz + 3 * v;
			double r = fct_v3_dot(pl->n, p) + pl->d, x[3];
			if (r * r <= e2)
				continue;
			onto_planes(planes, &ls[i], 1, p, x);
			double bound2 = max_move * max_move * e2, d2;
			if (viewpoint && along_ray(planes, &ls[i], 1, viewpoint, p, x) &&
			    !((d2 = fct_v3_dist2(x, p)) <= bound2)) {
				if (!met_before(viewpoint, p, x, r))
					onto_planes(planes, &ls[i], 1, p, x);
				else if (!on_other_plane(planes, ls, k, i, p, e2))
					for (int q = 0; q < 3; q++)
						x[q] = p[q] + sqrt(bound2 / d2) * (x[q] - p[q]);
			}
			if (n == cap && fct_grow((void **)&tears, &cap, n + 1, sizeof *tears, err)) {
				free(tears);
				return -1;
			}
			tears[n].v = (uint32_t)v, tears[n].label = ls[i];
			memcpy(tears[n++].x, x, sizeof x);
		}
	}
	if (n && fct_mesh_set_vertex_count(m, nv0 + n, err)) {
		free(tears);
		return -1;
	}
	for (size_t t = 0; t < n; t++) {
		uint32_t v = tears[t].v;
		copy_vertex_for(m, patch, vf + vstart[v], vstart[v + 1] - vstart[v], v, nv0 + t, tears[t].label,
		                tears[t].x);
	}
	st->torn = n;
	free(tears);
	return 0;
}

int fct_planes_meet(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                    const double *sigma, const double *spacing, double max_move,
                    const double *viewpoint, struct fct_meet_stats *st, struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	uint32_t *vstart = NULL, *vf = NULL;
	size_t nv1 = m->nv ? m->nv : 1;
	double *before = fct_alloc_array(3 * nv1, sizeof *before, err);
	unsigned char *kind = fct_alloc_array(nv1, 1, err);
	int rc = -1;
	if (!before || !kind || fct_vertex_faces(m, &vstart, &vf, err))
		goto out;
	memcpy(before, m->xyz, 3 * m->nv * sizeof *before);
	for (size_t v = 0; v < m->nv; v++) {
		int32_t ls[8];
		int n = face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls);
		kind[v] = 0;
		if (n < 2)
			continue;
		const double *p = before + 3 * v;
		double e2 = (sigma ? sigma[v] * sigma[v] : 0) + (spacing ? spacing[v] * spacing[v] : 0);
		double bound2 = e2 > 0 && max_move > 0 ? max_move * max_move * e2 : INFINITY;
		double x[3], best[3], bd = INFINITY;
		if (n >= 3 && onto_planes(planes, ls, n, p, x) && fct_v3_dist2(x, p) <= bound2) {
			memcpy(best, x, sizeof x);
			kind[v] = 3;
		}
		for (int i = 0; i < n && !kind[v]; i++)
			for (int j = i + 1; j < n; j++) {
				int32_t pair[2] = {ls[i], ls[j]};
				if (!onto_planes(planes, pair, 2, p, x))
					continue;
				if (viewpoint)
					along_ray(planes, pair, 2, viewpoint, p, x);
				if (viewpoint && crease_hides(m, patch, vf + vstart[v], vstart[v + 1] - vstart[v],
				                              (uint32_t)v, planes, pair, viewpoint, p, x,
				                              max_move * sqrt(e2)))
					continue;
				double d2 = fct_v3_dist2(x, p);
				if (d2 <= bound2 && d2 < bd)
					bd = d2, memcpy(best, x, sizeof x);
			}
		if (!kind[v] && bd < INFINITY)
			kind[v] = 2;
		if (kind[v])
			memcpy(m->xyz + 3 * v, best, sizeof best);
		else
			st->stayed++;
	}
	/* Moves that spoil a face are taken back, in rounds. */
	for (int round = 0; round < 16; round++) {
		size_t undone = 0;
		for (size_t f = 0; f < m->nf; f++) {
			if (!spoilt(m, f, patch[f], planes, before))
				continue;
			for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
				uint32_t v = m->fvert[c];
				if (kind[v]) {
					memcpy(m->xyz + 3 * (size_t)v, before + 3 * (size_t)v, sizeof(double[3]));
					kind[v] = 0;
					undone++;
				}
			}
		}
		st->undone += undone;
		if (!undone)
			break;
	}
	for (size_t v = 0; v < m->nv; v++) {
		st->lines += kind[v] == 2;
		st->corners += kind[v] == 3;
	}
	if (tear_off_plane(m, patch, planes, sigma, spacing, max_move, viewpoint, vstart, vf, st, err))
		goto out;
	rc = 0;
out:
	free(before), free(kind), free(vstart), free(vf);
	return rc;
}

void fct_planar_params_default(struct fct_planar_params *p)
{
	p->max_error = 1.5;
	p->border_tol = 1;
	p->outline_tol = 3;
	p->max_move = 4;
	p->min_free = 64;
	p->min_plane = 64;
	p->min_piece = 64;
	p->max_hole = 64;
	p->facet_angle = 20;
}

/* Each vertex's sigma: the property, else the noise the data show, else
 * the planes' median rms for all (too few vertices to tell). */
static int vertex_sigma(const struct fct_mesh *m, const struct fct_plane *pl, size_t np,
                        double **out, int *estimated, struct fct_err *err)
{
	double *sg = fct_alloc_array(m->nv ? m->nv : 1, sizeof *sg, err);
	if (!sg)
		return -1;
	*out = sg;
	*estimated = 0;
	const struct fct_prop *p = fct_elem_find(&m->vertex, "sigma");
	if (p && p->count_type == FCT_NONE) {
		for (size_t v = 0; v < m->nv; v++)
			sg[v] = fct_prop_get(p, v);
		return 0;
	}
	float *f = fct_alloc_array(m->nv ? m->nv : 1, sizeof *f, err);
	if (!f)
		return -1;
	struct fct_err ignored;
	if (!fct_noise_estimate_vertices(f, m, &ignored)) {
		for (size_t v = 0; v < m->nv; v++)
			sg[v] = f[v];
		*estimated = 1;
		free(f);
		return 0;
	}
	free(f);
	double *r = fct_alloc_array(np ? np : 1, sizeof *r, err);
	if (!r)
		return -1;
	size_t n = 0;
	for (size_t l = 0; l < np; l++)
		if (pl[l].rms > 0)
			r[n++] = pl[l].rms;
	qsort(r, n, sizeof *r, fct_cmp_double);
	double s = n ? r[n / 2] : 0;
	free(r);
	for (size_t v = 0; v < m->nv; v++)
		sg[v] = s;
	return 0;
}

/* A copy of m's vertex positions (*n of them), or NULL out of memory. */
static double *copy_positions(const struct fct_mesh *m, size_t *n, struct fct_err *err)
{
	double *x = fct_alloc_array(3 * (m->nv ? m->nv : 1), sizeof *x, err);
	if (x && m->nv)
		memcpy(x, m->xyz, 3 * m->nv * sizeof *x);
	*n = m->nv;
	return x;
}

/* The mean length of the faces' edges (shared ones counted twice). */
static double mean_edge(const struct fct_mesh *m)
{
	double sum = 0;
	size_t n = 0;
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], k = m->fstart[f + 1] - s;
		for (uint32_t i = 0; i < k; i++) {
			const double *a = m->xyz + 3 * (size_t)m->fvert[s + i];
			const double *b = m->xyz + 3 * (size_t)m->fvert[s + (i + 1) % k];
			sum += sqrt(fct_v3_dist2(a, b));
			n++;
		}
	}
	return n ? sum / (double)n : 0;
}

/* Each vertex's sample spacing: what one pixel of the camera spans at its
 * distance from centre c, or without a camera the input's mean edge. */
static double *sample_spacing(const struct fct_mesh *m, const struct fct_camera *cam,
                              const double c[3], double fallback, struct fct_err *err)
{
	double *s = fct_alloc_array(m->nv ? m->nv : 1, sizeof *s, err);
	if (!s)
		return NULL;
	double angle = cam ? fct_camera_pixel_angle(cam) : 0;
	for (size_t v = 0; v < m->nv; v++)
		s[v] = angle > 0 ? angle * sqrt(fct_v3_dist2(m->xyz + 3 * v, c)) : fallback;
	return s;
}

/* The free-form faces of m (patch -1) decimated alone by quadric edge
 * collapse (qem.h) in units of sigma, their borders held and corner[v]
 * kept: into F, whose faces are numbered as m's vertices; its vertex
 * arrays hold the survivors, and vmap[i] is m's number of its vertex i
 * (nmap of them).  The pieces that have not changed since the last round
 * are cache's (freedecim.h). */
static int decimate_free(struct fct_mesh *F, uint32_t **vmap, size_t *nmap, const struct fct_mesh *m,
                         const int32_t *patch, const double *sigma, const unsigned char *corner,
                         const double *vp, const struct fct_planar_params *p,
                         struct fct_free_cache *cache, struct fct_qem_stats *qs, struct fct_err *err)
{
	unsigned char *free_face = fct_alloc_array(m->nf ? m->nf : 1, 1, err);
	if (!free_face)
		return -1;
	for (size_t f = 0; f < m->nf; f++)
		free_face[f] = patch[f] < 0;
	struct fct_qem_params qp;
	fct_qem_params_default(&qp);
	qp.max_error = p->max_error;
	qp.border_tol = p->border_tol;
	qp.hold_borders = 1;
	qp.sigma = sigma;
	qp.corner = corner;
	if (vp) {
		qp.use_viewpoint = 1;
		memcpy(qp.viewpoint, vp, sizeof qp.viewpoint);
	}
	int rc = fct_free_decimate(F, vmap, nmap, m, free_face, &qp, cache, qs, err);
	free(free_face);
	return rc;
}

/* The patches' outlines as wires (m's vertex numbers): each kept segment of
 * each chain, its right side -1 when that is free-form or the outside. */
static struct fct_wire *outline_wires(const struct fct_chains *c, size_t *n, struct fct_err *err)
{
	size_t ne = 0;
	for (size_t i = 0; i < c->n; i++)
		for (size_t q = c->start[i] + 1; q < c->start[i + 1]; q++)
			ne += c->keep[q];
	struct fct_wire *w = fct_alloc_array(ne ? ne : 1, sizeof *w, err);
	if (!w)
		return NULL;
	size_t row = 0;
	for (size_t i = 0; i < c->n; i++) {
		size_t last = c->start[i];
		for (size_t q = c->start[i] + 1; q < c->start[i + 1]; q++) {
			if (!c->keep[q] || c->vert[q] == c->vert[last])
				continue;   /* dropped, or a lasso left with no point between */
			w[row++] = (struct fct_wire){ c->vert[last], c->vert[q], c->left[i],
			                              c->right[i] >= 0 ? c->right[i] : -1 };
			last = q;
		}
	}
	*n = row;
	return w;
}

static int tri_cmp(const void *x, const void *y)
{
	const uint32_t *a = x, *b = y;
	for (int i = 0; i < 4; i++)
		if (a[i] != b[i])
			return a[i] < b[i] ? -1 : 1;
	return 0;
}

/* Drop each triangle of w (triangles only) with the corners of another,
 * keeping the free-form one (or the first): a patch's polygon laid over an
 * island of the free-form surface that its decimation left as one triangle
 * there.  lab follows.  The count dropped into *dropped. */
static int drop_duplicate_triangles(struct fct_mesh *w, int32_t *lab, size_t *dropped,
                                    struct fct_err *err)
{
	uint32_t (*key)[4] = fct_alloc_array(w->nf ? w->nf : 1, sizeof *key, err);
	size_t *keep = fct_alloc_array(w->nf ? w->nf : 1, sizeof *keep, err);
	unsigned char *gone = calloc(w->nf ? w->nf : 1, 1);
	int rc = -1;
	if (!key || !keep || !gone) {
		if (key && keep)
			fct_fail(err, "out of memory");
		goto out;
	}
	for (size_t f = 0; f < w->nf; f++) {
		uint32_t v[3];
		memcpy(v, w->fvert + w->fstart[f], sizeof v);
		for (int i = 0; i < 2; i++)
			for (int j = 0; j < 2 - i; j++)
				if (v[j] > v[j + 1]) {
					uint32_t t = v[j];
					v[j] = v[j + 1], v[j + 1] = t;
				}
		/* free-form first among equals, then by face index */
		key[f][0] = v[0], key[f][1] = v[1], key[f][2] = v[2];
		key[f][3] = (uint32_t)f;
	}
	qsort(key, w->nf, sizeof *key, tri_cmp);
	for (size_t i = 0; i < w->nf;) {
		size_t j = i + 1;
		while (j < w->nf && !memcmp(key[j], key[i], 3 * sizeof(uint32_t)))
			j++;
		if (j - i > 1) {
			size_t best = i;
			for (size_t k = i; k < j; k++)
				if (lab[key[k][3]] < 0) {
					best = k;
					break;
				}
			for (size_t k = i; k < j; k++)
				if (k != best)
					gone[key[k][3]] = 1;
		}
		i = j;
	}
	size_t n = 0;
	for (size_t f = 0; f < w->nf; f++)
		if (!gone[f])
			lab[n] = lab[f], keep[n++] = f;
	*dropped = w->nf - n;
	rc = n == w->nf ? 0 : fct_mesh_gather_faces(w, keep, n, err);
out:
	free(key), free(keep), free(gone);
	return rc;
}

/* A patch's chains are simplified to their tolerance halved k times, and
 * kept as sampled from k = AS_SAMPLED on, where k is the larger of its
 * patches' tight[]: a whole outline tightened, the last resort for a large
 * patch that mending where it crossed did not make clean. */
#define AS_SAMPLED 3

/* The rounds of build_model that may mend outlines and tighten them
 * (enough for AS_SAMPLED steps and a few rounds of their consequences). */
#define LAST_TIGHTENING 6

static int chain_tightness(const struct fct_chains *c, size_t i, const unsigned char *tight)
{
	int k = tight[c->left[i]];
	if (c->right[i] >= 0 && tight[c->right[i]] > k)
		k = tight[c->right[i]];
	return k;
}

/* What tripatch and flag_diagonals flag at a vertex of the outlines
 * (trouble[]): an end of a loop edge that crosses or touches another where
 * its patch's loops were refused, in the frame with fewer such crossings,
 * or in the other; an end of a diagonal that exists elsewhere. */
#define TROUBLE_CROSSING 1
#define TROUBLE_CROSSING_OTHER 2
#define TROUBLE_DIAGONAL 4

/* The edges of w that three or more faces share: a diagonal of a rebuilt
 * patch that exists elsewhere already (its ends are joined across a fold, or
 * by the free-form faces).  The patches of the faces on the edge are
 * flagged unclean and, when may_mend, its ends flagged TROUBLE_DIAGONAL in
 * trouble (the outline next to them is mended: mend_outlines).  *ndiag
 * counts the edges. */
static int flag_diagonals(const struct fct_mesh *w, const int32_t *lab, int may_mend,
                           unsigned char *trouble, unsigned char *unclean, size_t *ndiag,
                           struct fct_err *err)
{
	struct fct_adj adj;
	if (fct_adj_build(&adj, w, err))
		return -1;
	for (size_t e = 0; e < adj.ne; e++) {
		if (fct_adj_edge_nfaces(&adj, e) <= 2)
			continue;
		(*ndiag)++;
		if (may_mend) {
			trouble[adj.edge_v[2 * e]] |= TROUBLE_DIAGONAL;
			trouble[adj.edge_v[2 * e + 1]] |= TROUBLE_DIAGONAL;
		}
		for (uint32_t k = adj.edge_fstart[e]; k < adj.edge_fstart[e + 1]; k++)
			if (lab[adj.edge_f[k]] >= 0)
				unclean[lab[adj.edge_f[k]]] = 1;
	}
	fct_adj_free(&adj);
	return 0;
}

/* Mend the outlines where they went wrong, there only: each simplified
 * segment of a chain that bounds a patch flagged in which[], whose two ends
 * are ends of crossing loop edges (trouble bits in want), or one of them
 * an end of a diagonal found elsewhere, has the points it replaced forced
 * (kept from the next try on, whatever the chain's tolerance): all of
 * them, or beside a diagonal first the middle one.
 * The outline then changes where the trouble is, not all round the patch:
 * whether a tiny crossing somewhere (which rounding may decide) exists no
 * longer decides the whole outline.  mended[l] counts the points newly
 * forced on patch l's outline, *spans the segments. */
static void mend_outlines(const struct fct_chains *c, const unsigned char *trouble, unsigned char want,
                          const unsigned char *which, unsigned char *force, size_t *mended,
                          size_t *spans)
{
	for (size_t i = 0; i < c->n; i++) {
		int32_t l = c->left[i], r = c->right[i];
		if (!which[l] && (r < 0 || !which[r]))
			continue;
		for (size_t a = c->start[i], b; a + 1 < c->start[i + 1]; a = b) {
			for (b = a + 1; !c->keep[b]; b++)
				;
			unsigned char ta = trouble[c->vert[a]], tb = trouble[c->vert[b]];
			int crossing = (ta & tb & want & (TROUBLE_CROSSING | TROUBLE_CROSSING_OTHER)) != 0;
			if (!crossing && !((ta | tb) & want & TROUBLE_DIAGONAL))
				continue;
			/* A crossing: the whole stretch as sampled, which follows the
			 * boundary as the mesh has it.  Beside a diagonal: first its
			 * middle point, which changes the polygon there; the whole
			 * stretch when the diagonal comes back (an end of the stretch
			 * was forced already). */
			int whole = crossing || force[c->vert[a]] || force[c->vert[b]];
			size_t n = 0, lo = whole ? a + 1 : (a + b) / 2, hi = whole ? b : lo + (b > a + 1);
			for (size_t q = lo; q < hi; q++)
				if (!force[c->vert[q]])
					force[c->vert[q]] = 1, n++;
			*spans += n > 0;
			mended[l] += n;
			if (r >= 0)
				mended[r] += n;
		}
	}
}

/* Each chain's own tolerance in tol[]: for a chain between two patches
 * whose every point lies within max_move of its uncertainty of the planes'
 * line (a crease), twice the largest such bound, as fct_planes_meet will
 * move its points onto the line anyway and only its ends matter; 0 (the
 * simplification's default) for the others. */
static void crease_tolerances(double *tol, const struct fct_chains *c, const struct fct_mesh *m,
                              const struct fct_plane *pl, const double *sigma,
                              const double *spacing, double max_move, const double *vp)
{
	for (size_t i = 0; i < c->n; i++) {
		tol[i] = 0;
		if (c->right[i] < 0 || c->closed[i] || max_move <= 0)
			continue;
		int32_t pair[2] = {c->left[i], c->right[i]};
		double worst = 0;
		size_t q;
		for (q = c->start[i]; q < c->start[i + 1]; q++) {
			uint32_t v = c->vert[q];
			const double *p = m->xyz + 3 * (size_t)v;
			double x[3], bound = max_move * sqrt(sigma[v] * sigma[v] + spacing[v] * spacing[v]);
			if (!onto_planes(pl, pair, 2, p, x))
				break;
			if (vp)
				along_ray(pl, pair, 2, vp, p, x);
			if (!(fct_v3_dist2(x, p) <= bound * bound))
				break;
			if (bound > worst)
				worst = bound;
		}
		if (q == c->start[i + 1])
			tol[i] = 2 * worst;
	}
}


/* Each chain of a patch against the outside (the mesh's border: an
 * occlusion, the image's edge) seen from vp: in tol[], outline_tol times
 * its points' mean sample spacing over the sine of the angle at which their
 * rays meet the patch's plane.  A point's pixel is known to a fraction of
 * a spacing across its ray, and projection along the ray stretches that
 * over the plane by one over that sine: the top of a box at 3 m seen from
 * 1.1 m above had teeth of 0.1-0.2 m along its far edge (mkscene's Kinect
 * room). */
static void border_tolerances(double *tol, const struct fct_chains *c, const struct fct_mesh *m,
                              const struct fct_plane *pl, const double *spacing, double outline_tol,
                              const double *vp)
{
	if (!vp)
		return;
	for (size_t i = 0; i < c->n; i++) {
		if (c->right[i] != FCT_CHAIN_OUTSIDE || c->left[i] < 0)
			continue;
		const double *n = pl[c->left[i]].n;
		double sum = 0;
		for (size_t q = c->start[i]; q < c->start[i + 1]; q++) {
			uint32_t v = c->vert[q];
			double r[3];
			fct_v3_sub(r, m->xyz + 3 * (size_t)v, vp);
			double rl = sqrt(fct_v3_dot(r, r));
			double sine = rl > 0 ? fabs(fct_v3_dot(n, r)) / rl : 1;
			sum += spacing[v] / fmax(sine, MIN_GRAZING);
		}
		tol[i] = outline_tol * sum / (double)(c->start[i + 1] - c->start[i]);
	}
}

/* What the rounds of fct_planar_model carry from one to the next: the
 * mesh's adjacency (the mesh stays the same), the chains of the last
 * labelling with that labelling (a round that only mends or tightens keeps
 * it), the free-form decimation's pieces. */
struct rounds {
	struct fct_adj adj;
	int have_adj;
	struct fct_chains chains;
	int32_t *patch;
	struct fct_free_cache free;
	struct fct_chain_cache crossings;
};

static void rounds_free(struct rounds *r)
{
	if (r->have_adj)
		fct_adj_free(&r->adj);
	fct_chains_free(&r->chains);
	free(r->patch);
	fct_free_cache_free(&r->free);
	fct_chain_cache_free(&r->crossings);
}

/* The chains of m's labelling patch (fct_chains_extract), from r when
 * the labelling is the last round's. */
static int extract_chains(struct fct_chains *c, const struct fct_mesh *m, const int32_t *patch,
                          struct rounds *r, struct fct_err *err)
{
	if (r->patch && (!m->nf || !memcmp(r->patch, patch, m->nf * sizeof *patch)))
		return fct_chains_copy(c, &r->chains, err);
	if (!r->have_adj) {
		if (fct_adj_build(&r->adj, m, err))
			return -1;
		r->have_adj = 1;
	}
	if (fct_chains_extract_adj(c, m, &r->adj, patch, err))
		return -1;
	fct_chains_free(&r->chains);
	free(r->patch);
	if (!(r->patch = fct_alloc_array(m->nf ? m->nf : 1, sizeof *r->patch, err)))
		return -1;
	if (m->nf)
		memcpy(r->patch, patch, m->nf * sizeof *patch);
	if (fct_chains_copy(&r->chains, c, err)) {
		free(r->patch);
		r->patch = NULL;
		return -1;
	}
	return 0;
}

/* One try at the model from the dense m and its labels: the free-form faces
 * decimated alone, their outline's surviving vertices frozen into the
 * chains, the other chains simplified, each patch triangulated from its
 * outline (tripatch), all assembled into w.  unclean[l] is set for the
 * patches tripatch could not triangulate cleanly or whose triangles would
 * share an edge with two other faces. */
static int build_model(struct fct_mesh *w, const struct fct_mesh *m, const int32_t *patch,
                       const struct fct_plane *pl, size_t np, const double *sigma,
                       const double *spacing, const double *vp, const struct fct_planar_params *p,
                       const unsigned char *tight, int may_mend, unsigned char *force,
                       unsigned char *trouble, size_t *mended, unsigned char *unclean,
                       struct rounds *carry,
                       struct fct_planar_stats *st, struct fct_err *err)
{
	struct fct_chains c;
	memset(&c, 0, sizeof c);
	struct fct_mesh F;
	fct_mesh_init(&F);
	uint32_t *vmap = NULL;
	size_t nmap = 0;
	unsigned char *corner = calloc(m->nv ? m->nv : 1, 1), *alive = calloc(m->nv ? m->nv : 1, 1);
	unsigned char *again = calloc(np ? np : 1, 1);
	struct fct_wire *wires = NULL;
	int32_t *lab = NULL;
	double *tol = NULL;
	int rc = -1;
	if (!corner || !alive || !again) {
		fct_fail(err, "out of memory");
		goto out;
	}
	if (extract_chains(&c, m, patch, carry, err))
		goto out;
	/* The junctions stay, where the chains meet, and a loop's first point,
	 * where its wire starts and ends.  So does every point of a chain
	 * against the free-form surface whose ends another chain of one of its
	 * patches joins too: with its inner points gone, the patch's outline
	 * would run to and fro along one segment there (a sliver of the patch
	 * between the free-form surface and the border, say). */
	if (!(c.frozen = calloc(c.n ? c.n : 1, 1))) {
		fct_fail(err, "out of memory");
		goto out;
	}
	for (size_t i = 0; i < c.n; i++) {
		corner[c.vert[c.start[i]]] = 1;
		corner[c.vert[c.start[i + 1] - 1]] = 1;
		/* The chains tightened to the last stay as sampled. */
		if (chain_tightness(&c, i, tight) < AS_SAMPLED)
			continue;
		c.frozen[i] = 1;
		for (size_t q = c.start[i]; q < c.start[i + 1]; q++)
			corner[c.vert[q]] = 1;
	}
	/* The stretches of outline mended stay as sampled, against the
	 * free-form surface too (but not where their patch became free-form:
	 * there they are no outline any more). */
	for (size_t q = 0; q < c.start[c.n]; q++)
		corner[c.vert[q]] |= force[c.vert[q]];
	for (size_t i = 0; i < c.n; i++) {
		if (c.right[i] != -1 || c.closed[i])
			continue;
		uint32_t a = c.vert[c.start[i]], b = c.vert[c.start[i + 1] - 1];
		for (size_t j = 0; j < c.n; j++) {
			uint32_t x = c.vert[c.start[j]], y = c.vert[c.start[j + 1] - 1];
			if (j == i || !((x == a && y == b) || (x == b && y == a)) ||
			    (c.left[j] != c.left[i] && c.right[j] != c.left[i]))
				continue;
			for (size_t q = c.start[i]; q < c.start[i + 1]; q++)
				corner[c.vert[q]] = 1;
			break;
		}
	}
	if (decimate_free(&F, &vmap, &nmap, m, patch, sigma, corner, vp, p, &carry->free, &st->qem, err))
		goto out;
	for (size_t i = 0; i < nmap; i++)
		alive[vmap[i]] = 1;
	/* A chain against the free-form surface keeps what its decimation kept;
	 * the others are simplified to their tolerance. */
	for (size_t i = 0; i < c.n; i++) {
		if (c.right[i] != -1 && !c.frozen[i])
			continue;
		c.frozen[i] = 1;
		for (size_t q = c.start[i]; q < c.start[i + 1]; q++)
			c.keep[q] = alive[c.vert[q]];
	}
	struct fct_chain_params cp;
	fct_chain_params_default(&cp);
	cp.scale = spacing;
	cp.scale_factor = p->outline_tol;
	if (!(tol = fct_alloc_array(c.n ? c.n : 1, sizeof *tol, err)))
		goto out;
	crease_tolerances(tol, &c, m, pl, sigma, spacing, p->max_move, vp);
	border_tolerances(tol, &c, m, pl, spacing, p->outline_tol, vp);
	for (size_t i = 0; i < c.n; i++) {
		int k = chain_tightness(&c, i, tight);
		if (!k)
			continue;
		if (!(tol[i] > 0)) {
			double sum = 0;
			for (size_t q = c.start[i]; q < c.start[i + 1]; q++)
				sum += spacing[c.vert[q]];
			tol[i] = p->outline_tol * sum / (double)(c.start[i + 1] - c.start[i]);
		}
		tol[i] = ldexp(tol[i], -k);
	}
	cp.tolerance = tol;
	cp.keep_vertex = force;
	cp.cache = &carry->crossings;
	cp.count_left = 0;
	size_t ne;
	if (fct_chains_simplify(&c, m, patch, pl, np, &cp, &st->chains, err) ||
	    !(wires = outline_wires(&c, &ne, err)))
		goto out;
	/* The planes' triangles, on m's vertices with the decimation's moves. */
	if (fct_mesh_copy(w, m, err) || fct_mesh_gather_faces(w, NULL, 0, err))
		goto out;
	w->has_faces = 0;
	while (w->face.nprops)
		fct_elem_remove(&w->face, w->face.props[0].name);
	for (size_t i = 0; i < nmap; i++)
		memcpy(w->xyz + 3 * (size_t)vmap[i], F.xyz + 3 * i, sizeof(double[3]));
	for (size_t j = 0; j < w->vertex.nprops; j++) {
		struct fct_prop *dst = &w->vertex.props[j];
		const struct fct_prop *src = fct_elem_find(&F.vertex, dst->name);
		if (src && src->count_type == FCT_NONE && dst->count_type == FCT_NONE)
			for (size_t i = 0; i < nmap; i++)
				fct_prop_set(dst, vmap[i], fct_prop_get(src, i));
	}
	struct fct_tripatch_params tp;
	fct_tripatch_params_default(&tp);
	tp.unclean = unclean;
	tp.trouble = may_mend ? trouble : NULL;
	if (fct_wires_set(w, wires, ne, err) || fct_tripatch(w, &tp, &st->tri, err))
		goto out;
	/* Then the free-form faces. */
	size_t nplanar = w->nf;
	if (!(lab = fct_alloc_array(nplanar + F.nf ? nplanar + F.nf : 1, sizeof *lab, err)))
		goto out;
	const struct fct_prop *wp = fct_elem_find(&w->face, "patch");
	for (size_t f = 0; f < nplanar; f++)
		lab[f] = wp ? (int32_t)fct_prop_get(wp, f) : -1;
	for (size_t f = 0; f < F.nf; f++) {
		long k = fct_mesh_add_face(w, F.fvert + F.fstart[f], fct_face_size(&F, f), err);
		if (k < 0)
			goto out;
		lab[k] = -1;
	}
	size_t dup = 0;
	if (drop_duplicate_triangles(w, lab, &dup, err) || fct_patches_set(w, lab, err) ||
	    flag_diagonals(w, lab, may_mend, trouble, unclean, &st->pinned, err))
		goto out;
	/* Where the frame with fewer crossings leaves nothing to mend (its
	 * stretches are as sampled already), the other frame's crossings. */
	if (may_mend) {
		mend_outlines(&c, trouble, TROUBLE_CROSSING | TROUBLE_DIAGONAL, unclean, force, mended,
		              &st->mended);
		for (size_t l = 0; l < np; l++)
			again[l] = unclean[l] && !mended[l];
		mend_outlines(&c, trouble, TROUBLE_CROSSING_OTHER, again, force, mended, &st->mended);
	}
	st->duplicates_dropped += dup;
	st->planar_triangles = nplanar;
	st->free_faces = F.nf;
	rc = 0;
out:
	fct_chains_free(&c);
	fct_mesh_free(&F);
	free(vmap), free(corner), free(alive), free(again), free(wires), free(lab), free(tol);
	return rc;
}

/* Without a camera, drop the pieces of fewer than min_faces faces: a
 * fusion's floating debris (a fused scan's noise leaves thousands of small
 * pieces beside the room: tsdfuse's 20 7-Scenes frames at 1 cm, 2567 of
 * 2693 pieces under 64 faces, 3% of the faces).  A view's mesh keeps its
 * pieces: each is a surface the camera saw. */
static int drop_debris(struct fct_mesh *m, size_t min_faces, struct fct_planar_stats *st,
                       struct fct_err *err)
{
	struct fct_camera cam;
	int have_cam = fct_header_camera(m, &cam, err);
	if (have_cam)
		return have_cam < 0 ? -1 : 0;
	long n = fct_mesh_drop_small_pieces(m, min_faces, &st->debris_pieces, err);
	if (n < 0)
		return -1;
	st->debris_faces = (size_t)n;
	return 0;
}

/* A triangle thinner than this (twice its area over its longest edge
 * squared) has no area worth the name: 1.6 um across a 16 mm edge, which
 * writing the coordinates as float can make nothing. */
#define NO_AREA 1e-4
/* The rounds of fct_planar_model from which a triangle of no area takes
 * every creased vertex of its patch off its line, and every one of the
 * mesh: each round takes back at least one move or none is left, and the
 * rounds stay few. */
#define UNCREASE_PATCH 2
#define UNCREASE_ALL LAST_TIGHTENING
/* Creases taken off their lines in one round, at most (more: the patches'). */
#define MAX_BAD_CREASES 64

/* Vertex v of m back where its nearer plane alone put it, if
 * fct_planes_project put it on a crease line: 1, else 0. */
static int off_crease_line(struct fct_mesh *m, double *off_crease, uint32_t v)
{
	if (isnan(off_crease[3 * (size_t)v]))
		return 0;
	memcpy(m->xyz + 3 * (size_t)v, off_crease + 3 * (size_t)v, sizeof(double[3]));
	off_crease[3 * (size_t)v] = NAN;
	return 1;
}

/* The crease (its two patches, lower first) of vertex v, or 0 when v is not
 * between exactly two patches. */
static int crease_of(const int32_t *patch, const uint32_t *vstart, const uint32_t *vf, uint32_t v,
                     int32_t pair[2])
{
	int32_t ls[8];
	if (face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls) != 2)
		return 0;
	pair[0] = ls[0] < ls[1] ? ls[0] : ls[1];
	pair[1] = ls[0] < ls[1] ? ls[1] : ls[0];
	return 1;
}

/* Vertices that fct_planes_project put on two planes' line (off_crease not
 * NaN) can be three corners of one triangle of the model w (built on m's
 * vertices): the outline's points on a crease lie in their rays' order,
 * which noise shuffles, so an outline running along the line folds back on
 * itself, and triangulating in the image joins three of its points.  Such
 * a triangle has no area and no normal, and flipping cannot always remove
 * it (tripatch's flip_slivers: not where its longest edge is the outline).
 * Every creased vertex of the creases through the corners of each triangle
 * of w thinner than NO_AREA (a corner of one patch put on a line alone)
 * goes back where its nearer plane alone put it
 * (from round UNCREASE_PATCH on, every creased vertex of the triangle's
 * patch's faces in m; from UNCREASE_ALL on, every creased vertex), for
 * build_model to try again: the fold is the whole crease's, and taking
 * back only the corners leaves the next three points of it to meet.
 * vstart, vf: m's faces of each vertex; hit_patch is np bytes of scratch.
 * Returns the vertices taken back. */
static size_t uncrease_slivers(struct fct_mesh *m, double *off_crease, const int32_t *patch,
                               const uint32_t *vstart, const uint32_t *vf,
                               const struct fct_mesh *w, int round, unsigned char *hit_patch,
                               size_t np)
{
	size_t back = 0, nbad = 0;
	int32_t bad[MAX_BAD_CREASES][2];
	int any = 0, whole_patches = round >= UNCREASE_PATCH;
	const struct fct_prop *wp = fct_elem_find(&w->face, "patch");
	if (np)
		memset(hit_patch, 0, np);
	for (size_t f = 0; f < w->nf; f++) {
		uint32_t s = w->fstart[f];
		double n[3];
		if (w->fstart[f + 1] - s != 3 ||
		    !(thickness(w->xyz + 3 * (size_t)w->fvert[s], w->xyz + 3 * (size_t)w->fvert[s + 1],
		                w->xyz + 3 * (size_t)w->fvert[s + 2], n) < NO_AREA))
			continue;
		any = 1;
		long lab = wp ? (long)fct_prop_get(wp, f) : -1;
		if (lab >= 0 && (size_t)lab < np)
			hit_patch[lab] = 1;
		for (uint32_t q = s; q < s + 3; q++) {
			uint32_t v = w->fvert[q];
			int32_t pair[2];
			if (v >= m->nv || isnan(off_crease[3 * (size_t)v]))
				continue;
			if (!crease_of(patch, vstart, vf, v, pair)) {   /* a vertex of one patch */
				back += off_crease_line(m, off_crease, v);
				continue;
			}
			size_t k = 0;
			while (k < nbad && !(bad[k][0] == pair[0] && bad[k][1] == pair[1]))
				k++;
			if (k == nbad && nbad < MAX_BAD_CREASES)
				memcpy(bad[nbad++], pair, sizeof pair);
			else if (k == nbad)
				whole_patches = 1;
			back += off_crease_line(m, off_crease, v);
		}
	}
	if (!any)
		return back;
	if (!whole_patches) {
		for (uint32_t v = 0; v < m->nv; v++) {
			int32_t pair[2];
			if (isnan(off_crease[3 * (size_t)v]) || !crease_of(patch, vstart, vf, v, pair))
				continue;
			for (size_t k = 0; k < nbad; k++)
				if (bad[k][0] == pair[0] && bad[k][1] == pair[1]) {
					back += off_crease_line(m, off_crease, v);
					break;
				}
		}
		return back;
	}
	for (size_t f = 0; f < m->nf; f++) {
		if (round < UNCREASE_ALL && !(patch[f] >= 0 && hit_patch[patch[f]]))
			continue;
		for (uint32_t q = m->fstart[f]; q < m->fstart[f + 1]; q++)
			back += off_crease_line(m, off_crease, m->fvert[q]);
	}
	return back;
}

/* Each vertex marked occluded (fct_planes_project: a crease there would
 * hide its sample) is split: the faces of its patch whose plane it is not
 * on get a copy on that plane along its ray (before the sample at a sine
 * of MIN_GRAZING or more; else straight across), so that the two patches
 * meet there in no vertex: an occlusion border for each.  sigma and
 * off_crease grow with the vertices. */
static int split_occluded(struct fct_mesh *m, const int32_t *patch, const struct fct_plane *planes,
                          const double *vp, const unsigned char *occluded, double **sigma,
                          double **off_crease, size_t *split, struct fct_err *err)
{
	*split = 0;
	size_t nv0 = m->nv, n = 0;
	for (size_t v = 0; v < nv0; v++)
		n += occluded[v];
	if (!n)
		return 0;
	uint32_t *vstart, *vf;
	if (fct_vertex_faces(m, &vstart, &vf, err))
		return -1;
	double *sg = realloc(*sigma, (nv0 + n) * sizeof *sg);
	if (!sg) {
		free(vstart), free(vf);
		return fct_fail(err, "out of memory");
	}
	*sigma = sg;
	double *oc = realloc(*off_crease, 3 * (nv0 + n) * sizeof *oc);
	if (!oc) {
		free(vstart), free(vf);
		return fct_fail(err, "out of memory");
	}
	*off_crease = oc;
	if (fct_mesh_set_vertex_count(m, nv0 + n, err)) {
		free(vstart), free(vf);
		return -1;
	}
	size_t c = nv0;
	for (size_t v = 0; v < nv0; v++) {
		if (!occluded[v])
			continue;
		int32_t ls[8];
		int k = face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls);
		const double *p = m->xyz + 3 * v;
		double r0 = fabs(fct_v3_dot(planes[ls[0]].n, p) + planes[ls[0]].d);
		double r1 = k > 1 ? fabs(fct_v3_dot(planes[ls[1]].n, p) + planes[ls[1]].d) : 0;
		int32_t other = k > 1 ? (r0 <= r1 ? ls[1] : ls[0]) : -1;
		double x[3], r = other >= 0 ? fct_v3_dot(planes[other].n, p) + planes[other].d : 0;
		memcpy(x, p, sizeof x);
		if (other >= 0) {
			onto_planes(planes, &other, 1, p, x);
			double y[3];
			if (along_ray(planes, &other, 1, vp, p, y) && met_before(vp, p, y, r))
				memcpy(x, y, sizeof y);
		}
		copy_vertex_for(m, patch, vf + vstart[v], vstart[v + 1] - vstart[v], (uint32_t)v, c, other, x);
		sg[c] = sg[v];
		oc[3 * c] = NAN;
		c++;
	}
	*split = n;
	free(vstart), free(vf);
	return 0;
}

/* *n: the free-form faces of the model m with a corner on one of its open
 * borders (edges of one face).  Where a model's faces go: on a scan's
 * ragged open borders the free-form decimation keeps a vertex every few
 * samples (the 20 7-Scenes frames fused at 1 cm: 8306 of the model's 15733
 * faces, bench/NOTES.md). */
static int count_border_free(const struct fct_mesh *m, size_t *n, struct fct_err *err)
{
	*n = 0;
	int32_t *lab = NULL;
	int present = 0;
	struct fct_adj adj;
	if (fct_patches_get(m, &lab, &present, -1, err))
		return -1;
	if (fct_adj_build(&adj, m, err)) {
		free(lab);
		return -1;
	}
	unsigned char *on = calloc(m->nv ? m->nv : 1, 1);
	if (!on) {
		free(lab);
		fct_adj_free(&adj);
		return fct_fail(err, "out of memory");
	}
	for (size_t e = 0; e < adj.ne; e++)
		if (fct_adj_edge_nfaces(&adj, e) == 1)
			on[adj.edge_v[2 * e]] = on[adj.edge_v[2 * e + 1]] = 1;
	for (size_t f = 0; f < m->nf; f++) {
		if (present && lab[f] >= 0)
			continue;
		uint32_t c = m->fstart[f];
		while (c < m->fstart[f + 1] && !on[m->fvert[c]])
			c++;
		*n += c < m->fstart[f + 1];
	}
	free(on), free(lab);
	fct_adj_free(&adj);
	return 0;
}

/* The vertices of the faces whose patch became free-form (only[v] set on
 * entry) that still have a patch go back to their samples (sample: the
 * first nsample vertices' positions before fct_planes_project) and are
 * projected again onto the nearest plane of the patches they have now;
 * only[] is left set for those alone.  Projection put a vertex where two
 * patches met onto the nearer plane, which may be the one gone: left
 * there, it lies off its other patch's plane by as much as the crease's
 * noise, and fct_planes_meet tore it from that patch, a crack beside the
 * free-form faces (the carved fusion of the 20 7-Scenes frames with a
 * sigma per vertex: 14 vertices 1.2-2.3 cm off the plane, 42 border edges
 * in the model of a watertight mesh).  A vertex left with no patch stays
 * on the plane it was put on, within its noise of its sample.  Copies
 * split_occluded made (from nsample on) have one patch each and no sample
 * of their own: they stay.  vstart, vf: m's faces of each vertex.  *n gets
 * the vertices that moved onto a plane from their samples. */
static int reproject_orphans(struct fct_mesh *m, const int32_t *patch, const uint32_t *vstart,
                             const uint32_t *vf, const double *sample, size_t nsample,
                             unsigned char *only, const struct fct_plane *pl,
                             const double *vp, const double *sigma, double pixel_angle,
                             double max_move, double *off_crease, size_t *n, struct fct_err *err)
{
	*n = 0;
	int any = 0;
	for (size_t v = 0; v < m->nv; v++) {
		int32_t ls[8];
		if (only[v] && (v >= nsample || !face_labels(patch, vf + vstart[v], vstart[v + 1] - vstart[v], ls)))
			only[v] = 0;
		if (!only[v])
			continue;
		memcpy(m->xyz + 3 * v, sample + 3 * v, sizeof(double[3]));
		any = 1;
	}
	size_t creased;
	if (!any)
		return 0;
	return project_vertices(m, vstart, vf, patch, pl, vp, sigma, pixel_angle, max_move, off_crease,
	                        NULL, only, n, &creased, err);
}

/* The labels tidied (fct_patches_unfacet, fct_patches_tidy) and the vertices
 * put on their planes (fct_planes_project), all on one adjacency of m:
 * none of them changes its faces.  cam: NULL without a camera, else vp its
 * viewpoint.  *sample gets the positions before, *off_crease and
 * *occluded fct_planes_project's. */
static int label_and_project(struct fct_mesh *m, int32_t *patch, const struct fct_plane *pl,
                             size_t np, const struct fct_camera *cam, const double *vp,
                             const double *sigma, const struct fct_planar_params *p,
                             double **sample, size_t *nsample, double **off_crease,
                             unsigned char **occluded, struct fct_planar_stats *st,
                             struct fct_err *err)
{
	struct fct_adj adj;
	if (fct_adj_build(&adj, m, err))
		return -1;
	size_t nv = m->nv ? m->nv : 1;
	int rc = -1;
	if (fct_patches_unfacet(patch, m, &adj, pl, np, p->facet_angle, 0.5, &st->facets, err) ||
	    fct_patches_tidy(patch, m, &adj, pl, np, !cam, sigma, p->max_move, p->min_plane,
	                     p->min_free, &st->tidy, err) ||
	    !(*sample = copy_positions(m, nsample, err)) ||
	    !(*off_crease = fct_alloc_array(3 * nv, sizeof **off_crease, err)) ||
	    !(*occluded = fct_alloc_array(nv, 1, err)))
		goto out;
	memset(*occluded, 0, nv);
	rc = fct_planes_project(m, &adj, patch, pl, cam ? vp : NULL, sigma,
	                        cam ? fct_camera_pixel_angle(cam) : 0, p->max_move, *off_crease,
	                        cam ? *occluded : NULL, &st->projected, &st->creased, err);
out:
	fct_adj_free(&adj);
	return rc;
}

int fct_planar_model(struct fct_mesh *m, const struct fct_planar_params *p,
                     struct fct_planar_stats *st, struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	struct fct_plane *pl = NULL;
	size_t np = 0;
	int32_t *patch = NULL;
	double *sigma = NULL, *spacing = NULL, *off_crease = NULL, *sample = NULL;
	unsigned char *occluded = NULL, *orphan = NULL;
	size_t nsample = 0;
	unsigned char *unclean = NULL, *tight = NULL, *force = NULL, *trouble = NULL, *hit_patch = NULL;
	size_t *nfaces = NULL, *mended = NULL;
	struct fct_mesh w;
	fct_mesh_init(&w);
	struct rounds carry;
	memset(&carry, 0, sizeof carry);
	int present = 0, rc = -1;
	double input_spacing = 0;
	st->vertices_in = m->nv, st->faces_in = m->nf;
	if (fct_planes_get(m, &pl, &np, err) || fct_patches_get(m, &patch, &present, (long)np, err))
		goto out;
	if (!present) {
		fct_fail(err, "no face property patch: segment it first (segplanes)");
		goto out;
	}
	if (drop_debris(m, p->min_piece, st, err))
		goto out;
	if (st->debris_faces) {   /* the labels of the faces kept */
		free(patch);
		patch = NULL;
		if (fct_patches_get(m, &patch, &present, (long)np, err))
			goto out;
	}
	st->planes = np;
	struct fct_camera cam;
	double pose[12], inv[12], vp[3] = {0, 0, 0};
	int have_cam = fct_header_camera(m, &cam, err), have_pose = 0;
	if (have_cam < 0 || (have_cam > 0 && (have_pose = fct_header_pose(m, pose, err)) < 0))
		goto out;
	if (have_pose) {
		fct_pose_invert(pose, inv);
		vp[0] = pose[3], vp[1] = pose[7], vp[2] = pose[11];
	}
	/* Without a camera, the small holes of a fused scan are mostly voxels
	 * no view saw (a fusion of noisy views leaves hundreds); the free-form
	 * decimation would keep each one's border, a triangle at least with
	 * its fan around it (the 20 7-Scenes frames fused at 1 cm: 790 of the
	 * model's 1019 border loops were triangles).  Those whose border lies
	 * within the noise of one plane are filled; one across a depth jump is
	 * what a view did not see past an occlusion, as is every hole with a
	 * camera: it stays. */
	if (vertex_sigma(m, pl, np, &sigma, &st->sigma_estimated, err) ||
	    (!have_cam && p->max_hole >= 3 &&
	     fct_fill_free_holes(m, &patch, pl, np, p->max_hole, sigma, p->max_move,
	                         &st->free_holes_filled, err)) ||
	    label_and_project(m, patch, pl, np, have_cam ? &cam : NULL, vp, sigma, p, &sample,
	                      &nsample, &off_crease, &occluded, st, err) ||
	    split_occluded(m, patch, pl, vp, occluded, &sigma, &off_crease, &st->split, err) ||
	    (p->max_hole >= 3 &&
	     fct_fill_plane_holes(m, &patch, pl, np, p->max_hole, &st->holes_filled, err)) ||
	    !(spacing = sample_spacing(m, have_cam ? &cam : NULL, vp, input_spacing = mean_edge(m), err)) ||
	    !(unclean = calloc(np ? np : 1, 1)) || !(tight = calloc(np ? np : 1, 1)) ||
	    !(force = calloc(m->nv ? m->nv : 1, 1)) ||
	    !(trouble = calloc(m->nv ? m->nv : 1, 1)) || !(hit_patch = calloc(np ? np : 1, 1)) ||
	    !(nfaces = calloc(np ? np : 1, sizeof *nfaces)) ||
	    !(mended = calloc(np ? np : 1, sizeof *mended)) || !(orphan = calloc(m->nv ? m->nv : 1, 1)))
		goto out;
	for (size_t f = 0; f < m->nf; f++)
		if (patch[f] >= 0)
			nfaces[patch[f]]++;
	/* Rounds, until every patch triangulates cleanly from its outline.  A
	 * patch whose loops cross (in both frames tripatch tries), or whose
	 * triangles put a diagonal on an edge that exists elsewhere, is mended
	 * where that happens (mend_outlines: the segments there kept as
	 * sampled) and tried again; one that cannot be mended there has its
	 * whole outline tightened if large, and becomes free-form if small or
	 * still unclean.  From round LAST_TIGHTENING on nothing is mended or
	 * tightened any more: each round makes a patch free-form or ends, so
	 * the rounds end (a fused scan's 50 patches were still pinning after
	 * 8). */
	for (int round = 0;; round++) {
		int may_tighten = round < LAST_TIGHTENING;
		memset(unclean, 0, np ? np : 1);
		memset(trouble, 0, m->nv ? m->nv : 1);
		memset(mended, 0, (np ? np : 1) * sizeof *mended);
		fct_mesh_free(&w);
		fct_mesh_init(&w);
		size_t more = 0;
		if (build_model(&w, m, patch, pl, np, sigma, spacing, have_cam ? vp : NULL, p, tight,
		                may_tighten, force, trouble, mended, unclean, &carry, st, err))
			goto out;
		/* (build_model left m's adjacency in carry: the mesh's faces
		 * stay the same from round to round) */
		size_t back = st->creased && carry.have_adj ?
		              uncrease_slivers(m, off_crease, patch, carry.adj.vert_fstart, carry.adj.vert_f,
		                               &w, round, hit_patch, np) : 0;
		st->uncreased += back;
		more += back;
		/* Unclean: a patch mended tries again; else a small one
		 * becomes free-form, and a large one's whole outline is
		 * tightened (halved, then halved again, then kept as sampled;
		 * free-form when still unclean). */
		/* The small patches made free-form may be what spoils a large
		 * one (a diagonal across both): its whole outline waits a round. */
		int small_gone = 0;
		for (size_t l = 0; l < np; l++)
			small_gone |= unclean[l] && !mended[l] && nfaces[l] < m->nf / LARGE_PATCH;
		for (size_t l = 0; l < np; l++)
			if (unclean[l] && mended[l])
				unclean[l] = 0, more++;
			else if (unclean[l] && small_gone && round + 1 < LAST_TIGHTENING &&
			         nfaces[l] >= m->nf / LARGE_PATCH)
				unclean[l] = 0;
			else if (may_tighten && unclean[l] && tight[l] < AS_SAMPLED && nfaces[l] >= m->nf / LARGE_PATCH) {
				tight[l]++, unclean[l] = 0, more++;
				st->tightened++;
				st->dense_patches += tight[l] == AS_SAMPLED;
			}
		int gone = 0;
		for (size_t f = 0; f < m->nf; f++)
			if (patch[f] >= 0 && unclean[patch[f]]) {
				patch[f] = -1, more++, gone = 1;
				for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++)
					orphan[m->fvert[c]] = 1;
			}
		/* (carry's adjacency is m's: its faces stay the same) */
		size_t again_moved = 0;
		if (gone && reproject_orphans(m, patch, carry.adj.vert_fstart, carry.adj.vert_f, sample, nsample,
		                              orphan, pl, have_cam ? vp : NULL, sigma,
		                              have_cam ? fct_camera_pixel_angle(&cam) : 0, p->max_move,
		                              off_crease, &again_moved, err))
			goto out;
		st->reprojected += again_moved;
		if (gone)
			memset(orphan, 0, m->nv);
		if (!more)
			break;
		st->rounds++;
		for (size_t l = 0; l < np; l++)
			st->unclean_patches += unclean[l];
	}
	fct_mesh_free(m);
	*m = w;
	fct_mesh_init(&w);
	free(patch), free(sigma);
	patch = NULL, sigma = NULL;
	int estimated, dummy;
	if (fct_patches_get(m, &patch, &dummy, (long)np, err) || drop_unused_vertices(m, err) ||
	    vertex_sigma(m, pl, np, &sigma, &estimated, err))
		goto out;
	free(patch);
	patch = NULL;
	free(spacing);
	if (fct_patches_get(m, &patch, &dummy, (long)np, err) ||
	    !(spacing = sample_spacing(m, have_cam ? &cam : NULL, vp, input_spacing, err)) ||
	    fct_planes_meet(m, patch, pl, sigma, spacing, p->max_move, have_cam ? vp : NULL, &st->meet,
	                    err) ||
	    drop_unused_vertices(m, err))
		goto out;
	if (count_border_free(m, &st->border_free_faces, err))
		goto out;
	if (have_cam && fct_elem_find(&m->vertex, "s") && fct_elem_find(&m->vertex, "t") &&
	    fct_camera_texcoords(m, &cam, have_pose ? inv : NULL, &st->no_pixel, err))
		goto out;
	st->vertices_out = m->nv, st->faces_out = m->nf;
	rc = 0;
out:
	fct_mesh_free(&w);
	rounds_free(&carry);
	free(pl), free(patch), free(sigma), free(spacing), free(unclean), free(tight), free(nfaces);
	free(force), free(trouble), free(mended), free(off_crease), free(hit_patch), free(occluded);
	free(sample), free(orphan);
	return rc;
}

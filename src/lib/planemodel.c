/* planemodel.c - the planar model's preparation of a segmentation (see
 * planemodel.h). */
#include "planemodel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "adj.h"
#include "geom.h"
#include "polytri.h"

/* Union-find root of x (negative entries: roots, minus their size). */
static uint32_t uf_find(int32_t *parent, uint32_t x)
{
	while (parent[x] >= 0) {
		int32_t p = parent[x];
		if (parent[p] >= 0)
			parent[x] = parent[p];
		x = (uint32_t)p;
	}
	return x;
}

int fct_patches_tidy(int32_t *patch, const struct fct_mesh *m, size_t min_plane, size_t min_free,
                     struct fct_tidy_stats *st, struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	size_t nf = m->nf;
	struct fct_adj adj;
	if (fct_adj_build(&adj, m, err))
		return -1;
	int32_t *root = fct_alloc_array(nf ? nf : 1, sizeof *root, err);
	int32_t *host = fct_alloc_array(nf ? nf : 1, sizeof *host, err);
	uint32_t *count = fct_alloc_array(nf ? nf : 1, sizeof *count, err);
	if (!root || !host || !count) {
		free(root), free(host), free(count);
		fct_adj_free(&adj);
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
	/* Pieces of free-form faces (joined across edges), their size and the
	 * one patch around them (-2: none yet, -3: more than one). */
	for (size_t f = 0; f < nf; f++)
		root[f] = -1, host[f] = -2;
	for (size_t e = 0; e < adj.ne; e++) {
		const uint32_t *fs = &adj.edge_f[adj.edge_fstart[e]];
		uint32_t k = fct_adj_edge_nfaces(&adj, e);
		for (uint32_t i = 0; i < k; i++)
			for (uint32_t j = i + 1; j < k; j++)
				if (patch[fs[i]] < 0 && patch[fs[j]] < 0) {
					uint32_t a = uf_find(root, fs[i]), b = uf_find(root, fs[j]);
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
	for (size_t e = 0; e < adj.ne; e++) {
		const uint32_t *fs = &adj.edge_f[adj.edge_fstart[e]];
		uint32_t k = fct_adj_edge_nfaces(&adj, e);
		for (uint32_t i = 0; i < k; i++)
			for (uint32_t j = 0; j < k; j++) {
				if (patch[fs[i]] >= 0 || patch[fs[j]] < 0)
					continue;
				uint32_t r = uf_find(root, fs[i]);
				if (host[r] == -2)
					host[r] = patch[fs[j]];
				else if (host[r] != patch[fs[j]])
					host[r] = -3;
			}
	}
	for (size_t f = 0; f < nf; f++) {
		if (patch[f] >= 0)
			continue;
		uint32_t r = uf_find(root, (uint32_t)f);
		if (host[r] >= 0 && (size_t)(-root[r]) < min_free) {
			patch[f] = host[r];
			st->speck_faces++;
		}
	}
	free(root), free(host), free(count);
	fct_adj_free(&adj);
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

/* Fill one hole: loop[0..k) in border order (faces on its left), inside
 * patch p. */
static int fill_loop(struct fct_mesh *m, int32_t **patch, const struct fct_plane *pl, int32_t p,
                     const uint32_t *loop, size_t k, size_t *filled, struct fct_err *err)
{
	double u[3], v[3], *xy = fct_alloc_array(2 * k, sizeof *xy, err);
	uint32_t *lv = fct_alloc_array(k, sizeof *lv, err), lstart[2] = {0, (uint32_t)k};
	uint32_t *tri = NULL;
	size_t ntri = 0;
	int rc = -1;
	if (!xy || !lv)
		goto out;
	plane_frame(pl->n, u, v);
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
	int r = fct_polytri(xy, k, lstart, 1, lv, FCT_POLYTRI_GREEDY, &tri, &ntri, NULL, &local);
	if (r != 0) {
		rc = r > 0 ? 0 : fct_fail(err, "%s", local.msg);
		goto out;
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

int fct_fill_plane_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                         size_t nplanes, size_t max_edges, size_t *filled, struct fct_err *err)
{
	*filled = 0;
	struct fct_adj adj;
	if (fct_adj_build(&adj, m, err))
		return -1;
	size_t nv1 = m->nv ? m->nv : 1;
	uint32_t *next = fct_alloc_array(nv1, sizeof *next, err);
	uint32_t *face = fct_alloc_array(nv1, sizeof *face, err);
	unsigned char *outdeg = fct_alloc_array(nv1, 1, err);
	uint32_t *loop = fct_alloc_array(max_edges + 1, sizeof *loop, err);
	int rc = -1;
	if (!next || !face || !outdeg || !loop)
		goto out;
	memset(outdeg, 0, nv1);
	/* Each border edge as its face walks it: a -> b, the face on its left. */
	for (size_t f = 0; f < m->nf; f++) {
		uint32_t s = m->fstart[f], n = m->fstart[f + 1] - s;
		for (uint32_t c = 0; c < n; c++) {
			uint32_t e = adj.face_e[s + c];
			if (e == FCT_ADJ_NONE || fct_adj_edge_nfaces(&adj, e) != 1)
				continue;
			uint32_t a = m->fvert[s + c], b = m->fvert[s + (c + 1) % n];
			next[a] = b, face[a] = (uint32_t)f;
			outdeg[a] += outdeg[a] < 2;
		}
	}
	size_t nf0 = m->nf;
	for (size_t a = 0; a < m->nv; a++) {
		if (outdeg[a] != 1)
			continue;
		/* Walk the loop from its lowest vertex only, once. */
		size_t k = 0;
		uint32_t x = (uint32_t)a;
		int ok = 1;
		do {
			if (outdeg[x] != 1 || x < a || k == max_edges) {
				ok = 0;
				break;
			}
			loop[k++] = x;
			x = next[x];
		} while (x != a);
		if (!ok || k < 3)
			continue;
		int32_t p = face[loop[0]] < nf0 ? (*patch)[face[loop[0]]] : -1;
		for (size_t i = 1; i < k && p >= 0; i++)
			if ((*patch)[face[loop[i]]] != p)
				p = -1;
		if (p < 0 || (size_t)p >= nplanes)
			continue;
		if (fill_loop(m, patch, &planes[p], p, loop, k, filled, err))
			goto out;
	}
	rc = 0;
out:
	free(next), free(face), free(outdeg), free(loop);
	fct_adj_free(&adj);
	return rc;
}

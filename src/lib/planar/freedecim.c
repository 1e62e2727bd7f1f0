/* freedecim.c - the free-form faces decimated piece by piece, unchanged
 * pieces remembered from the round before (see freedecim.h). */
#include "planar/freedecim.h"

#include <stdlib.h>
#include <string.h>

#include "core/unionfind.h"

/* A piece of the last round: its face count and its decimation's figures. */
struct fct_free_piece {
	size_t nfaces;
	struct fct_qem_stats st;
};

/* A surviving triangle: the face of m it came from, its place among the
 * triangles collected (to keep a fanned face's triangles in order), its
 * corners as m's vertices. */
struct fct_free_tri {
	uint32_t face, seq;
	uint32_t v[3];
};

void fct_free_cache_free(struct fct_free_cache *c)
{
	free(c->dead), free(c->xyz), free(c->attr), free(c->corner), free(c->in), free(c->piece);
	free(c->pieces), free(c->tri);
	memset(c, 0, sizeof *c);
}

/* m's scalar vertex properties, the ones a decimation carries per vertex
 * (the float and double ones interpolated, the others the kept end's). */
static int carried(const struct fct_prop *p)
{
	return p->count_type == FCT_NONE;
}

/* The centre of the whole mesh, as fct_qem_decimate takes it, and every
 * vertex as m has it. */
static int cache_init(struct fct_free_cache *c, const struct fct_mesh *m, struct fct_err *err)
{
	if (fct_qem_centre(c->centre, m, err))
		return -1;
	c->nv = m->nv, c->nf = m->nf;
	c->nattr = 0;
	for (size_t j = 0; j < m->vertex.nprops; j++)
		c->nattr += carried(&m->vertex.props[j]);
	size_t nv1 = m->nv ? m->nv : 1;
	if (!(c->dead = fct_alloc_array(nv1, 1, err)) ||
	    !(c->xyz = fct_alloc_array(3 * nv1, sizeof *c->xyz, err)) ||
	    !(c->attr = fct_alloc_array(c->nattr * nv1 + 1, sizeof *c->attr, err)) ||
	    !(c->corner = fct_alloc_array(nv1, 1, err)) ||
	    !(c->in = fct_alloc_array(3 * nv1, sizeof *c->in, err)) ||
	    !(c->piece = fct_alloc_array(m->nf ? m->nf : 1, sizeof *c->piece, err)))
		return -1;
	memset(c->dead, 0, nv1);
	memset(c->corner, 0, nv1);
	if (m->nv) {
		memcpy(c->xyz, m->xyz, 3 * m->nv * sizeof *m->xyz);
		memcpy(c->in, m->xyz, 3 * m->nv * sizeof *m->xyz);
	}
	size_t col = 0;
	for (size_t j = 0; j < m->vertex.nprops; j++) {
		const struct fct_prop *p = &m->vertex.props[j];
		if (!carried(p))
			continue;
		for (size_t v = 0; v < m->nv; v++)
			c->attr[c->nattr * v + col] = fct_prop_get(p, v);
		col++;
	}
	for (size_t f = 0; f < m->nf; f++)
		c->piece[f] = -1;
	c->valid = 1;
	return 0;
}

/* The pieces: vpiece[v] and fpiece[f] (-1 off the free faces), numbered
 * in the order of their first face; their vertices vlist[vstart[k] ..
 * vstart[k + 1]) and faces flist[fstart[k] .. fstart[k + 1]), each in
 * increasing order.  Returns the number of pieces. */
static size_t find_pieces(const struct fct_mesh *m, const unsigned char *is_free, int32_t *up,
                          int32_t *vpiece, int32_t *fpiece, uint32_t *vstart, uint32_t *vlist,
                          uint32_t *fstart, uint32_t *flist)
{
	for (size_t v = 0; v < m->nv; v++)
		up[v] = -1, vpiece[v] = -1;
	for (size_t f = 0; f < m->nf; f++) {
		if (!is_free[f] || m->fstart[f] == m->fstart[f + 1])
			continue;
		uint32_t r = fct_uf_root(up, m->fvert[m->fstart[f]]);
		for (uint32_t i = m->fstart[f] + 1; i < m->fstart[f + 1]; i++) {
			uint32_t s = fct_uf_root(up, m->fvert[i]);
			if (s == r)
				continue;
			if (up[s] < up[r]) {
				uint32_t t = r;
				r = s, s = t;
			}
			up[r] += up[s];
			up[s] = (int32_t)r;
		}
	}
	/* Number the roots in face order; vpiece first holds the root's number. */
	size_t np = 0;
	for (size_t f = 0; f < m->nf; f++) {
		fpiece[f] = -1;
		if (!is_free[f] || m->fstart[f] == m->fstart[f + 1])
			continue;
		uint32_t r = fct_uf_root(up, m->fvert[m->fstart[f]]);
		if (vpiece[r] < 0)
			vpiece[r] = (int32_t)np++;
		fpiece[f] = vpiece[r];
	}
	for (size_t f = 0; f < m->nf; f++)
		if (fpiece[f] >= 0)
			for (uint32_t i = m->fstart[f]; i < m->fstart[f + 1]; i++)
				vpiece[m->fvert[i]] = fpiece[f];
	memset(vstart, 0, (np + 1) * sizeof *vstart);
	memset(fstart, 0, (np + 1) * sizeof *fstart);
	for (size_t v = 0; v < m->nv; v++)
		if (vpiece[v] >= 0)
			vstart[vpiece[v] + 1]++;
	for (size_t f = 0; f < m->nf; f++)
		if (fpiece[f] >= 0)
			fstart[fpiece[f] + 1]++;
	for (size_t k = 0; k < np; k++)
		vstart[k + 1] += vstart[k], fstart[k + 1] += fstart[k];
	for (size_t v = 0; v < m->nv; v++)
		if (vpiece[v] >= 0)
			vlist[vstart[vpiece[v]]++] = (uint32_t)v;
	for (size_t f = 0; f < m->nf; f++)
		if (fpiece[f] >= 0)
			flist[fstart[fpiece[f]]++] = (uint32_t)f;
	for (size_t k = np; k > 0; k--)
		vstart[k] = vstart[k - 1], fstart[k] = fstart[k - 1];
	vstart[0] = fstart[0] = 0;
	return np;
}

/* Is piece k (its faces fl[0 .. nf), vertices vl[0 .. nv)) the last
 * round's, decimated with these corners and its vertices where m has them
 * (a vertex a round put back off a crease line moves)? */
static int unchanged(const struct fct_free_cache *c, const struct fct_mesh *m, const uint32_t *fl,
                     size_t nf, const uint32_t *vl, size_t nv, const unsigned char *corner)
{
	int32_t old = c->piece[fl[0]];
	if (old < 0 || c->pieces[old].nfaces != nf)
		return 0;
	for (size_t i = 1; i < nf; i++)
		if (c->piece[fl[i]] != old)
			return 0;
	for (size_t i = 0; i < nv; i++)
		if ((corner ? corner[vl[i]] : 0) != c->corner[vl[i]] ||
		    memcmp(c->in + 3 * (size_t)vl[i], m->xyz + 3 * (size_t)vl[i], 3 * sizeof *m->xyz))
			return 0;
	return 1;
}

static int tri_order(const void *x, const void *y)
{
	const struct fct_free_tri *a = x, *b = y;
	if (a->face != b->face)
		return a->face < b->face ? -1 : 1;
	return a->seq < b->seq ? -1 : a->seq > b->seq;
}

/* Decimate one piece (faces fl[0 .. nf), vertices vl[0 .. nv)) alone,
 * with the whole mesh's centre: its survivors into the cache's vertex
 * arrays, its triangles appended to tri (*ntri, room for all), its
 * figures into *st.  local: scratch of m's vertices. */
static int run_piece(struct fct_free_cache *c, const struct fct_mesh *m, const uint32_t *fl,
                     size_t nf, const uint32_t *vl, size_t nv, const struct fct_qem_params *qp,
                     uint32_t *local, struct fct_free_tri *tri, size_t *ntri,
                     struct fct_qem_stats *st, struct fct_err *err)
{
	struct fct_mesh s;
	fct_mesh_init(&s);
	unsigned char *corner = NULL;
	double *sigma = NULL;
	uint32_t *fv = NULL;
	size_t fvcap = 0;
	int rc = -1;
	if (fct_mesh_set_vertex_count(&s, nv, err))
		goto out;
	for (size_t i = 0; i < nv; i++) {
		local[vl[i]] = (uint32_t)i;
		memcpy(s.xyz + 3 * i, m->xyz + 3 * (size_t)vl[i], sizeof(double[3]));
	}
	for (size_t j = 0; j < m->vertex.nprops; j++) {
		const struct fct_prop *p = &m->vertex.props[j];
		if (carried(p) && !fct_elem_add_scalar(&s.vertex, p->name, p->type, err))
			goto out;
	}
	struct fct_prop *idx = fct_elem_add_scalar(&s.vertex, "fct_vertex", FCT_UINT32, err);
	if (!idx)
		goto out;
	for (size_t j = 0, col = 0; j < m->vertex.nprops; j++) {
		const struct fct_prop *p = &m->vertex.props[j];
		if (!carried(p))
			continue;
		struct fct_prop *q = &s.vertex.props[col++];
		for (size_t i = 0; i < nv; i++)
			fct_prop_set(q, i, fct_prop_get(p, vl[i]));
	}
	for (size_t i = 0; i < nv; i++)
		fct_prop_set(idx, i, (double)vl[i]);
	for (size_t i = 0; i < nf; i++) {
		uint32_t f = fl[i], n = fct_face_size(m, f);
		if (fct_grow((void **)&fv, &fvcap, n, sizeof *fv, err))
			goto out;
		for (uint32_t k = 0; k < n; k++)
			fv[k] = local[m->fvert[m->fstart[f] + k]];
		if (fct_mesh_add_face(&s, fv, n, err) < 0)
			goto out;
	}
	struct fct_prop *fidx = fct_elem_add_scalar(&s.face, "fct_face", FCT_UINT32, err);
	if (!fidx)
		goto out;
	for (size_t i = 0; i < nf; i++)
		fct_prop_set(fidx, i, (double)fl[i]);
	struct fct_qem_params p = *qp;
	p.use_centre = 1;
	memcpy(p.centre, c->centre, sizeof p.centre);
	if ((qp->corner && !(corner = fct_alloc_array(nv ? nv : 1, 1, err))) ||
	    (qp->sigma && !(sigma = fct_alloc_array(nv ? nv : 1, sizeof *sigma, err))))
		goto out;
	for (size_t i = 0; i < nv; i++) {
		if (corner)
			corner[i] = qp->corner[vl[i]];
		if (sigma)
			sigma[i] = qp->sigma[vl[i]];
	}
	p.corner = corner;
	p.sigma = sigma;
	if (fct_qem_decimate(&s, &p, st, err))
		goto out;
	/* The survivors, then the triangles on m's vertex numbers. */
	for (size_t i = 0; i < nv; i++) {
		c->dead[vl[i]] = 1;
		c->corner[vl[i]] = qp->corner ? qp->corner[vl[i]] : 0;
		memcpy(c->in + 3 * (size_t)vl[i], m->xyz + 3 * (size_t)vl[i], 3 * sizeof *m->xyz);
	}
	idx = fct_elem_find(&s.vertex, "fct_vertex");
	fidx = fct_elem_find(&s.face, "fct_face");
	for (size_t i = 0; i < s.nv; i++) {
		uint32_t v = (uint32_t)fct_prop_get(idx, i);
		local[i] = v;   /* s's survivor i is m's v (local's first use is over) */
		c->dead[v] = 0;
		memcpy(c->xyz + 3 * (size_t)v, s.xyz + 3 * i, sizeof(double[3]));
		for (size_t j = 0; j < c->nattr; j++)
			c->attr[c->nattr * v + j] = fct_prop_get(&s.vertex.props[j], i);
	}
	for (size_t f = 0; f < s.nf; f++) {
		struct fct_free_tri *t = &tri[(*ntri)];
		t->face = (uint32_t)fct_prop_get(fidx, f);
		t->seq = (uint32_t)*ntri;
		for (int k = 0; k < 3; k++)
			t->v[k] = local[s.fvert[3 * f + (size_t)k]];
		(*ntri)++;
	}
	rc = 0;
out:
	fct_mesh_free(&s);
	free(corner), free(sigma), free(fv);
	return rc;
}

/* The figures of the whole decimation from its pieces' (np of them, with
 * their vertices vstart/vlist): sums, and the largest errors and passes;
 * corners counted as the whole would count them, over every vertex. */
static void add_figures(struct fct_qem_stats *qs, const struct fct_free_piece *pc, size_t np,
                        const uint32_t *vstart, const uint32_t *vlist, const int32_t *vpiece,
                        const struct fct_mesh *m, const unsigned char *corner)
{
	for (size_t k = 0; k < np; k++) {
		const struct fct_qem_stats *s = &pc[k].st;
		qs->faces_in += s->faces_in;
		qs->dropped += s->dropped;
		qs->locked += s->locked;
		qs->collapses += s->collapses;
		qs->refused_topology += s->refused_topology;
		qs->refused_flip += s->refused_flip;
		qs->refused_error += s->refused_error;
		qs->holes_closed += s->holes_closed;
		qs->corners += s->corners;
		qs->passes = s->passes > qs->passes ? s->passes : qs->passes;
		qs->max_error = s->max_error > qs->max_error ? s->max_error : qs->max_error;
		qs->max_cost = s->max_cost > qs->max_cost ? s->max_cost : qs->max_cost;
		/* A piece of no triangle stops before it classes its vertices;
		 * the whole would class them (as corners where flagged). */
		if (s->faces_in == 0 && corner)
			for (uint32_t i = vstart[k]; i < vstart[k + 1]; i++)
				qs->corners += corner[vlist[i]] != 0;
	}
	/* The whole runs passes until none collapses anything; a piece that
	 * is done sooner refuses again in each pass after its own last what it
	 * refused in that one. */
	for (size_t k = 0; k < np; k++) {
		const struct fct_qem_stats *s = &pc[k].st;
		size_t more = qs->passes - s->passes;
		if (s->passes == 0)
			continue;
		qs->refused_topology += more * s->last_refused[0];
		qs->refused_flip += more * s->last_refused[1];
		qs->refused_error += more * s->last_refused[2];
		for (int i = 0; i < 3; i++)
			qs->last_refused[i] += s->last_refused[i];
	}
	/* With no triangle at all the whole stops before classing any vertex;
	 * else the vertices of no piece are corners where flagged. */
	if (qs->faces_in == 0) {
		qs->corners = 0;
		return;
	}
	if (corner)
		for (size_t v = 0; v < m->nv; v++)
			qs->corners += vpiece[v] < 0 && corner[v];
}

int fct_free_decimate(struct fct_mesh *F, uint32_t **vmap, size_t *nmap, const struct fct_mesh *m,
                      const unsigned char *is_free, const struct fct_qem_params *qp,
                      struct fct_free_cache *c, struct fct_qem_stats *qs, struct fct_err *err)
{
	memset(qs, 0, sizeof *qs);
	qs->vertices_in = m->nv;
	if (!c->valid && cache_init(c, m, err))
		return -1;
	size_t nv1 = m->nv ? m->nv : 1, nf1 = m->nf ? m->nf : 1;
	int32_t *up = fct_alloc_array(nv1, sizeof *up, err);
	int32_t *vpiece = fct_alloc_array(nv1, sizeof *vpiece, err);
	int32_t *fpiece = fct_alloc_array(nf1, sizeof *fpiece, err);
	uint32_t *vstart = fct_alloc_array(nf1 + 1, sizeof *vstart, err);
	uint32_t *fstart = fct_alloc_array(nf1 + 1, sizeof *fstart, err);
	uint32_t *vlist = fct_alloc_array(nv1, sizeof *vlist, err);
	uint32_t *flist = fct_alloc_array(nf1, sizeof *flist, err);
	uint32_t *local = fct_alloc_array(nv1, sizeof *local, err);
	struct fct_free_piece *pc = NULL;
	struct fct_free_tri *tri = NULL;
	unsigned char *same = NULL;
	int rc = -1;
	if (!up || !vpiece || !fpiece || !vstart || !fstart || !vlist || !flist || !local)
		goto out;
	size_t np = find_pieces(m, is_free, up, vpiece, fpiece, vstart, vlist, fstart, flist);
	/* Room for every triangle a fan of the free faces makes. */
	size_t room = 0;
	for (size_t f = 0; f < m->nf; f++)
		if (fpiece[f] >= 0 && fct_face_size(m, f) > 2)
			room += fct_face_size(m, f) - 2;
	room += c->ntri;
	if (!(pc = fct_alloc_array(np ? np : 1, sizeof *pc, err)) ||
	    !(same = fct_alloc_array(np ? np : 1, 1, err)) ||
	    !(tri = fct_alloc_array(room ? room : 1, sizeof *tri, err)))
		goto out;
	for (size_t k = 0; k < np; k++) {
		uint32_t *fl = flist + fstart[k], *vl = vlist + vstart[k];
		size_t nf = fstart[k + 1] - fstart[k], nv = vstart[k + 1] - vstart[k];
		same[k] = unchanged(c, m, fl, nf, vl, nv, qp->corner);
		pc[k].nfaces = nf;
		if (same[k])
			pc[k].st = c->pieces[c->piece[fl[0]]].st;
	}
	/* The triangles of the pieces kept, in their order, then the new ones. */
	size_t ntri = 0;
	for (size_t i = 0; i < c->ntri; i++) {
		int32_t k = fpiece[c->tri[i].face];
		if (k >= 0 && same[k]) {
			tri[ntri] = c->tri[i];
			tri[ntri].seq = (uint32_t)ntri;
			ntri++;
		}
	}
	for (size_t k = 0; k < np; k++)
		if (!same[k] && run_piece(c, m, flist + fstart[k], fstart[k + 1] - fstart[k],
		                          vlist + vstart[k], vstart[k + 1] - vstart[k], qp, local,
		                          tri, &ntri, &pc[k].st, err))
			goto out;
	qsort(tri, ntri, sizeof *tri, tri_order);
	/* F: the survivors in m's order, then the triangles. */
	size_t n = 0;
	for (size_t v = 0; v < m->nv; v++)
		n += !(vpiece[v] >= 0 && c->dead[v]);
	if (!(*vmap = fct_alloc_array(n ? n : 1, sizeof **vmap, err)) ||
	    fct_mesh_set_vertex_count(F, n, err))
		goto out;
	*nmap = n;
	n = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (!(vpiece[v] >= 0 && c->dead[v])) {
			(*vmap)[n] = (uint32_t)v;
			memcpy(F->xyz + 3 * n, (vpiece[v] >= 0 ? c->xyz : m->xyz) + 3 * v, sizeof(double[3]));
			n++;
		}
	for (size_t j = 0, col = 0; j < m->vertex.nprops; j++) {
		const struct fct_prop *p = &m->vertex.props[j];
		if (!carried(p))
			continue;
		struct fct_prop *q = fct_elem_add_scalar(&F->vertex, p->name, p->type, err);
		if (!q)
			goto out;
		for (size_t i = 0; i < *nmap; i++) {
			uint32_t v = (*vmap)[i];
			fct_prop_set(q, i, vpiece[v] >= 0 ? c->attr[c->nattr * v + col] : fct_prop_get(p, v));
		}
		col++;
	}
	if (fct_mesh_set_triangle_count(F, ntri, err))
		goto out;
	for (size_t t = 0; t < ntri; t++)
		memcpy(F->fvert + 3 * t, tri[t].v, sizeof tri[t].v);
	add_figures(qs, pc, np, vstart, vlist, vpiece, m, qp->corner);
	qs->faces_out = ntri;
	qs->vertices_out = *nmap;
	/* What the next round starts from. */
	free(c->piece), free(c->pieces), free(c->tri);
	c->piece = fpiece, c->pieces = pc, c->npieces = np, c->tri = tri, c->ntri = ntri;
	fpiece = NULL, pc = NULL, tri = NULL;
	rc = 0;
out:
	free(up), free(vpiece), free(fpiece), free(vstart), free(fstart), free(vlist), free(flist);
	free(local), free(pc), free(same), free(tri);
	return rc;
}

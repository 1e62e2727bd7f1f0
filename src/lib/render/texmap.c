/* texmap.c - texture coordinates per face corner or per vertex; see
 * texmap.h. */
#include <stdlib.h>
#include <string.h>

#include "io/texcoord.h"
#include "render/texmap.h"

int fct_texmap_corners(const struct fct_mesh *m, float **st, int32_t **texnum,
                       struct fct_err *err)
{
	*st = NULL;
	*texnum = NULL;
	const struct fct_prop *tc = fct_elem_find(&m->face, "texcoord"), *ps, *pt;
	if (tc && tc->count_type == FCT_NONE)
		tc = NULL;
	if (!tc && !fct_texcoord_vertex(m, &ps, &pt))
		return 0;
	size_t nc = m->fstart[m->nf];
	float *c = fct_alloc_array(nc, 2 * sizeof *c, err);
	int32_t *tn = fct_alloc_array(m->nf, sizeof *tn, err);
	if (!c || !tn) {
		free(c);
		free(tn);
		return -1;
	}
	if (tc) {
		/* fct_prop_get reads scalars; a list's items are a flat column
		 * of the same type, read through a scalar view of it. */
		struct fct_prop items = *tc;
		items.count_type = FCT_NONE;
		for (size_t f = 0; f < m->nf; f++) {
			size_t n = tc->off[f + 1] - tc->off[f], k = fct_face_size(m, f);
			if (n != 2 * k) {
				free(c);
				free(tn);
				return fct_fail(err, "face %zu: texcoord has %zu numbers for %zu corners", f, n, k);
			}
			for (size_t i = 0; i < n; i++)
				c[2 * (size_t)m->fstart[f] + i] = (float)fct_prop_get(&items, tc->off[f] + i);
		}
	} else {
		for (size_t i = 0; i < nc; i++) {
			c[2 * i] = (float)fct_prop_get(ps, m->fvert[i]);
			c[2 * i + 1] = (float)fct_prop_get(pt, m->fvert[i]);
		}
	}
	const struct fct_prop *pn = fct_elem_find(&m->face, "texnumber");
	for (size_t f = 0; f < m->nf; f++) {
		double v = pn && pn->count_type == FCT_NONE ? fct_prop_get(pn, f) : 0;
		tn[f] = v >= -1 && v < INT32_MAX ? (int32_t)v : -1;
	}
	*st = c;
	*texnum = tn;
	return 1;
}

/* Replace the face list texcoord by st. */
static int set_face_lists(struct fct_mesh *m, const float *st, struct fct_err *err)
{
	struct fct_prop *tc = fct_mesh_add_corner_list(m, "texcoord", FCT_FLOAT32, 2, err);
	if (!tc)
		return -1;
	memcpy(tc->data, st, 2 * (size_t)m->fstart[m->nf] * sizeof(float));
	fct_elem_remove(&m->vertex, "s");
	fct_elem_remove(&m->vertex, "t");
	return 0;
}

/* Vertex s t, a vertex copied for each further pair of coordinates its
 * corners take (copies chained per vertex through next). */
static int split_vertices(struct fct_mesh *m, const float *st, struct fct_err *err)
{
	size_t nv = m->nv, total = nv, scap = 0, ccap = 0, ncap = 0;
	size_t nc = m->fstart[m->nf];
	size_t *src = NULL;
	float *vst = NULL;      /* the coordinates of each vertex and copy */
	uint32_t *next = NULL;  /* next copy of the same vertex, 0: none */
	int rc = -1;
	unsigned char *set = calloc(nv ? nv : 1, 1);
	if (!set) {
		fct_fail(err, "out of memory");
		goto out;
	}
	if (fct_grow((void **)&src, &scap, nv + 1, sizeof *src, err) ||
	    fct_grow((void **)&vst, &ccap, 2 * (nv + 1), sizeof *vst, err) ||
	    fct_grow((void **)&next, &ncap, nv + 1, sizeof *next, err))
		goto out;
	for (size_t v = 0; v < nv; v++)
		src[v] = v, vst[2 * v] = vst[2 * v + 1] = 0, next[v] = 0;
	for (size_t c = 0; c < nc; c++) {
		uint32_t v = m->fvert[c];
		const float *want = st + 2 * c;
		if (!set[v]) {
			set[v] = 1;
			vst[2 * (size_t)v] = want[0], vst[2 * (size_t)v + 1] = want[1];
			continue;
		}
		uint32_t k = v, last = v;
		int found;
		while (!(found = !memcmp(vst + 2 * (size_t)k, want, 2 * sizeof *want)) && next[k])
			last = k = next[k];
		if (!found) {
			if (total >= UINT32_MAX - 1) {
				fct_fail(err, "too many vertices");
				goto out;
			}
			if (fct_grow((void **)&src, &scap, total + 1, sizeof *src, err) ||
			    fct_grow((void **)&vst, &ccap, 2 * (total + 1), sizeof *vst, err) ||
			    fct_grow((void **)&next, &ncap, total + 1, sizeof *next, err))
				goto out;
			k = (uint32_t)total++;
			src[k] = v, next[k] = 0, next[last] = k;
			vst[2 * (size_t)k] = want[0], vst[2 * (size_t)k + 1] = want[1];
		}
		m->fvert[c] = k;
	}
	if (fct_elem_gather(&m->vertex, src, total, err) ||
	    fct_grow((void **)&m->xyz, &m->xyz_cap, 3 * total, sizeof *m->xyz, err))
		goto out;
	for (size_t i = nv; i < total; i++)
		memcpy(m->xyz + 3 * i, m->xyz + 3 * src[i], 3 * sizeof *m->xyz);
	m->nv = total;
	fct_elem_remove(&m->vertex, "s");
	fct_elem_remove(&m->vertex, "t");
	struct fct_prop *ps = fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, err);
	if (!ps || !fct_elem_add_scalar(&m->vertex, "t", FCT_FLOAT32, err))
		goto out;
	float *s = fct_elem_find(&m->vertex, "s")->data, *t = fct_elem_find(&m->vertex, "t")->data;
	for (size_t v = 0; v < total; v++)
		s[v] = vst[2 * v], t[v] = vst[2 * v + 1];
	fct_elem_remove(&m->face, "texcoord");
	rc = 0;
out:
	free(set);
	free(src);
	free(vst);
	free(next);
	return rc;
}

int fct_texmap_set_corners(struct fct_mesh *m, const float *st, const int32_t *texnum,
                           int per_face, struct fct_err *err)
{
	if (per_face ? set_face_lists(m, st, err) : split_vertices(m, st, err))
		return -1;
	if (!texnum)
		return 0;
	struct fct_prop *tn = fct_elem_add_scalar(&m->face, "texnumber", FCT_INT32, err);
	if (!tn)
		return -1;
	memcpy(tn->data, texnum, m->nf * sizeof *texnum);
	return 0;
}

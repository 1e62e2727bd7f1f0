/* mesh.c - mesh storage, typed property columns and row selection. */
#include "core/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const struct {
	const char *name, *alias;
	size_t size;
} type_info[] = {
	[FCT_NONE] = {"none", "none", 0},
	[FCT_INT8] = {"char", "int8", 1},
	[FCT_UINT8] = {"uchar", "uint8", 1},
	[FCT_INT16] = {"short", "int16", 2},
	[FCT_UINT16] = {"ushort", "uint16", 2},
	[FCT_INT32] = {"int", "int32", 4},
	[FCT_UINT32] = {"uint", "uint32", 4},
	[FCT_FLOAT32] = {"float", "float32", 4},
	[FCT_FLOAT64] = {"double", "float64", 8},
};

size_t fct_type_size(enum fct_type t)
{
	return t <= FCT_FLOAT64 ? type_info[t].size : 0;
}

const char *fct_type_name(enum fct_type t)
{
	return t <= FCT_FLOAT64 ? type_info[t].name : "none";
}

enum fct_type fct_type_parse(const char *name)
{
	for (int t = FCT_INT8; t <= FCT_FLOAT64; t++)
		if (!strcmp(name, type_info[t].name) || !strcmp(name, type_info[t].alias))
			return (enum fct_type)t;
	return FCT_NONE;
}

void fct_mesh_init(struct fct_mesh *m)
{
	memset(m, 0, sizeof *m);
	m->xyz_type = FCT_FLOAT32;
	m->fcount_type = FCT_UINT8;
	m->findex_type = FCT_INT32;
}

/* Scalar columns' data allocated together (fct_elem_add_scalars_big):
 * freed with the last column that uses it. */
struct fct_block {
	void *mem;
	size_t users;
};

/* Let go of p's data: freed if it is p's own or p is its block's last
 * user.  p->data and p->block are stale afterwards. */
static void prop_release(struct fct_prop *p)
{
	if (!p->block) {
		free(p->data);
	} else if (--p->block->users == 0) {
		free(p->block->mem);
		free(p->block);
	}
}

/* Give a column in a block its own copy of its data, before it grows. */
static int prop_own(struct fct_prop *p, struct fct_err *err)
{
	if (!p->block)
		return 0;
	size_t sz = fct_type_size(p->type);
	void *d = fct_alloc_array(p->cap, sz, err);
	if (!d)
		return -1;
	if (p->cap)   /* a column of no rows has no data */
		memcpy(d, p->data, p->cap * sz);
	prop_release(p);
	p->data = d, p->block = NULL;
	return 0;
}

static void prop_free(struct fct_prop *p)
{
	free(p->name);
	prop_release(p);
	free(p->off);
}

static void elem_free(struct fct_elem *e)
{
	for (size_t i = 0; i < e->nprops; i++)
		prop_free(&e->props[i]);
	free(e->props);
	free(e->name);
	memset(e, 0, sizeof *e);
}

void fct_mesh_free(struct fct_mesh *m)
{
	if (!m)
		return;
	free(m->xyz);
	free(m->fstart);
	free(m->fvert);
	elem_free(&m->vertex);
	elem_free(&m->face);
	for (size_t i = 0; i < m->nelems; i++)
		elem_free(&m->elems[i]);
	free(m->elems);
	for (size_t i = 0; i < m->ncomments; i++)
		free(m->comments[i].text);
	free(m->comments);
	fct_mesh_init(m);
}

struct fct_prop *fct_elem_find(const struct fct_elem *e, const char *name)
{
	for (size_t i = 0; i < e->nprops; i++)
		if (!strcmp(e->props[i].name, name))
			return &e->props[i];
	return NULL;
}

struct fct_elem *fct_mesh_find_elem(const struct fct_mesh *m, const char *name)
{
	for (size_t i = 0; i < m->nelems; i++)
		if (!strcmp(m->elems[i].name, name))
			return &m->elems[i];
	return NULL;
}

/* Make column p hold count rows: scalars zero-filled, lists empty. */
static int prop_resize(struct fct_prop *p, size_t old, size_t count, struct fct_err *err)
{
	size_t sz = fct_type_size(p->type);
	if (p->count_type == FCT_NONE) {
		if ((count > p->cap && prop_own(p, err)) || fct_grow(&p->data, &p->cap, count, sz, err))
			return -1;
		if (count > old)
			memset((char *)p->data + old * sz, 0, (count - old) * sz);
		return 0;
	}
	if (fct_grow((void **)&p->off, &p->off_cap, count + 1, sizeof *p->off, err))
		return -1;
	if (old == 0)
		p->off[0] = 0;
	for (size_t i = old; i < count; i++)
		p->off[i + 1] = p->off[old];
	return 0;
}

int fct_elem_resize(struct fct_elem *e, size_t count, struct fct_err *err)
{
	for (size_t i = 0; i < e->nprops; i++)
		if (prop_resize(&e->props[i], e->count, count, err))
			return -1;
	e->count = count;
	return 0;
}

struct fct_prop *fct_elem_add_scalar(struct fct_elem *e, const char *name,
                                     enum fct_type t, struct fct_err *err)
{
	struct fct_prop *p = fct_elem_find(e, name);
	if (p && p->type == t && p->count_type == FCT_NONE)
		return p;
	if (p)
		fct_elem_remove(e, name);
	struct fct_prop *np = realloc(e->props, (e->nprops + 1) * sizeof *np);
	if (!np) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	e->props = np;
	p = &np[e->nprops];
	memset(p, 0, sizeof *p);
	p->type = t;
	if (!(p->name = fct_strdup(name, err)))
		return NULL;
	if (prop_resize(p, 0, e->count, err)) {
		prop_free(p);
		return NULL;
	}
	e->nprops++;
	return p;
}

int fct_elem_add_scalars_big(struct fct_elem *e, const char *const *names, size_t n, enum fct_type t,
                             struct fct_err *err)
{
	size_t sz = fct_type_size(t), values;
	if (!n)
		return 0;
	if (fct_mul_size(e->count, n, &values))
		return fct_fail(err, "too many values");
	struct fct_block *b = malloc(sizeof *b);
	void *mem = values ? fct_alloc_big(values, sz, err) : NULL;
	struct fct_prop *np = realloc(e->props, (e->nprops + n) * sizeof *np);
	if (np)
		e->props = np;
	if (!b || (values && !mem) || !np) {
		free(b);
		free(mem);
		return fct_fail(err, "out of memory");
	}
	if (values)
		memset(mem, 0, values * sz);
	b->mem = mem, b->users = 0;
	for (size_t i = 0; i < n; i++)   /* props has room for n more */
		fct_elem_remove(e, names[i]);
	for (size_t i = 0; i < n; i++) {
		struct fct_prop *p = &e->props[e->nprops];
		memset(p, 0, sizeof *p);
		p->name = fct_strdup(names[i], err);
		if (!p->name) {   /* the block goes with the last column removed */
			for (size_t k = 0; k < i; k++)
				fct_elem_remove(e, names[k]);
			if (!i) {
				free(mem);
				free(b);
			}
			return -1;
		}
		p->type = t;
		p->data = (char *)mem + i * e->count * sz, p->cap = e->count;
		p->block = b, b->users++;
		e->nprops++;
	}
	return 0;
}

struct fct_prop *fct_mesh_add_corner_list(struct fct_mesh *m, const char *name, enum fct_type t,
                                          unsigned per_corner, struct fct_err *err)
{
	size_t items, corners = m->nf ? m->fstart[m->nf] : 0;
	if (fct_mul_size(corners, per_corner, &items)) {
		fct_fail(err, "too many face corners");
		return NULL;
	}
	fct_elem_remove(&m->face, name);
	struct fct_prop *p = fct_elem_add_scalar(&m->face, name, t, err);
	if (!p)
		return NULL;
	/* The scalar column becomes a list: data of items values, rows by the
	 * faces' corners. */
	size_t sz = fct_type_size(t);
	void *data = fct_alloc_array(items, sz, err);
	size_t *off = fct_alloc_array(m->nf + 1, sizeof *off, err);
	if (!data || !off) {
		free(data);
		free(off);
		fct_elem_remove(&m->face, name);
		return NULL;
	}
	memset(data, 0, (items ? items : 1) * sz);
	for (size_t f = 0; f <= m->nf; f++)
		off[f] = (size_t)per_corner * (m->nf ? m->fstart[f] : 0);
	free(p->data);
	p->data = data, p->cap = items ? items : 1;
	p->off = off, p->off_cap = m->nf + 1;
	p->count_type = FCT_UINT8;
	return p;
}

struct fct_elem *fct_mesh_add_elem(struct fct_mesh *m, const char *name, size_t count,
                                   struct fct_err *err)
{
	struct fct_elem *ne = realloc(m->elems, (m->nelems + 1) * sizeof *ne);
	if (!ne) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	m->elems = ne;
	struct fct_elem *e = &ne[m->nelems];
	memset(e, 0, sizeof *e);
	if (!(e->name = fct_strdup(name, err)))
		return NULL;
	e->count = count;
	m->nelems++;
	return e;
}

void fct_elem_remove(struct fct_elem *e, const char *name)
{
	struct fct_prop *p = fct_elem_find(e, name);
	if (!p)
		return;
	size_t i = (size_t)(p - e->props);
	prop_free(p);
	memmove(p, p + 1, (e->nprops - i - 1) * sizeof *p);
	e->nprops--;
}

void fct_mesh_remove_elem(struct fct_mesh *m, const char *name)
{
	struct fct_elem *e = fct_mesh_find_elem(m, name);
	if (!e)
		return;
	size_t i = (size_t)(e - m->elems);
	elem_free(e);
	memmove(e, e + 1, (m->nelems - i - 1) * sizeof *e);
	m->nelems--;
}

double fct_prop_get(const struct fct_prop *p, size_t i)
{
	switch (p->type) {
	case FCT_INT8: return ((const int8_t *)p->data)[i];
	case FCT_UINT8: return ((const uint8_t *)p->data)[i];
	case FCT_INT16: return ((const int16_t *)p->data)[i];
	case FCT_UINT16: return ((const uint16_t *)p->data)[i];
	case FCT_INT32: return ((const int32_t *)p->data)[i];
	case FCT_UINT32: return ((const uint32_t *)p->data)[i];
	case FCT_FLOAT32: return ((const float *)p->data)[i];
	case FCT_FLOAT64: return ((const double *)p->data)[i];
	default: abort();
	}
}

/* Round v to an integer in [lo, hi]; NaN becomes 0. */
static double clamp_round(double v, double lo, double hi)
{
	if (!(v == v))
		return 0;
	v = nearbyint(v);
	return v < lo ? lo : v > hi ? hi : v;
}

void fct_prop_set(struct fct_prop *p, size_t i, double v)
{
	switch (p->type) {
	case FCT_INT8: ((int8_t *)p->data)[i] = (int8_t)clamp_round(v, INT8_MIN, INT8_MAX); break;
	case FCT_UINT8: ((uint8_t *)p->data)[i] = (uint8_t)clamp_round(v, 0, UINT8_MAX); break;
	case FCT_INT16: ((int16_t *)p->data)[i] = (int16_t)clamp_round(v, INT16_MIN, INT16_MAX); break;
	case FCT_UINT16: ((uint16_t *)p->data)[i] = (uint16_t)clamp_round(v, 0, UINT16_MAX); break;
	case FCT_INT32: ((int32_t *)p->data)[i] = (int32_t)clamp_round(v, INT32_MIN, INT32_MAX); break;
	case FCT_UINT32: ((uint32_t *)p->data)[i] = (uint32_t)clamp_round(v, 0, UINT32_MAX); break;
	case FCT_FLOAT32: ((float *)p->data)[i] = (float)v; break;
	case FCT_FLOAT64: ((double *)p->data)[i] = v; break;
	default: abort();
	}
}

long fct_mesh_add_vertex(struct fct_mesh *m, double x, double y, double z, struct fct_err *err)
{
	if (fct_grow((void **)&m->xyz, &m->xyz_cap, 3 * (m->nv + 1), sizeof *m->xyz, err))
		return -1;
	if (fct_elem_resize(&m->vertex, m->nv + 1, err))
		return -1;
	double *p = m->xyz + 3 * m->nv;
	p[0] = x, p[1] = y, p[2] = z;
	return (long)m->nv++;
}

long fct_mesh_add_face(struct fct_mesh *m, const uint32_t *v, size_t n, struct fct_err *err)
{
	size_t base = m->nf ? m->fstart[m->nf] : 0;
	if (base + n > UINT32_MAX)
		return fct_fail(err, "too many face vertices");
	if (fct_grow((void **)&m->fstart, &m->fstart_cap, m->nf + 2, sizeof *m->fstart, err) ||
	    fct_grow((void **)&m->fvert, &m->fvert_cap, base + n, sizeof *m->fvert, err) ||
	    fct_elem_resize(&m->face, m->nf + 1, err))
		return -1;
	m->fstart[0] = 0;
	memcpy(m->fvert + base, v, n * sizeof *v);
	m->fstart[m->nf + 1] = (uint32_t)(base + n);
	m->has_faces = 1;
	return (long)m->nf++;
}

/* Bulk construction knows its sizes: fct_reserve, exactly.
 *
 * Plain realloc, not fct_alloc_big, although marching cubes' output (73 MB
 * for the room at 1 cm) faults in 17.8k 4 KB pages, about 23 ms, when it
 * cannot reuse freed memory: measured on the 2-vCPU VM (THP "madvise"),
 * huge pages for these arrays made gen_mcubes fused 0.094 -> 0.225 s CPU
 * (medians of 9) and tsdfuse --threads 1 mcubes_s 0.078 -> 0.072 s in some
 * runs and 0.125 s in others.  The VM hands free 2 MB blocks back to its
 * host (virtio-balloon free page reporting), so a fresh huge page is
 * faulted in by the host 4 KB at a time: 73 MB took 165 ms so, 3.5 ms in
 * huge pages still backed, 24 ms in 4 KB pages (recycled by the guest,
 * always backed).  Calloc for the normals (their zero fill not written
 * twice) changed nothing measurable. */
int fct_mesh_set_vertex_count(struct fct_mesh *m, size_t nv, struct fct_err *err)
{
	size_t n;
	if (fct_mul_size(nv, 3, &n))
		return fct_fail(err, "too many vertices");
	if (fct_reserve((void **)&m->xyz, &m->xyz_cap, n, sizeof *m->xyz, err) ||
	    fct_elem_resize(&m->vertex, nv, err))
		return -1;
	m->nv = nv;
	return 0;
}

int fct_mesh_set_triangle_count(struct fct_mesh *m, size_t nf, struct fct_err *err)
{
	if (nf > UINT32_MAX / 3)
		return fct_fail(err, "too many faces");
	if (fct_reserve((void **)&m->fstart, &m->fstart_cap, nf + 1, sizeof *m->fstart, err) ||
	    fct_reserve((void **)&m->fvert, &m->fvert_cap, 3 * nf, sizeof *m->fvert, err) ||
	    fct_elem_resize(&m->face, nf, err))
		return -1;
	for (size_t f = 0; f <= nf; f++)
		m->fstart[f] = (uint32_t)(3 * f);
	m->nf = nf;
	m->has_faces = 1;
	return 0;
}

/* Huge pages where the plain realloc above is kept for marching cubes: a
 * 640x480 depth map's grid mesh (18.4 MB of xyz, fstart, fvert and vertex
 * properties, each written whole once) faulted in about 4000 4 KB pages,
 * and in huge pages its faces, positions and s t sigma took 3.6 ms of
 * dm2mesh's run instead of 8.2 (7-Scenes 000000, medians of 11 on the
 * 2-vCPU VM; see fct_alloc_big).
 *
 * An array not allocated yet (*cap 0) from fct_alloc_big, n elements. */
static int take_big(void **ptr, size_t *cap, size_t n, size_t elem, struct fct_err *err)
{
	if (*cap)
		return 0;
	void *p = fct_alloc_big(n, elem, err);
	if (!p)
		return -1;
	free(*ptr);
	*ptr = p, *cap = n;
	return 0;
}

int fct_mesh_set_counts_big(struct fct_mesh *m, size_t nv, size_t nf, struct fct_err *err)
{
	size_t n;
	/* sizes the calls below refuse are left to them */
	if (!fct_mul_size(nv, 3, &n) && nf <= UINT32_MAX / 3 &&
	    (take_big((void **)&m->xyz, &m->xyz_cap, n, sizeof *m->xyz, err) ||
	     take_big((void **)&m->fstart, &m->fstart_cap, nf + 1, sizeof *m->fstart, err) ||
	     take_big((void **)&m->fvert, &m->fvert_cap, 3 * nf, sizeof *m->fvert, err)))
		return -1;
	return fct_mesh_set_vertex_count(m, nv, err) || fct_mesh_set_triangle_count(m, nf, err) ? -1 : 0;
}

/* Gather rows of one column into fresh storage. */
static int prop_gather(struct fct_prop *p, const size_t *src, size_t n, struct fct_err *err)
{
	size_t sz = fct_type_size(p->type);
	if (p->count_type == FCT_NONE) {
		char *d = malloc(n ? n * sz : 1);
		if (!d)
			return fct_fail(err, "out of memory");
		for (size_t i = 0; i < n; i++)
			memcpy(d + i * sz, (char *)p->data + src[i] * sz, sz);
		prop_release(p);
		p->data = d, p->block = NULL;
		p->cap = n;
		return 0;
	}
	size_t items = 0;
	for (size_t i = 0; i < n; i++)
		items += p->off[src[i] + 1] - p->off[src[i]];
	char *d = malloc(items ? items * sz : 1);
	size_t *off = malloc((n + 1) * sizeof *off);
	if (!d || !off) {
		free(d);
		free(off);
		return fct_fail(err, "out of memory");
	}
	off[0] = 0;
	for (size_t i = 0; i < n; i++) {
		size_t k = p->off[src[i] + 1] - p->off[src[i]];
		memcpy(d + off[i] * sz, (char *)p->data + p->off[src[i]] * sz, k * sz);
		off[i + 1] = off[i] + k;
	}
	free(p->data);
	free(p->off);
	p->data = d, p->cap = items;
	p->off = off, p->off_cap = n + 1;
	return 0;
}

int fct_elem_gather(struct fct_elem *e, const size_t *src, size_t n, struct fct_err *err)
{
	for (size_t i = 0; i < e->nprops; i++)
		if (prop_gather(&e->props[i], src, n, err))
			return -1;
	e->count = n;
	return 0;
}

int fct_mesh_gather_faces(struct fct_mesh *m, const size_t *src, size_t n, struct fct_err *err)
{
	size_t total = 0;
	for (size_t i = 0; i < n; i++)
		total += fct_face_size(m, src[i]);
	uint32_t *fs = malloc((n + 1) * sizeof *fs);
	uint32_t *fv = malloc((total ? total : 1) * sizeof *fv);
	if (!fs || !fv) {
		free(fs);
		free(fv);
		return fct_fail(err, "out of memory");
	}
	fs[0] = 0;
	for (size_t i = 0; i < n; i++) {
		uint32_t k = fct_face_size(m, src[i]);
		memcpy(fv + fs[i], m->fvert + m->fstart[src[i]], k * sizeof *fv);
		fs[i + 1] = fs[i] + k;
	}
	if (fct_elem_gather(&m->face, src, n, err)) {
		free(fs);
		free(fv);
		return -1;
	}
	free(m->fstart);
	free(m->fvert);
	m->fstart = fs, m->fstart_cap = n + 1;
	m->fvert = fv, m->fvert_cap = total;
	m->nf = n;
	return 0;
}

int fct_mesh_gather_vertices(struct fct_mesh *m, const size_t *src, size_t n, struct fct_err *err)
{
	uint32_t *map = malloc((m->nv ? m->nv : 1) * sizeof *map);
	size_t *keep = malloc((m->nf ? m->nf : 1) * sizeof *keep);
	double *xyz = malloc((n ? 3 * n : 1) * sizeof *xyz);
	if (!map || !keep || !xyz) {
		free(map), free(keep), free(xyz);
		return fct_fail(err, "out of memory");
	}
	for (size_t i = 0; i < m->nv; i++)
		map[i] = UINT32_MAX;
	for (size_t i = 0; i < n; i++) {
		if (map[src[i]] == UINT32_MAX)
			map[src[i]] = (uint32_t)i;
		memcpy(xyz + 3 * i, m->xyz + 3 * src[i], 3 * sizeof *xyz);
	}
	size_t nkeep = 0;
	for (size_t f = 0; f < m->nf; f++) {
		int ok = 1;
		for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++)
			ok &= map[m->fvert[k]] != UINT32_MAX;
		if (ok)
			keep[nkeep++] = f;
	}
	int rc = fct_elem_gather(&m->vertex, src, n, err);
	if (!rc)
		rc = fct_mesh_gather_faces(m, keep, nkeep, err);
	if (!rc) {
		for (size_t k = 0; k < m->fstart[m->nf]; k++)
			m->fvert[k] = map[m->fvert[k]];
		free(m->xyz);
		m->xyz = xyz, m->xyz_cap = 3 * n;
		m->nv = n;
		xyz = NULL;
	}
	free(map), free(keep), free(xyz);
	return rc;
}

static int elem_copy(struct fct_elem *d, const struct fct_elem *s, struct fct_err *err)
{
	memset(d, 0, sizeof *d);
	if (s->name && !(d->name = fct_strdup(s->name, err)))
		return -1;
	d->count = s->count;
	if (!s->nprops)
		return 0;
	if (!(d->props = calloc(s->nprops, sizeof *d->props)))
		return fct_fail(err, "out of memory");
	for (size_t i = 0; i < s->nprops; i++, d->nprops++) {
		const struct fct_prop *sp = &s->props[i];
		struct fct_prop *dp = &d->props[i];
		dp->type = sp->type, dp->count_type = sp->count_type;
		if (!(dp->name = fct_strdup(sp->name, err)))
			return -1;
		size_t values = sp->count_type ? (s->count ? sp->off[s->count] : 0) : s->count;
		size_t bytes = values * fct_type_size(sp->type);
		if (!(dp->data = malloc(bytes ? bytes : 1)))
			return fct_fail(err, "out of memory");
		if (bytes)
			memcpy(dp->data, sp->data, bytes);
		dp->cap = values;
		if (sp->count_type) {
			if (!(dp->off = malloc((s->count + 1) * sizeof *dp->off)))
				return fct_fail(err, "out of memory");
			if (s->count)
				memcpy(dp->off, sp->off, (s->count + 1) * sizeof *dp->off);
			else
				dp->off[0] = 0;
			dp->off_cap = s->count + 1;
		}
	}
	return 0;
}

/* Duplicate n items of size sz, or NULL for none. */
static void *dup_array(const void *src, size_t n, size_t sz, int *fail)
{
	if (!n || !src)
		return NULL;
	void *d = malloc(n * sz);
	if (!d)
		*fail = 1;
	else
		memcpy(d, src, n * sz);
	return d;
}

/* The first property in which elements a and b differ, or NULL. */
static const char *elem_differs(const struct fct_elem *a, const struct fct_elem *b)
{
	size_t n = a->nprops < b->nprops ? a->nprops : b->nprops;
	for (size_t i = 0; i < n; i++) {
		const struct fct_prop *p = &a->props[i], *q = &b->props[i];
		if (strcmp(p->name, q->name) || p->type != q->type || p->count_type != q->count_type)
			return p->name;
	}
	if (a->nprops != b->nprops)
		return a->nprops > n ? a->props[n].name : b->props[n].name;
	return NULL;
}

/* Append the rows of column q (count rows) after the old rows of p. */
static int prop_append(struct fct_prop *p, size_t old, const struct fct_prop *q, size_t count,
                       struct fct_err *err)
{
	size_t sz = fct_type_size(p->type);
	if (p->count_type == FCT_NONE) {
		if ((old + count > p->cap && prop_own(p, err)) || fct_grow(&p->data, &p->cap, old + count, sz, err))
			return -1;
		if (count)
			memcpy((char *)p->data + old * sz, q->data, count * sz);
		return 0;
	}
	size_t pitems = old ? p->off[old] : 0, qitems = count ? q->off[count] : 0;
	if (fct_grow((void **)&p->off, &p->off_cap, old + count + 1, sizeof *p->off, err) ||
	    fct_grow(&p->data, &p->cap, pitems + qitems, sz, err))
		return -1;
	p->off[0] = 0;
	for (size_t i = 0; i < count; i++)
		p->off[old + i + 1] = pitems + q->off[i + 1];
	if (qitems)
		memcpy((char *)p->data + pitems * sz, q->data, qitems * sz);
	return 0;
}

int fct_mesh_append(struct fct_mesh *dst, const struct fct_mesh *src, struct fct_err *err)
{
	const char *d;
	if ((d = elem_differs(&dst->vertex, &src->vertex)))
		return fct_fail(err, "vertex property %s: not in both meshes alike", d);
	if ((d = elem_differs(&dst->face, &src->face)))
		return fct_fail(err, "face property %s: not in both meshes alike", d);
	size_t nv = dst->nv + src->nv, nf = dst->nf + src->nf;
	size_t dfv = dst->nf ? dst->fstart[dst->nf] : 0, sfv = src->nf ? src->fstart[src->nf] : 0;
	if (nv > UINT32_MAX || dfv + sfv > UINT32_MAX || nv < dst->nv)
		return fct_fail(err, "more than 2^32 - 1 vertices or face corners");
	if (fct_grow((void **)&dst->xyz, &dst->xyz_cap, 3 * nv, sizeof *dst->xyz, err) ||
	    fct_grow((void **)&dst->fstart, &dst->fstart_cap, nf + 1, sizeof *dst->fstart, err) ||
	    fct_grow((void **)&dst->fvert, &dst->fvert_cap, dfv + sfv, sizeof *dst->fvert, err))
		return -1;
	for (size_t i = 0; i < dst->vertex.nprops; i++)
		if (prop_append(&dst->vertex.props[i], dst->nv, &src->vertex.props[i], src->nv, err))
			return -1;
	for (size_t i = 0; i < dst->face.nprops; i++)
		if (prop_append(&dst->face.props[i], dst->nf, &src->face.props[i], src->nf, err))
			return -1;
	if (src->nv)
		memcpy(dst->xyz + 3 * dst->nv, src->xyz, 3 * src->nv * sizeof *dst->xyz);
	dst->fstart[0] = 0;
	for (size_t f = 0; f < src->nf; f++)
		dst->fstart[dst->nf + f + 1] = (uint32_t)(dfv + src->fstart[f + 1]);
	for (size_t i = 0; i < sfv; i++)
		dst->fvert[dfv + i] = (uint32_t)(src->fvert[i] + dst->nv);
	if (src->xyz_type == FCT_FLOAT64)
		dst->xyz_type = FCT_FLOAT64;
	dst->has_faces |= src->has_faces;
	dst->nv = dst->vertex.count = nv;
	dst->nf = dst->face.count = nf;
	return 0;
}

int fct_mesh_copy(struct fct_mesh *dst, const struct fct_mesh *src, struct fct_err *err)
{
	int fail = 0;
	fct_mesh_init(dst);
	dst->xyz_type = src->xyz_type;
	dst->fcount_type = src->fcount_type;
	dst->findex_type = src->findex_type;
	dst->has_faces = src->has_faces;
	dst->nv = src->nv;
	dst->xyz = dup_array(src->xyz, 3 * src->nv, sizeof *src->xyz, &fail);
	dst->xyz_cap = 3 * src->nv;
	dst->nf = src->nf;
	if (src->nf) {
		dst->fstart = dup_array(src->fstart, src->nf + 1, sizeof *src->fstart, &fail);
		dst->fstart_cap = src->nf + 1;
		dst->fvert = dup_array(src->fvert, src->fstart[src->nf], sizeof *src->fvert, &fail);
		dst->fvert_cap = src->fstart[src->nf];
	}
	if (fail)
		goto oom;
	if (elem_copy(&dst->vertex, &src->vertex, err) || elem_copy(&dst->face, &src->face, err))
		goto fail;
	if (src->nelems) {
		if (!(dst->elems = calloc(src->nelems, sizeof *dst->elems)))
			goto oom;
		for (size_t i = 0; i < src->nelems; i++, dst->nelems++)
			if (elem_copy(&dst->elems[i], &src->elems[i], err))
				goto fail;
	}
	for (size_t i = 0; i < src->ncomments; i++)
		if (fct_mesh_add_comment(dst, src->comments[i].text, src->comments[i].obj_info, err))
			goto fail;
	return 0;
oom:
	fct_fail(err, "out of memory");
fail:
	fct_mesh_free(dst);
	return -1;
}

int fct_mesh_add_comment(struct fct_mesh *m, const char *text, int obj_info, struct fct_err *err)
{
	struct fct_comment *c = realloc(m->comments, (m->ncomments + 1) * sizeof *c);
	if (!c)
		return fct_fail(err, "out of memory");
	m->comments = c;
	if (!(c[m->ncomments].text = fct_strdup(text, err)))
		return -1;
	c[m->ncomments].obj_info = obj_info;
	m->ncomments++;
	return 0;
}

int fct_mesh_keep_precision(struct fct_mesh *m, double resolution)
{
	double most = 0;
	for (size_t i = 0; i < 3 * m->nv; i++)
		most = fmax(most, fabs(m->xyz[i]));
	/* float's rounding error at |x| is at most |x| 2^-24 */
	if (!(resolution > 0) || !(most * 0x1p-24 > resolution))
		return 0;
	m->xyz_type = FCT_FLOAT64;
	return 1;
}

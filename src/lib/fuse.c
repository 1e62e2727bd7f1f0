/* fuse.c - multi-view fusion by true signed distance, space carving and
 * level-set curvature flow: Sun, Paik, Koschan and Abidi, sec. 3 (see
 * fuse.h).
 *
 * Nearest points.  Hilton finds each band voxel's nearest point on the
 * view's mesh with a k-D tree.  Range-image meshes have triangles far
 * smaller than voxels, so here the search is a closest-point transform by
 * propagation: every triangle is splatted exactly into the voxels of its
 * bounding box grown by half a voxel, which gives a connected shell of
 * voxels around the surface with their nearest triangle; then the
 * band is grown layer by layer (26-neighbours), each new voxel taking the
 * best of its finished neighbours' triangles and walking downhill on the
 * mesh (across the edge or around the vertex where its closest point lies)
 * to the local minimum.  Cost: a few closest-point tests per band voxel,
 * independent of how finely the view is triangulated beyond the splat. */
#include "fuse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "adj.h"
#include "geom.h"

/* Per-view scratch: a hash of 8^3 blocks holding each voxel's best squared
 * distance, triangle and propagation layer. ------------------------------ */

#define NOLAYER 255

struct sblock {
	int32_t bx, by, bz;
	float d2[FCT_VOXBLOCK_N];
	int32_t tri[FCT_VOXBLOCK_N];
	uint8_t layer[FCT_VOXBLOCK_N];
};

struct scratch {
	uint64_t *keys;          /* UINT64_MAX: empty slot */
	uint32_t *slot;          /* block index of a key */
	size_t cap, n;           /* hash capacity (power of two), blocks */
	struct sblock **blk;
	size_t blkcap;
	struct sblock *last;     /* the block found last (most lookups repeat it) */
};

static uint64_t block_key(int32_t bx, int32_t by, int32_t bz)
{
	return ((uint64_t)(uint32_t)bx & 0x1fffff) << 42 | ((uint64_t)(uint32_t)by & 0x1fffff) << 21 |
	       ((uint64_t)(uint32_t)bz & 0x1fffff);
}

static size_t key_hash(uint64_t k, size_t cap)
{
	k *= 0x9e3779b97f4a7c15ull;
	return (size_t)(k >> 17) & (cap - 1);
}

static void scratch_free(struct scratch *s)
{
	for (size_t i = 0; i < s->n; i++)
		free(s->blk[i]);
	free(s->blk);
	free(s->keys);
	free(s->slot);
	memset(s, 0, sizeof *s);
}

static int scratch_rehash(struct scratch *s, size_t cap, struct fct_err *err)
{
	uint64_t *keys = fct_alloc_array(cap, sizeof *keys, err);
	uint32_t *slot = fct_alloc_array(cap, sizeof *slot, err);
	if (!keys || !slot) {
		free(keys);
		free(slot);
		return -1;
	}
	memset(keys, 0xff, cap * sizeof *keys);
	for (size_t i = 0; i < s->n; i++) {
		uint64_t k = block_key(s->blk[i]->bx, s->blk[i]->by, s->blk[i]->bz);
		size_t h = key_hash(k, cap);
		while (keys[h] != UINT64_MAX)
			h = (h + 1) & (cap - 1);
		keys[h] = k;
		slot[h] = (uint32_t)i;
	}
	free(s->keys);
	free(s->slot);
	s->keys = keys;
	s->slot = slot;
	s->cap = cap;
	return 0;
}

/* The scratch block (bx, by, bz), created (d2 = inf, layer = NOLAYER) when
 * create is set; NULL when absent or out of memory (err set then). */
static struct sblock *scratch_block(struct scratch *s, int32_t bx, int32_t by, int32_t bz,
                                    int create, struct fct_err *err)
{
	if (s->last && s->last->bx == bx && s->last->by == by && s->last->bz == bz)
		return s->last;
	uint64_t k = block_key(bx, by, bz);
	if (s->cap) {
		size_t h = key_hash(k, s->cap);
		while (s->keys[h] != UINT64_MAX) {
			if (s->keys[h] == k)
				return s->last = s->blk[s->slot[h]];
			h = (h + 1) & (s->cap - 1);
		}
	}
	if (!create)
		return NULL;
	if (2 * (s->n + 1) > s->cap && scratch_rehash(s, s->cap ? 2 * s->cap : 1024, err))
		return NULL;
	if (fct_grow((void **)&s->blk, &s->blkcap, s->n + 1, sizeof *s->blk, err))
		return NULL;
	struct sblock *b = malloc(sizeof *b);
	if (!b) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	b->bx = bx, b->by = by, b->bz = bz;
	for (int i = 0; i < FCT_VOXBLOCK_N; i++)
		b->d2[i] = INFINITY;
	memset(b->tri, 0xff, sizeof b->tri);
	memset(b->layer, NOLAYER, sizeof b->layer);
	size_t h = key_hash(k, s->cap);
	while (s->keys[h] != UINT64_MAX)
		h = (h + 1) & (s->cap - 1);
	s->keys[h] = k;
	s->slot[h] = (uint32_t)s->n;
	s->blk[s->n++] = b;
	return s->last = b;
}

static inline int local_index(int32_t i, int32_t j, int32_t k)
{
	return fct_vox_local_of(i) + FCT_VOXBLOCK * (fct_vox_local_of(j) + FCT_VOXBLOCK * fct_vox_local_of(k));
}

/* The view's triangles with what the search needs. ----------------------- */

struct geo {
	size_t nt;
	const double *xyz;
	uint32_t *tv;            /* 3 per triangle */
	double *tn;              /* unit normal, 3 per triangle */
	int32_t *nb;             /* triangle across edge k (corner k to k+1); -1 border, -2 other */
	double *vn;              /* angle-weighted vertex pseudo-normals */
	uint8_t *vborder;
	struct fct_adj adj;
	struct fct_mesh tris;    /* the triangulated mesh when the input has polygons */
	int own;
};

static void geo_free(struct geo *G)
{
	free(G->tv);
	free(G->tn);
	free(G->nb);
	free(G->vn);
	free(G->vborder);
	fct_adj_free(&G->adj);
	if (G->own)
		fct_mesh_free(&G->tris);
	memset(G, 0, sizeof *G);
}

static int geo_build(struct geo *G, const struct fct_mesh *m, struct fct_err *err)
{
	memset(G, 0, sizeof *G);
	const struct fct_mesh *t = m;
	int alltri = 1;
	for (size_t f = 0; f < m->nf && alltri; f++)
		alltri = fct_face_size(m, f) == 3;
	if (!alltri) {
		/* Fan-triangulate polygons into a copy of the positions. */
		G->own = 1;
		fct_mesh_init(&G->tris);
		if (fct_mesh_set_vertex_count(&G->tris, m->nv, err))
			goto fail;
		memcpy(G->tris.xyz, m->xyz, 3 * m->nv * sizeof *m->xyz);
		for (size_t f = 0; f < m->nf; f++) {
			const uint32_t *v = &m->fvert[m->fstart[f]];
			for (uint32_t k = 2; k < fct_face_size(m, f); k++) {
				uint32_t tri[3] = { v[0], v[k - 1], v[k] };
				if (fct_mesh_add_face(&G->tris, tri, 3, err) < 0)
					goto fail;
			}
		}
		t = &G->tris;
	}
	size_t nt = t->nf, nv = t->nv;
	G->nt = nt;
	G->xyz = t->xyz;
	G->tv = fct_alloc_array(nt, 3 * sizeof *G->tv, err);
	G->tn = fct_alloc_array(nt, 3 * sizeof *G->tn, err);
	G->nb = fct_alloc_array(nt, 3 * sizeof *G->nb, err);
	G->vn = calloc(nv ? 3 * nv : 1, sizeof *G->vn);
	G->vborder = calloc(nv ? nv : 1, 1);
	if (!G->tv || !G->tn || !G->nb || !G->vn || !G->vborder) {
		fct_fail(err, "out of memory");
		goto fail;
	}
	if (fct_adj_build(&G->adj, t, err))
		goto fail;
	for (size_t f = 0; f < nt; f++) {
		const uint32_t *v = &t->fvert[t->fstart[f]];
		memcpy(&G->tv[3 * f], v, 3 * sizeof *v);
		const double *a = &t->xyz[3 * v[0]], *b = &t->xyz[3 * v[1]], *c = &t->xyz[3 * v[2]];
		double e1[3], e2[3], n[3];
		fct_v3_sub(e1, b, a);
		fct_v3_sub(e2, c, a);
		fct_v3_cross(n, e1, e2);
		double len = sqrt(fct_v3_dot(n, n));
		int degenerate = fct_triangle_degenerate(a, b, c) || !(len > 0) || !isfinite(len);
		for (int k = 0; k < 3; k++)
			G->tn[3 * f + k] = degenerate ? NAN : n[k] / len;
		for (int k = 0; k < 3; k++) {
			uint32_t e = G->adj.face_e[t->fstart[f] + k];
			int32_t other = -2;
			if (e == FCT_ADJ_NONE) {
				other = -2;
			} else if (fct_adj_edge_nfaces(&G->adj, e) == 1) {
				other = -1;
				G->vborder[v[k]] = G->vborder[v[(k + 1) % 3]] = 1;
			} else if (fct_adj_edge_nfaces(&G->adj, e) == 2) {
				const uint32_t *ef = &G->adj.edge_f[G->adj.edge_fstart[e]];
				other = (int32_t)(ef[0] == f ? ef[1] : ef[0]);
			}
			G->nb[3 * f + k] = other;
		}
		if (degenerate)
			continue;
		/* Angle-weighted pseudo-normals (Baerentzen and Aanaes). */
		for (int k = 0; k < 3; k++) {
			const double *p = &t->xyz[3 * v[k]], *q = &t->xyz[3 * v[(k + 1) % 3]],
			             *r = &t->xyz[3 * v[(k + 2) % 3]];
			double u[3], w[3];
			fct_v3_sub(u, q, p);
			fct_v3_sub(w, r, p);
			double c = fct_v3_dot(u, w) / sqrt(fct_v3_dot(u, u) * fct_v3_dot(w, w));
			double ang = acos(c < -1 ? -1 : c > 1 ? 1 : c);
			fct_v3_axpy(&G->vn[3 * v[k]], &G->vn[3 * v[k]], ang, &G->tn[3 * f]);
		}
	}
	/* A triangle next to a degenerate one treats that edge as a border. */
	for (size_t f = 0; f < nt; f++)
		for (int k = 0; k < 3; k++) {
			int32_t o = G->nb[3 * f + k];
			if (o >= 0 && isnan(G->tn[3 * (size_t)o]))
				G->nb[3 * f + k] = -1;
		}
	return 0;
fail:
	geo_free(G);
	return -1;
}

static inline double tri_closest(const struct geo *G, size_t t, const double x[3], double q[3],
                                 enum fct_tri_region *r)
{
	const uint32_t *v = &G->tv[3 * t];
	return fct_closest_on_triangle_nd(x, &G->xyz[3 * v[0]], &G->xyz[3 * v[1]], &G->xyz[3 * v[2]], q, r);
}

/* Walk from triangle t downhill to the triangle nearest x: across the edge
 * or around the vertex where the closest point lies.  Returns the triangle,
 * *d2 its squared distance. */
static int32_t walk(const struct geo *G, int32_t t, const double x[3], float *d2out)
{
	double q[3];
	enum fct_tri_region r;
	double best = tri_closest(G, (size_t)t, x, q, &r);
	for (int step = 0; step < 32; step++) {
		int32_t next = -1;
		double nd = best;
		if (r == FCT_TRI_AB || r == FCT_TRI_BC || r == FCT_TRI_CA) {
			int k = r == FCT_TRI_AB ? 0 : r == FCT_TRI_BC ? 1 : 2;
			int32_t o = G->nb[3 * (size_t)t + k];
			if (o >= 0) {
				double qq[3];
				enum fct_tri_region rr;
				double d = tri_closest(G, (size_t)o, x, qq, &rr);
				if (d < nd)
					nd = d, next = o;
			}
		} else if (r == FCT_TRI_A || r == FCT_TRI_B || r == FCT_TRI_C) {
			uint32_t v = G->tv[3 * (size_t)t + (r == FCT_TRI_A ? 0 : r == FCT_TRI_B ? 1 : 2)];
			for (uint32_t i = G->adj.vert_fstart[v]; i < G->adj.vert_fstart[v + 1]; i++) {
				uint32_t o = G->adj.vert_f[i];
				if (isnan(G->tn[3 * (size_t)o]))
					continue;
				double qq[3];
				enum fct_tri_region rr;
				double d = tri_closest(G, o, x, qq, &rr);
				if (d < nd)
					nd = d, next = (int32_t)o;
			}
		}
		if (next < 0)
			break;
		t = next;
		best = tri_closest(G, (size_t)t, x, q, &r);
	}
	*d2out = (float)best;
	return t;
}

/* Sensor geometry. ------------------------------------------------------- */

/* Pixel (u, v) and depth of world point p in r; 0 when it has none. */
static int range_project(const struct fct_range_image *r, const double p[3], double *u, double *v,
                         double *depth)
{
	double c[3];
	fct_pose_apply(r->inv, p, c);
	if (r->view.cam.kind == FCT_CAMERA_NONE) {
		*u = c[0] / r->view.ortho_step - r->u0;
		*v = c[1] / r->view.ortho_step - r->v0;
		*depth = -c[2];
		return 1;
	}
	return fct_camera_project(&r->view.cam, c, u, v, depth);
}

void fct_range_image_free(struct fct_range_image *r)
{
	if (r) {
		free(r->range);
		r->range = NULL;
	}
}

int fct_range_image_make(struct fct_range_image *r, const struct fct_fuse_view *v,
                         size_t max_pixels, struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	r->view = *v;
	fct_pose_invert(v->pose, r->inv);
	const struct fct_mesh *m = v->mesh;
	int ortho = v->cam.kind == FCT_CAMERA_NONE, pin = v->cam.kind == FCT_CAMERA_PINHOLE;
	if (ortho) {
		if (!(v->ortho_step > 0))
			return fct_fail(err, "orthographic view without a pixel size");
		double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
		for (size_t i = 0; i < m->nv; i++) {
			double c[3];
			fct_pose_apply(r->inv, &m->xyz[3 * i], c);
			for (int k = 0; k < 2; k++) {
				double s = c[k] / v->ortho_step;
				lo[k] = s < lo[k] ? s : lo[k];
				hi[k] = s > hi[k] ? s : hi[k];
			}
		}
		if (!(lo[0] <= hi[0] && lo[1] <= hi[1]))
			return fct_fail(err, "empty view");
		if (hi[0] - lo[0] > 1e6 || hi[1] - lo[1] > 1e6 ||
		    (hi[0] - lo[0] + 3) * (hi[1] - lo[1] + 3) > (double)max_pixels)
			return fct_fail(err, "range image of %.0f x %.0f pixels is too large",
			                hi[0] - lo[0] + 3, hi[1] - lo[1] + 3);
		r->u0 = floor(lo[0]) - 1;
		r->v0 = floor(lo[1]) - 1;
		r->width = (int)(ceil(hi[0]) - r->u0) + 2;
		r->height = (int)(ceil(hi[1]) - r->v0) + 2;
	} else {
		r->width = v->cam.width;
		r->height = v->cam.height;
		if (r->width < 1 || r->height < 1 ||
		    (double)r->width * (double)r->height > (double)max_pixels)
			return fct_fail(err, "camera of %d x %d pixels: no range image", r->width, r->height);
	}
	size_t np = (size_t)r->width * (size_t)r->height;
	r->range = calloc(np, sizeof *r->range);
	double *uvd = fct_alloc_array(m->nv, 3 * sizeof *uvd, err);
	if (!r->range || !uvd) {
		free(uvd);
		fct_range_image_free(r);
		return fct_fail(err, "out of memory");
	}
	for (size_t i = 0; i < m->nv; i++)
		if (!range_project(r, &m->xyz[3 * i], &uvd[3 * i], &uvd[3 * i + 1], &uvd[3 * i + 2]) ||
		    !(uvd[3 * i + 2] > 0))
			uvd[3 * i + 2] = NAN;
	for (size_t f = 0; f < m->nf; f++) {
		const uint32_t *fv = &m->fvert[m->fstart[f]];
		for (uint32_t k = 2; k < fct_face_size(m, f); k++) {
			const double *a = &uvd[3 * fv[0]], *b = &uvd[3 * fv[k - 1]], *c = &uvd[3 * fv[k]];
			if (!(isfinite(a[2]) && isfinite(b[2]) && isfinite(c[2])))
				continue;
			double umin = fmin(a[0], fmin(b[0], c[0])), umax = fmax(a[0], fmax(b[0], c[0]));
			double vmin = fmin(a[1], fmin(b[1], c[1])), vmax = fmax(a[1], fmax(b[1], c[1]));
			if (v->cam.kind == FCT_CAMERA_CYLINDRICAL && umax - umin > r->width / 2.0)
				continue;       /* across the seam */
			double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
			if (!(fabs(area) > 1e-12))
				continue;
			int u0 = (int)fmax(ceil(umin - 1e-9), 0), u1 = (int)fmin(floor(umax + 1e-9), r->width - 1);
			int v0 = (int)fmax(ceil(vmin - 1e-9), 0), v1 = (int)fmin(floor(vmax + 1e-9), r->height - 1);
			/* Depth is affine in the image for orthographic views; for
			 * perspective ones 1/depth is. */
			double za = pin ? 1 / a[2] : a[2], zb = pin ? 1 / b[2] : b[2], zc = pin ? 1 / c[2] : c[2];
			for (int y = v0; y <= v1; y++)
				for (int x = u0; x <= u1; x++) {
					double wb = ((x - a[0]) * (c[1] - a[1]) - (y - a[1]) * (c[0] - a[0])) / area;
					double wc = ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) / area;
					double wa = 1 - wb - wc;
					if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9)
						continue;
					double z = wa * za + wb * zb + wc * zc;
					if (pin)
						z = 1 / z;
					float *d = &r->range[(size_t)y * (size_t)r->width + (size_t)x];
					if (z > 0 && (*d == 0 || z < *d))
						*d = (float)z;
				}
		}
	}
	free(uvd);
	return 0;
}

/* Fusion. ---------------------------------------------------------------- */

static inline int in_clip(const struct fct_fuse_params *p, int32_t i, int32_t j, int32_t k)
{
	return !p->has_clip || (i >= p->clip_lo[0] && i <= p->clip_hi[0] && j >= p->clip_lo[1] &&
	                        j <= p->clip_hi[1] && k >= p->clip_lo[2] && k <= p->clip_hi[2]);
}

/* Voxel coordinates of world points must keep blocks within the 21-bit keys. */
#define MAX_INDEX (1 << 23)

static int index_of(double x, double voxel, int32_t *i, int up)
{
	double s = up ? ceil(x / voxel) : floor(x / voxel);
	if (!(fabs(s) < MAX_INDEX))
		return -1;
	*i = (int32_t)s;
	return 0;
}

static int update_voxel(struct fct_voxgrid *g, int32_t i, int32_t j, int32_t k, double d, double w,
                        struct fct_err *err)
{
	int l;
	struct fct_voxblock *b = fct_voxgrid_voxel_at(g, i, j, k, 1, &l, err);
	if (!b)
		return -1;
	double W = (double)b->weight[l] + w;
	b->sdf[l] = (float)(b->sdf[l] + (d - b->sdf[l]) * w / W);
	b->weight[l] = (float)W;
	return 0;
}

static double view_weight(const struct fct_fuse_view *v, const struct fct_fuse_params *p,
                          const double q[3], const double n[3])
{
	if (p->weight == FCT_FUSE_CONSTANT)
		return 1;
	double ray[3];
	if (v->cam.kind == FCT_CAMERA_NONE) {
		ray[0] = -v->pose[2], ray[1] = -v->pose[6], ray[2] = -v->pose[10];
	} else {
		double c[3] = { v->pose[3], v->pose[7], v->pose[11] };
		fct_v3_sub(ray, q, c);
	}
	double len = sqrt(fct_v3_dot(ray, ray));
	if (!(len > 0))
		return 1e-3;
	if (p->weight == FCT_FUSE_INCIDENCE) {
		double c = fabs(fct_v3_dot(ray, n)) / len;
		return c > 1e-3 ? c : 1e-3;
	}
	if (v->cam.kind == FCT_CAMERA_NONE)
		return 1;
	double depth = fabs(fct_v3_dot(ray, (double[3]){ v->pose[2], v->pose[6], v->pose[10] }));
	if (v->cam.kind == FCT_CAMERA_CYLINDRICAL)
		depth = len;
	return depth > 1e-3 ? 1 / (depth * depth) : 1e6;
}

static int fuse_projective(struct fct_voxgrid *g, const struct fct_fuse_view *v,
                           const struct fct_fuse_params *p, struct fct_fuse_stats *st,
                           struct fct_err *err)
{
	struct fct_range_image r;
	if (fct_range_image_make(&r, v, (size_t)1 << 28, err))
		return -1;
	double vox = fct_voxgrid_voxel(g), band = p->band;
	struct scratch s = { 0 };
	int rc = -1;
	const struct fct_mesh *m = v->mesh;
	for (size_t i = 0; i < m->nv; i++) {
		const double *x = &m->xyz[3 * i];
		int32_t lo[3], hi[3];
		int bad = 0;
		for (int k = 0; k < 3; k++) {
			bad |= index_of(x[k] - band, vox, &lo[k], 1) | index_of(x[k] + band, vox, &hi[k], 0);
			lo[k] = fct_vox_block_of(lo[k]);
			hi[k] = fct_vox_block_of(hi[k]);
		}
		if (bad) {
			fct_fail(err, "vertex %zu is too far from the origin for the voxel size", i);
			goto done;
		}
		for (int32_t bz = lo[2]; bz <= hi[2]; bz++)
			for (int32_t by = lo[1]; by <= hi[1]; by++)
				for (int32_t bx = lo[0]; bx <= hi[0]; bx++)
					if (!scratch_block(&s, bx, by, bz, 1, err))
						goto done;
	}
	for (size_t bi = 0; bi < s.n; bi++) {
		const struct sblock *b = s.blk[bi];
		for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
			int32_t i = b->bx * 8 + l % 8, j = b->by * 8 + l / 8 % 8, k = b->bz * 8 + l / 64;
			if (!in_clip(p, i, j, k))
				continue;
			double x[3] = { i * vox, j * vox, k * vox }, u, w, depth;
			if (!range_project(&r, x, &u, &w, &depth))
				continue;
			long ui = lround(u), vi = lround(w);
			if (ui < 0 || vi < 0 || ui >= r.width || vi >= r.height)
				continue;
			double R = r.range[(size_t)vi * (size_t)r.width + (size_t)ui];
			if (!(R > 0))
				continue;
			double d = R - depth;
			if (d < -band)
				continue;
			double wt = p->weight == FCT_FUSE_DEPTH2 && v->cam.kind != FCT_CAMERA_NONE ? 1 / (R * R) : 1;
			if (update_voxel(g, i, j, k, d < band ? d : band, wt, err))
				goto done;
			st->voxels++;
		}
	}
	st->faces += m->nf;
	rc = 0;
done:
	scratch_free(&s);
	fct_range_image_free(&r);
	return rc;
}

/* Set voxel (i, j, k) of the scratch to triangle t at squared distance d2
 * in layer L when better; *isnew tells whether it was untouched. */
static int offer(struct scratch *s, int32_t i, int32_t j, int32_t k, int32_t t, float d2, int L,
                 int *isnew, struct sblock **bout, int *lout, struct fct_err *err)
{
	struct sblock *b = scratch_block(s, fct_vox_block_of(i), fct_vox_block_of(j), fct_vox_block_of(k), 1, err);
	if (!b)
		return -1;
	int l = local_index(i, j, k);
	*isnew = b->layer[l] == NOLAYER;
	if (*isnew || (b->layer[l] == L && (d2 < b->d2[l] || (d2 == b->d2[l] && t < b->tri[l])))) {
		b->d2[l] = d2;
		b->tri[l] = t;
		if (*isnew)
			b->layer[l] = (uint8_t)L;
	}
	*bout = b;
	*lout = l;
	return 0;
}

struct vref {
	int32_t i, j, k;
};

int fct_fuse_view(struct fct_voxgrid *g, const struct fct_fuse_view *v,
                  const struct fct_fuse_params *p, struct fct_fuse_stats *stats,
                  struct fct_err *err)
{
	struct fct_fuse_stats dummy = { 0 };
	struct fct_fuse_stats *st = stats ? stats : &dummy;
	if (p->projective)
		return fuse_projective(g, v, p, st, err);
	double vox = fct_voxgrid_voxel(g), band = p->band;
	struct geo G;
	if (geo_build(&G, v->mesh, err))
		return -1;
	struct scratch s = { 0 };
	struct vref *cur = NULL, *next = NULL;
	size_t ncur = 0, curcap = 0, nnext = 0, nextcap = 0;
	int rc = -1;
	int layers = (int)ceil(band / vox) + 1;
	if (layers > 200)
		layers = 200;
	/* Splat: each triangle into the voxels of its box grown by half a
	 * voxel, a connected shell around the surface; the walks of the
	 * propagation correct what this misses. */
	for (size_t t = 0; t < G.nt; t++) {
		if (isnan(G.tn[3 * t]))
			continue;
		st->faces++;
		const uint32_t *tv = &G.tv[3 * t];
		int32_t lo[3], hi[3];
		int bad = 0;
		for (int k = 0; k < 3; k++) {
			double a = G.xyz[3 * tv[0] + k], b = G.xyz[3 * tv[1] + k], c = G.xyz[3 * tv[2] + k];
			bad |= index_of(fmin(a, fmin(b, c)) - vox / 2, vox, &lo[k], 1);
			bad |= index_of(fmax(a, fmax(b, c)) + vox / 2, vox, &hi[k], 0);
		}
		if (bad) {
			fct_fail(err, "triangle %zu is too far from the origin for the voxel size", t);
			goto done;
		}
		for (int32_t k = lo[2]; k <= hi[2]; k++)
			for (int32_t j = lo[1]; j <= hi[1]; j++)
				for (int32_t i = lo[0]; i <= hi[0]; i++) {
					double x[3] = { i * vox, j * vox, k * vox }, q[3];
					enum fct_tri_region r;
					float d2 = (float)tri_closest(&G, t, x, q, &r);
					int isnew, l;
					struct sblock *b;
					if (offer(&s, i, j, k, (int32_t)t, d2, 0, &isnew, &b, &l, err))
						goto done;
					if (isnew) {
						if (fct_grow((void **)&cur, &curcap, ncur + 1, sizeof *cur, err))
							goto done;
						cur[ncur++] = (struct vref){ i, j, k };
					}
				}
	}
	for (size_t c = 0; c < ncur; c++) {
		struct vref x0 = cur[c];
		struct sblock *b = scratch_block(&s, fct_vox_block_of(x0.i), fct_vox_block_of(x0.j),
		                                 fct_vox_block_of(x0.k), 0, err);
		int l = local_index(x0.i, x0.j, x0.k);
		double x[3] = { x0.i * vox, x0.j * vox, x0.k * vox };
		b->tri[l] = walk(&G, b->tri[l], x, &b->d2[l]);
	}
	/* Grow the band layer by layer. */
	double reach2 = (band + vox) * (band + vox);
	for (int L = 1; L <= layers && ncur; L++) {
		nnext = 0;
		for (size_t c = 0; c < ncur; c++) {
			struct vref x0 = cur[c];
			struct sblock *b0 = scratch_block(&s, fct_vox_block_of(x0.i), fct_vox_block_of(x0.j),
			                                  fct_vox_block_of(x0.k), 0, err);
			int32_t t = b0->tri[local_index(x0.i, x0.j, x0.k)];
			for (int dz = -1; dz <= 1; dz++)
				for (int dy = -1; dy <= 1; dy++)
					for (int dx = -1; dx <= 1; dx++) {
						int32_t i = x0.i + dx, j = x0.j + dy, k = x0.k + dz;
						struct sblock *b = scratch_block(&s, fct_vox_block_of(i), fct_vox_block_of(j),
						                                 fct_vox_block_of(k), 0, err);
						int l = local_index(i, j, k);
						if (b && b->layer[l] != NOLAYER && (b->layer[l] < L || b->tri[l] == t))
							continue;
						double x[3] = { i * vox, j * vox, k * vox }, q[3];
						enum fct_tri_region r;
						float d2 = (float)tri_closest(&G, (size_t)t, x, q, &r);
						if (d2 > reach2)
							continue;
						int isnew;
						if (offer(&s, i, j, k, t, d2, L, &isnew, &b, &l, err))
							goto done;
						if (isnew) {
							if (fct_grow((void **)&next, &nextcap, nnext + 1, sizeof *next, err))
								goto done;
							next[nnext++] = (struct vref){ i, j, k };
						}
					}
		}
		/* Walk each new voxel's triangle down to its nearest. */
		for (size_t c = 0; c < nnext; c++) {
			struct vref x0 = next[c];
			struct sblock *b = scratch_block(&s, fct_vox_block_of(x0.i), fct_vox_block_of(x0.j),
			                                 fct_vox_block_of(x0.k), 0, err);
			int l = local_index(x0.i, x0.j, x0.k);
			double x[3] = { x0.i * vox, x0.j * vox, x0.k * vox };
			b->tri[l] = walk(&G, b->tri[l], x, &b->d2[l]);
		}
		struct vref *tmp = cur;
		size_t tcap = curcap;
		cur = next, curcap = nextcap, ncur = nnext;
		next = tmp, nextcap = tcap;
	}
	/* Signed distances into the volume. */
	double band2 = band * band;
	for (size_t bi = 0; bi < s.n; bi++) {
		const struct sblock *b = s.blk[bi];
		for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
			if (b->layer[l] == NOLAYER || !(b->d2[l] <= band2))
				continue;
			int32_t i = b->bx * 8 + l % 8, j = b->by * 8 + l / 8 % 8, k = b->bz * 8 + l / 64;
			if (!in_clip(p, i, j, k))
				continue;
			size_t t = (size_t)b->tri[l];
			double x[3] = { i * vox, j * vox, k * vox }, q[3], xq[3];
			enum fct_tri_region r;
			double d2 = tri_closest(&G, t, x, q, &r);
			const double *n = &G.tn[3 * t];
			fct_v3_sub(xq, x, q);
			double d;
			if (r == FCT_TRI_FACE) {
				d = fct_v3_dot(xq, n);
			} else if (r == FCT_TRI_A || r == FCT_TRI_B || r == FCT_TRI_C) {
				uint32_t vv = G.tv[3 * t + (r == FCT_TRI_A ? 0 : r == FCT_TRI_B ? 1 : 2)];
				if (G.vborder[vv]) {
					st->border++;
					continue;
				}
				d = copysign(sqrt(d2), fct_v3_dot(xq, &G.vn[3 * vv]));
			} else {
				int e = r == FCT_TRI_AB ? 0 : r == FCT_TRI_BC ? 1 : 2;
				int32_t o = G.nb[3 * t + (size_t)e];
				if (o == -1) {
					st->border++;
					continue;
				}
				double pn[3];
				if (o >= 0)
					fct_v3_add(pn, n, &G.tn[3 * (size_t)o]);
				else
					memcpy(pn, n, sizeof pn);
				d = copysign(sqrt(d2), fct_v3_dot(xq, pn));
			}
			if (update_voxel(g, i, j, k, d, view_weight(v, p, q, n), err))
				goto done;
			st->voxels++;
		}
	}
	rc = 0;
done:
	free(cur);
	free(next);
	scratch_free(&s);
	geo_free(&G);
	return rc;
}

/* Space carving. --------------------------------------------------------- */

size_t fct_carve_bytes(const int32_t lo[3], const int32_t hi[3])
{
	double words = ceil((hi[0] - (double)lo[0] + 1) / 64) * (hi[1] - (double)lo[1] + 1) *
	               (hi[2] - (double)lo[2] + 1);
	double bytes = 2 * 8 * words;
	return bytes > (double)SIZE_MAX / 2 ? SIZE_MAX / 2 : (size_t)bytes;
}

/* Row r of bitset s dilated by one along x. */
static inline uint64_t dil_word(const uint64_t *row, size_t w, size_t nw)
{
	uint64_t x = row[w];
	uint64_t r = x | x << 1 | x >> 1;
	if (w > 0)
		r |= row[w - 1] >> 63;
	if (w + 1 < nw)
		r |= row[w + 1] << 63;
	return r;
}

int fct_carve(struct fct_voxgrid *g, const struct fct_range_image *views, size_t nviews,
              const int32_t lo[3], const int32_t hi[3], double band, float mark_weight,
              size_t *carved, struct fct_err *err)
{
	double vox = fct_voxgrid_voxel(g);
	size_t nx = (size_t)(hi[0] - lo[0] + 1), ny = (size_t)(hi[1] - lo[1] + 1),
	       nz = (size_t)(hi[2] - lo[2] + 1);
	if (hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2])
		return fct_fail(err, "carving box is empty");
	size_t nw = (nx + 63) / 64, rows, words;
	if (fct_mul_size(ny, nz, &rows) || fct_mul_size(rows, nw, &words))
		return fct_fail(err, "carving box too large");
	uint64_t *K = calloc(words, 8), *C = calloc(words, 8), *A = calloc(3 * nw, 8),
	         *B = calloc(3 * nw, 8);
	int rc = -1;
	if (!K || !C || !A || !B) {
		fct_fail(err, "out of memory for the carving bitsets (%zu MB)", 2 * words * 8 >> 20);
		goto done;
	}
	/* K: observed voxels. */
	for (size_t bi = 0; bi < fct_voxgrid_count(g); bi++) {
		const struct fct_voxblock *b = fct_voxgrid_at(g, bi);
		for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
			if (!(b->weight[l] > 0))
				continue;
			int64_t i = (int64_t)b->bx * 8 + l % 8 - lo[0], j = (int64_t)b->by * 8 + l / 8 % 8 - lo[1],
			        k = (int64_t)b->bz * 8 + l / 64 - lo[2];
			if (i < 0 || j < 0 || k < 0 || i >= (int64_t)nx || j >= (int64_t)ny || k >= (int64_t)nz)
				continue;
			K[((size_t)k * ny + (size_t)j) * nw + (size_t)i / 64] |= 1ull << (i % 64);
		}
	}
	/* C: seen through by some view (the outermost layer never). */
	for (size_t vi = 0; vi < nviews; vi++) {
		const struct fct_range_image *r = &views[vi];
		const struct fct_camera *cam = &r->view.cam;
		const double *M = r->inv;
		for (size_t k = 1; k + 1 < nz; k++)
			for (size_t j = 1; j + 1 < ny; j++) {
				uint64_t *row = &C[(k * ny + j) * nw];
				double y = (lo[1] + (double)j) * vox, z = (lo[2] + (double)k) * vox;
				double x0 = (lo[0] + 1.0) * vox;
				double c0[3], dc[3] = { M[0] * vox, M[4] * vox, M[8] * vox };
				for (int a = 0; a < 3; a++)
					c0[a] = M[4 * a] * x0 + M[4 * a + 1] * y + M[4 * a + 2] * z + M[4 * a + 3];
				for (size_t i = 1; i + 1 < nx; i++) {
					double c[3] = { c0[0] + dc[0] * (double)(i - 1), c0[1] + dc[1] * (double)(i - 1),
					                c0[2] + dc[2] * (double)(i - 1) };
					double u, v, depth;
					if (cam->kind == FCT_CAMERA_PINHOLE) {
						if (!(c[2] > 0))
							continue;
						u = cam->fx * c[0] / c[2] + cam->cx;
						v = cam->fy * c[1] / c[2] + cam->cy;
						depth = c[2];
					} else if (cam->kind == FCT_CAMERA_NONE) {
						u = c[0] / r->view.ortho_step - r->u0;
						v = c[1] / r->view.ortho_step - r->v0;
						depth = -c[2];
					} else if (!fct_camera_project(cam, c, &u, &v, &depth)) {
						continue;
					}
					if (!(u > -0.5 && v > -0.5 && u < r->width - 0.5 && v < r->height - 0.5))
						continue;
					size_t ui = (size_t)(u + 0.5), vv = (size_t)(v + 0.5);
					float R = r->range[vv * (size_t)r->width + ui];
					if (R > 0 && depth < R)
						row[i / 64] |= 1ull << (i % 64);
				}
			}
	}
	size_t ncarved = 0;
	for (size_t w = 0; w < words; w++) {
		C[w] &= ~K[w];
		ncarved += (size_t)__builtin_popcountll(C[w]);
	}
	if (carved)
		*carved = ncarved;
	/* Mark the empty and unknown voxels next to a change. */
	uint64_t lastmask = nx % 64 ? (1ull << (nx % 64)) - 1 : ~0ull;
	for (size_t k = 0; k < nz; k++)
		for (size_t j = 0; j < ny; j++) {
			/* A = dilation of C | K, B = dilation of U | K, U = ~(C | K). */
			memset(A, 0, 3 * nw * 8);
			memset(B, 0, 3 * nw * 8);
			for (int dz = -1; dz <= 1; dz++)
				for (int dy = -1; dy <= 1; dy++) {
					if ((k == 0 && dz < 0) || (k + 1 == nz && dz > 0) || (j == 0 && dy < 0) ||
					    (j + 1 == ny && dy > 0))
						continue;
					size_t rr = ((k + (size_t)dz) * ny + (j + (size_t)dy)) * nw;
					uint64_t *ck = &A[nw], *uk = &B[nw];
					for (size_t w = 0; w < nw; w++) {
						uint64_t m = w + 1 == nw ? lastmask : ~0ull;
						ck[w] = (C[rr + w] | K[rr + w]) & m;
						uk[w] = (~C[rr + w] & m);   /* U | K = ~C */
					}
					for (size_t w = 0; w < nw; w++) {
						A[2 * nw + w] |= dil_word(ck, w, nw);
						B[2 * nw + w] |= dil_word(uk, w, nw);
					}
				}
			size_t r0 = (k * ny + j) * nw;
			for (size_t w = 0; w < nw; w++) {
				uint64_t m = w + 1 == nw ? lastmask : ~0ull;
				uint64_t U = ~(C[r0 + w] | K[r0 + w]) & m;
				uint64_t mark[2] = { U & A[2 * nw + w], C[r0 + w] & B[2 * nw + w] };
				for (int s = 0; s < 2; s++)
					while (mark[s]) {
						int bit = __builtin_ctzll(mark[s]);
						mark[s] &= mark[s] - 1;
						int l;
						struct fct_voxblock *b = fct_voxgrid_voxel_at(
						        g, lo[0] + (int32_t)(w * 64 + (size_t)bit), lo[1] + (int32_t)j,
						        lo[2] + (int32_t)k, 1, &l, err);
						if (!b)
							goto done;
						b->sdf[l] = (float)(s ? band : -band);
						b->weight[l] = mark_weight;
					}
			}
		}
	rc = 0;
done:
	free(K);
	free(C);
	free(A);
	free(B);
	return rc;
}

/* Level-set curvature flow. ---------------------------------------------- */

int fct_curvature_flow(struct fct_voxgrid *g, int iters, double band, struct fct_err *err)
{
	size_t nb = fct_voxgrid_count(g);
	double h = fct_voxgrid_voxel(g), dt = h * h / 8;
	float *out = fct_alloc_array(nb, FCT_VOXBLOCK_N * sizeof *out, err);
	float *halo = fct_alloc_array(1000, sizeof *halo, err);
	if (!out || !halo) {
		free(out);
		free(halo);
		return -1;
	}
	for (int it = 0; it < iters; it++) {
		for (size_t bi = 0; bi < nb; bi++) {
			const struct fct_voxblock *b = fct_voxgrid_at(g, bi);
			/* The block with a one-voxel halo; unobserved = NaN. */
			for (int z = -1; z <= 8; z++)
				for (int y = -1; y <= 8; y++)
					for (int x = -1; x <= 8; x++) {
						int ox = x < 0 ? -1 : x > 7, oy = y < 0 ? -1 : y > 7, oz = z < 0 ? -1 : z > 7;
						const struct fct_voxblock *nbk = b;
						if (ox || oy || oz)
							nbk = fct_voxgrid_block(g, b->bx + ox, b->by + oy, b->bz + oz, 0, NULL);
						int l = (x - 8 * ox) + 8 * ((y - 8 * oy) + 8 * (z - 8 * oz));
						halo[(x + 1) + 10 * ((y + 1) + 10 * (z + 1))] =
						        nbk && nbk->weight[l] > 0 ? nbk->sdf[l] : NAN;
					}
			for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
				int x = l % 8 + 1, y = l / 8 % 8 + 1, z = l / 64 + 1;
				const float *h0 = &halo[x + 10 * (y + 10 * z)];
				out[bi * FCT_VOXBLOCK_N + (size_t)l] = b->sdf[l];
				if (!(b->weight[l] > 0))
					continue;
				/* Unobserved neighbours mirror the voxel (no flux across
				 * the edge of the data), so open borders stay put. */
				float cc[27];
				for (int dz = -1; dz <= 1; dz++)
					for (int dy = -1; dy <= 1; dy++)
						for (int dx = -1; dx <= 1; dx++) {
							float w = h0[dx + 10 * dy + 100 * dz];
							cc[13 + dx + 3 * dy + 9 * dz] = isnan(w) ? h0[0] : w;
						}
				const float *c = &cc[13];
				const int X = 1, Y = 3, Z = 9;
				double fx = (c[X] - c[-X]) / (2 * h), fy = (c[Y] - c[-Y]) / (2 * h),
				       fz = (c[Z] - c[-Z]) / (2 * h);
				double fxx = (c[X] - 2 * c[0] + c[-X]) / (h * h), fyy = (c[Y] - 2 * c[0] + c[-Y]) / (h * h),
				       fzz = (c[Z] - 2 * c[0] + c[-Z]) / (h * h);
				double fxy = (c[X + Y] - c[X - Y] - c[Y - X] + c[-X - Y]) / (4 * h * h);
				double fxz = (c[X + Z] - c[X - Z] - c[Z - X] + c[-X - Z]) / (4 * h * h);
				double fyz = (c[Y + Z] - c[Y - Z] - c[Z - Y] + c[-Y - Z]) / (4 * h * h);
				double g2 = fx * fx + fy * fy + fz * fz;
				double num = fxx * (fy * fy + fz * fz) + fyy * (fx * fx + fz * fz) +
				             fzz * (fx * fx + fy * fy) - 2 * (fx * fy * fxy + fx * fz * fxz + fy * fz * fyz);
				/* Where the gradient vanishes (the centre of a blob
				 * shrunk to a voxel, flat truncated regions) the
				 * flow is undefined: fall back on diffusion, which
				 * lifts an isolated minimum and leaves flat regions. */
				double nv = c[0] + dt * (g2 > 1e-6 ? num / g2 : (fxx + fyy + fzz) / 2);
				out[bi * FCT_VOXBLOCK_N + (size_t)l] = (float)(nv > band ? band : nv < -band ? -band : nv);
			}
		}
		for (size_t bi = 0; bi < nb; bi++)
			memcpy(fct_voxgrid_at(g, bi)->sdf, &out[bi * FCT_VOXBLOCK_N], sizeof(float) * FCT_VOXBLOCK_N);
	}
	free(out);
	free(halo);
	return 0;
}

/* fusecand.c - a view's candidate voxels for fusion: the blocks of the
 * volume its band may reach, from the boxes and slabs of its surface
 * points per block (Sun, Paik, Koschan and Abidi, sec. 3: the voxels
 * within the band of a view's surface), kept in a hash of 8^3 blocks. */
#include "fusion/fusepriv.h"

#include <stdlib.h>

#include "geom/geom.h"

static inline unsigned recent_slot(int32_t bx, int32_t by, int32_t bz)
{
	return ((uint32_t)bx + 3 * (uint32_t)by + 5 * (uint32_t)bz) & 15;
}

static uint64_t block_key(int32_t bx, int32_t by, int32_t bz)
{
	return ((uint64_t)(uint32_t)bx & 0x1fffff) << 42 | ((uint64_t)(uint32_t)by & 0x1fffff) << 21 |
	       ((uint64_t)(uint32_t)bz & 0x1fffff);
}

/* The slot of key k in a table of cap (a power of two).  The product's
 * high bits depend on every bit of the key; its low and middle ones only
 * on the key's low bits (z and part of y), which chained whole columns of
 * blocks along x into one probe sequence. */
static size_t key_hash(uint64_t k, size_t cap)
{
	k = (k ^ k >> 31) * 0x9e3779b97f4a7c15ull;
	return (size_t)(k ^ k >> 32) & (cap - 1);
}

void fuse_scratch_free(struct scratch *s)
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

/* The scratch block (bx, by, bz), created empty (lo > hi) when create is
 * set; NULL when absent or out of memory (err set then). */
static struct sblock *scratch_block(struct scratch *s, int32_t bx, int32_t by, int32_t bz,
                                    int create, struct fct_err *err)
{
	if (s->last && s->last->bx == bx && s->last->by == by && s->last->bz == bz)
		return s->last;
	struct sblock **rc = &s->recent[recent_slot(bx, by, bz)];
	if (*rc && (*rc)->bx == bx && (*rc)->by == by && (*rc)->bz == bz)
		return s->last = *rc;
	uint64_t k = block_key(bx, by, bz);
	if (s->cap) {
		size_t h = key_hash(k, s->cap);
		while (s->keys[h] != UINT64_MAX) {
			if (s->keys[h] == k)
				return s->last = *rc = s->blk[s->slot[h]];
			h = (h + 1) & (s->cap - 1);
		}
	}
	if (!create)
		return NULL;
	if (2 * (s->n + 1) > s->cap && scratch_rehash(s, s->cap ? 2 * s->cap : 1024, err))
		return NULL;
	if (fct_grow((void **)&s->blk, &s->blkcap, s->n + 1, sizeof *s->blk, err))
		return NULL;
	struct sblock *b = calloc(1, sizeof *b);
	if (!b) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	b->bx = bx, b->by = by, b->bz = bz;
	for (int a = 0; a < 3; a++)
		b->lo[a] = FCT_VOXBLOCK, b->hi[a] = -1, b->plo[a] = INFINITY, b->phi[a] = -INFINITY;
	b->slo = INFINITY, b->shi = -INFINITY;
	size_t h = key_hash(k, s->cap);
	while (s->keys[h] != UINT64_MAX)
		h = (h + 1) & (s->cap - 1);
	s->keys[h] = k;
	s->slot[h] = (uint32_t)s->n;
	s->blk[s->n++] = b;
	return s->last = *rc = b;
}

/* Voxel coordinates of world points must keep blocks within the 21-bit keys. */
#define MAX_INDEX (1 << 23)

/* Candidate voxels: the box of the surface's points (vertices, and points
 * at most half a voxel apart on larger triangles) per block of their cells,
 * grown by the band; for true distance also the slab of those points
 * across the block's mean normal, grown by the band. */
struct cand {
	struct scratch cells;    /* blocks with the box of their surface points (plo, phi) */
	double inv;
	struct fct_err *err;
};

/* Point p in voxel units.  The axes written out, as all the helpers of
 * the fuse_candidates' passes: a loop over them is not unrolled at -O2 and
 * goes through the stack, in loops over every vertex. */
static inline void to_voxels(const struct cand *c, const double p[3], double s[3])
{
	s[0] = p[0] * c->inv, s[1] = p[1] * c->inv, s[2] = p[2] * c->inv;
}

/* floor(s) for |s| < MAX_INDEX, without a call. */
static inline int32_t floor_index(double s)
{
	int32_t t = (int32_t)s;
	return t - (s < (double)t);
}

/* cell_of's failure, on the first axis out (i set all the same). */
static int too_far(struct cand *c, const double p[3], const double s[3], int32_t i[3])
{
	i[0] = i[1] = i[2] = 0;
	int k = !(fabs(s[0]) < MAX_INDEX) ? 0 : !(fabs(s[1]) < MAX_INDEX) ? 1 : 2;
	return fct_fail(c->err, "the view reaches %g m: too far from the origin for the voxel size", p[k]);
}

/* p in voxel units in s, its cell in i; -1 (err set) when p is too far out. */
static inline int cell_of(struct cand *c, const double p[3], double s[3], int32_t i[3])
{
	to_voxels(c, p, s);
	if (!(fabs(s[0]) < MAX_INDEX && fabs(s[1]) < MAX_INDEX && fabs(s[2]) < MAX_INDEX))
		return too_far(c, p, s, i);
	i[0] = floor_index(s[0]), i[1] = floor_index(s[1]), i[2] = floor_index(s[2]);
	return 0;
}

/* Voxels lo..hi (each axis) into the boxes of their blocks in s. */
static inline int add_box(struct scratch *s, const int32_t lo[3], const int32_t hi[3], struct fct_err *err)
{
	int32_t blo[3], bhi[3];
	for (int k = 0; k < 3; k++)
		blo[k] = fct_vox_block_of(lo[k]), bhi[k] = fct_vox_block_of(hi[k]);
	struct sblock *lb = s->last;
	if (lb && blo[0] == lb->bx && bhi[0] == lb->bx && blo[1] == lb->by && bhi[1] == lb->by &&
	    blo[2] == lb->bz && bhi[2] == lb->bz) {
		/* Within the block of the box before (most boxes are). */
		int32_t o[3] = { lb->bx * FCT_VOXBLOCK, lb->by * FCT_VOXBLOCK, lb->bz * FCT_VOXBLOCK };
		for (int k = 0; k < 3; k++) {
			int8_t l = (int8_t)(lo[k] - o[k]), h = (int8_t)(hi[k] - o[k]);
			lb->lo[k] = l < lb->lo[k] ? l : lb->lo[k];
			lb->hi[k] = h > lb->hi[k] ? h : lb->hi[k];
		}
		return 0;
	}
	for (int32_t bz = blo[2]; bz <= bhi[2]; bz++)
		for (int32_t by = blo[1]; by <= bhi[1]; by++)
			for (int32_t bx = blo[0]; bx <= bhi[0]; bx++) {
				struct sblock *b = scratch_block(s, bx, by, bz, 1, err);
				if (!b)
					return -1;
				int32_t o[3] = { bx * FCT_VOXBLOCK, by * FCT_VOXBLOCK, bz * FCT_VOXBLOCK };
				for (int k = 0; k < 3; k++) {
					int32_t l = lo[k] - o[k], h = hi[k] - o[k];
					l = l < 0 ? 0 : l;
					h = h > FCT_VOXBLOCK - 1 ? FCT_VOXBLOCK - 1 : h;
					b->lo[k] = (int8_t)(l < b->lo[k] ? l : b->lo[k]);
					b->hi[k] = (int8_t)(h > b->hi[k] ? h : b->hi[k]);
				}
			}
	return 0;
}

/* The box lo..hi (voxel units) holds surface points of b: into b's slab. */
static inline void slab_extend(struct sblock *b, const double lo[3], const double hi[3])
{
	const double *n = b->sn;
	if (!(n[0] || n[1] || n[2]))
		return;
	double a0 = n[0] * lo[0], c0 = n[0] * hi[0], a1 = n[1] * lo[1], c1 = n[1] * hi[1],
	       a2 = n[2] * lo[2], c2 = n[2] * hi[2];
	/* Sums from 0, in this order (-0 comes out +0). */
	double dl = 0 + dmin(a0, c0) + dmin(a1, c1) + dmin(a2, c2);
	double dh = 0 + dmax(c0, a0) + dmax(c1, a1) + dmax(c2, a2);
	b->slo = dmin(dl, b->slo);
	b->shi = dmax(dh, b->shi);
}

/* The box lo..hi (voxel units) of surface points in cells clo..chi into
 * the boxes of the blocks of those cells, clipped to each block's extent
 * [8 B, 8 B + 8] along an axis where it spans several (c->cells.last
 * is the block of a point then). */
static inline int add_span(struct cand *c, const double lo[3], const double hi[3], const int32_t clo[3],
                           const int32_t chi[3])
{
	int32_t blo[3], bhi[3];
	for (int k = 0; k < 3; k++)
		blo[k] = fct_vox_block_of(clo[k]), bhi[k] = fct_vox_block_of(chi[k]);
	struct sblock *lb = c->cells.last;
	if (lb && blo[0] == lb->bx && bhi[0] == lb->bx && blo[1] == lb->by && bhi[1] == lb->by &&
	    blo[2] == lb->bz && bhi[2] == lb->bz) {
		/* Within the block of the box before (most boxes are). */
		box_add(lb->plo, lb->phi, lo, hi);
		slab_extend(lb, lo, hi);
		return 0;
	}
	for (int32_t bz = blo[2]; bz <= bhi[2]; bz++)
		for (int32_t by = blo[1]; by <= bhi[1]; by++)
			for (int32_t bx = blo[0]; bx <= bhi[0]; bx++) {
				struct sblock *b = scratch_block(&c->cells, bx, by, bz, 1, c->err);
				if (!b)
					return -1;
				int32_t bb[3] = { bx, by, bz };
				double cl[3], ch[3];
				for (int k = 0; k < 3; k++) {
					double l = lo[k], h = hi[k], o = (double)bb[k] * FCT_VOXBLOCK;
					if (blo[k] < bhi[k]) {
						l = l < o ? o : l;
						h = h > o + FCT_VOXBLOCK ? o + FCT_VOXBLOCK : h;
					}
					cl[k] = l, ch[k] = h;
				}
				box_add(b->plo, b->phi, cl, ch);
				slab_extend(b, cl, ch);
			}
	return 0;
}

/* Point p, grown by h voxels each way, into the box of its cell's block. */
static inline int add_point(struct cand *c, const double p[3], double h)
{
	double s[3], lo[3], hi[3];
	int32_t i[3];
	if (cell_of(c, p, s, i))
		return -1;
	for (int k = 0; k < 3; k++)
		lo[k] = s[k] - h, hi[k] = s[k] + h;
	return add_span(c, lo, hi, i, i);
}

/* The vertices into the boxes of their cells' blocks; vb[i] is vertex i's
 * block.  Consecutive vertices are mostly in one block: a run
 * of them makes its box in locals and puts it into the block's once
 * (minima and maxima taken in the same order, so the box is the same). */
static int vertex_boxes(struct cand *c, const struct geo *G, struct sblock **vb)
{
	for (size_t i = 0; i < G->nv;) {
		double s[3], lo[3], hi[3];
		int32_t cell[3];
		if (cell_of(c, &G->xyz[3 * i], s, cell))
			return -1;
		struct sblock *b = scratch_block(&c->cells, fct_vox_block_of(cell[0]), fct_vox_block_of(cell[1]),
		                                 fct_vox_block_of(cell[2]), 1, c->err);
		if (!b)
			return -1;
		int32_t base[3] = { b->bx * FCT_VOXBLOCK, b->by * FCT_VOXBLOCK, b->bz * FCT_VOXBLOCK };
		memcpy(lo, s, sizeof s);
		memcpy(hi, s, sizeof s);
		vb[i] = b;
		for (i++; i < G->nv; i++) {
			if (cell_of(c, &G->xyz[3 * i], s, cell))
				return -1;
			if ((uint32_t)(cell[0] - base[0]) >= FCT_VOXBLOCK || (uint32_t)(cell[1] - base[1]) >= FCT_VOXBLOCK ||
			    (uint32_t)(cell[2] - base[2]) >= FCT_VOXBLOCK)
				break;   /* the next run's first vertex */
			box_add(lo, hi, s, s);
			vb[i] = b;
		}
		box_add(b->plo, b->phi, lo, hi);
	}
	return 0;
}

/* The slabs of the vertices' blocks (vb: each vertex's), across the mean
 * unit normal of the triangles at their first vertex (made here where G
 * has none): a voxel within the band of a point of the block is within
 * the band of its slab too, whatever the slab's direction, so walls
 * across the axes need not search the whole box around them. */
static void vertex_slabs(struct cand *c, const struct geo *G, struct sblock **vb)
{
	for (size_t t = 0; t < G->nt; t++) {
		const uint32_t *tv = &G->tv[3 * t];
		double n[3];
		if (G->tn) {
			const float *u = &G->tn[4 * t];
			n[0] = u[0], n[1] = u[1], n[2] = u[2];
		} else {
			fct_triangle_cross(n, &G->xyz[3 * tv[0]], &G->xyz[3 * tv[1]], &G->xyz[3 * tv[2]]);
			double len = sqrt(fct_v3_dot(n, n));
			for (int k = 0; k < 3; k++)
				n[k] /= len;
		}
		if (!(isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2])))
			continue;
		struct sblock *b = vb[tv[0]];
		for (int k = 0; k < 3; k++)
			b->sn[k] += n[k];
	}
	for (size_t bi = 0; bi < c->cells.n; bi++) {
		struct sblock *b = c->cells.blk[bi];
		double len = sqrt(b->sn[0] * b->sn[0] + b->sn[1] * b->sn[1] + b->sn[2] * b->sn[2]);
		for (int k = 0; k < 3; k++)
			b->sn[k] = len > 0 ? b->sn[k] / len : 0;
	}
	for (size_t i = 0; i < G->nv; i++) {
		double p[3];
		to_voxels(c, &G->xyz[3 * i], p);
		slab_extend(vb[i], p, p);
	}
}

/* The blocks of s around one cell block, for add_rows: its rows come back
 * to the same few blocks again and again, and a hash lookup for each costs
 * more than the row.  By block from base (NULL: not looked up yet); those
 * farther out (bands of many voxels) are looked up each time. */
enum { NEAR = 4 };

struct near {
	int32_t base[3];
	struct sblock *b[NEAR][NEAR][NEAR];
};

static inline struct sblock *near_block(struct scratch *s, struct near *nb, int32_t bx, int32_t by,
                                        int32_t bz, struct fct_err *err)
{
	uint32_t i = (uint32_t)(bx - nb->base[0]), j = (uint32_t)(by - nb->base[1]), k = (uint32_t)(bz - nb->base[2]);
	if (i >= NEAR || j >= NEAR || k >= NEAR)
		return scratch_block(s, bx, by, bz, 1, err);
	struct sblock **p = &nb->b[k][j][i];
	if (!*p)
		*p = scratch_block(s, bx, by, bz, 1, err);   /* created where it was before */
	return *p;
}

/* True distance: the voxels of box lo..hi within rb of cb's slab, row by
 * row, into the rows of their blocks in s (rows_box makes their boxes).
 * 0 or -1. */
static int add_rows(struct scratch *s, const struct sblock *cb, const int32_t lo[3], const int32_t hi[3],
                    double rb, struct fct_err *err)
{
	const double *n = cb->sn;
	int slab = (n[0] || n[1] || n[2]) && cb->slo <= cb->shi;
	double A = cb->slo - rb, B = cb->shi + rb;
	struct near nb = { { fct_vox_block_of(lo[0]), fct_vox_block_of(lo[1]), fct_vox_block_of(lo[2]) }, { { { 0 } } } };
	for (int32_t z = lo[2]; z <= hi[2]; z++)
		for (int32_t y = lo[1]; y <= hi[1]; y++) {
			int32_t x0 = lo[0], x1 = hi[0];
			if (slab) {
				double r = n[1] * y + n[2] * z;
				if (fabs(n[0]) > 1e-9) {
					double a = (A - r) / n[0], bb = (B - r) / n[0];
					if (a > bb)
						a = bb, bb = (A - r) / n[0];
					if (a > x0)
						x0 = a > x1 + 1 ? x1 + 1 : (int32_t)ceil(a);
					if (bb < x1)
						x1 = bb < x0 - 1 ? x0 - 1 : (int32_t)floor(bb);
				} else if (!(r >= A && r <= B)) {
					continue;
				}
			}
			if (x0 > x1)
				continue;
			int32_t by = fct_vox_block_of(y), bz = fct_vox_block_of(z);
			int ly = y - by * FCT_VOXBLOCK, lz = z - bz * FCT_VOXBLOCK;
			for (int32_t bx = fct_vox_block_of(x0); bx <= fct_vox_block_of(x1); bx++) {
				struct sblock *b = near_block(s, &nb, bx, by, bz, err);
				if (!b)
					return -1;
				int32_t o = bx * FCT_VOXBLOCK;
				int l = x0 > o ? x0 - o : 0, h = x1 < o + FCT_VOXBLOCK - 1 ? x1 - o : FCT_VOXBLOCK - 1;
				b->row[ly + FCT_VOXBLOCK * lz] |= (uint8_t)((0xffu << l) & (0xffu >> (7 - h)));
			}
		}
	return 0;
}

/* True distance: the box of b's fuse_candidates (lo..hi) from its rows, once
 * they are all in (add_rows keeps to the bits: a byte store there had the
 * compiler load everything again for each row). */
static void rows_box(struct sblock *b)
{
	unsigned any = 0;
	for (int z = 0; z < FCT_VOXBLOCK; z++)
		for (int y = 0; y < FCT_VOXBLOCK; y++) {
			unsigned r = b->row[y + FCT_VOXBLOCK * z];
			if (!r)
				continue;
			any |= r;
			b->lo[1] = (int8_t)(y < b->lo[1] ? y : b->lo[1]), b->hi[1] = (int8_t)(y > b->hi[1] ? y : b->hi[1]);
			b->lo[2] = (int8_t)(z < b->lo[2] ? z : b->lo[2]), b->hi[2] = (int8_t)(z > b->hi[2] ? z : b->hi[2]);
		}
	if (any)
		b->lo[0] = (int8_t)__builtin_ctz(any), b->hi[0] = (int8_t)(31 - __builtin_clz(any));
}

/* Triangles at most this many voxels across add the box of their vertices
 * (within a band that is wider anyway); larger ones, points at most half
 * a voxel apart. */
enum { BOX_TRIANGLE = 4 };

/* Boxes of surface points waiting to go into the cell blocks: consecutive
 * boxes over the same blocks make one, as add_span would put their union's
 * box into each of those blocks anyway (clipping to a block's extent
 * commutes with minima and maxima). */
struct pending {
	double lo[3], hi[3];     /* voxel units */
	int32_t clo[3], chi[3];  /* cells of a box of the union */
	int32_t blo[3], bhi[3];  /* and their blocks */
	int any;
};

static int pending_flush(struct cand *c, struct pending *P)
{
	if (!P->any)
		return 0;
	P->any = 0;
	return add_span(c, P->lo, P->hi, P->clo, P->chi);
}

/* Box lo..hi over cells clo..chi, into P.  0 or -1. */
static int pending_add(struct cand *c, struct pending *P, const double lo[3], const double hi[3],
                       const int32_t clo[3], const int32_t chi[3])
{
	int32_t blo[3], bhi[3];
	for (int k = 0; k < 3; k++)
		blo[k] = fct_vox_block_of(clo[k]), bhi[k] = fct_vox_block_of(chi[k]);
	if (P->any && !memcmp(blo, P->blo, sizeof blo) && !memcmp(bhi, P->bhi, sizeof bhi)) {
		box_add(P->lo, P->hi, lo, hi);
		return 0;
	}
	if (pending_flush(c, P))
		return -1;
	memcpy(P->lo, lo, sizeof P->lo), memcpy(P->hi, hi, sizeof P->hi);
	memcpy(P->clo, clo, sizeof P->clo), memcpy(P->chi, chi, sizeof P->chi);
	memcpy(P->blo, blo, sizeof P->blo), memcpy(P->bhi, bhi, sizeof P->bhi);
	P->any = 1;
	return 0;
}

/* A pixel of a depth image in image_cells: its vertex in voxel units,
 * that point's cell and the cell's block (block_key). */
struct pixpoint {
	double s[3];
	int32_t cell[3];
	uint64_t key;
};

/* The box of points p[0..n) into P when it is more than a voxel and at
 * most BOX_TRIANGLE voxels across (the triangle pass's bounds, measured
 * here in voxel units: 1e-6 voxel leaves room for the rounding of the
 * points' scaling, which is far less, so a box is left out only where
 * the triangle pass leaves its triangles out, and kept where it keeps
 * them): 1 when larger (not added), 0 or -1. */
static int corner_box(struct cand *c, struct pending *P, const struct pixpoint *const *p, int n)
{
	double lo[3], hi[3], e = 0;
	int32_t clo[3], chi[3];
	for (int k = 0; k < 3; k++) {
		lo[k] = hi[k] = p[0]->s[k], clo[k] = chi[k] = p[0]->cell[k];
		for (int m = 1; m < n; m++) {
			lo[k] = dmin(p[m]->s[k], lo[k]), hi[k] = dmax(p[m]->s[k], hi[k]);
			clo[k] = p[m]->cell[k] < clo[k] ? p[m]->cell[k] : clo[k];
			chi[k] = p[m]->cell[k] > chi[k] ? p[m]->cell[k] : chi[k];
		}
		e = dmax(hi[k] - lo[k], e);
	}
	if (e < 1 - 1e-6)
		return 0;
	if (e > BOX_TRIANGLE + 1e-6)
		return 1;
	return pending_add(c, P, lo, hi, clo, chi);
}

/* A depth image's pixel has data (fuse.h). */
static inline int has_data(float d)
{
	return d > 0 && d < INFINITY;
}

/* A pinhole view given as a depth image whose mesh is its pixel grid:
 * its pixels with data are the mesh's vertices, in row-major order, and
 * there are as many (fct_depth_mesh_kept makes it so; fuse.h).  Checked
 * vertex by vertex, as image_cells takes each pixel's point from the
 * mesh: it must lie on the pixel's ray at the pixel's depth, within a
 * thousandth of a pixel (as samples_chunk finds a vertex's sample) and
 * a hundred-thousandth of the depth.  Without a division: the camera's
 * x fx is the pixel's (u - cx) z on its ray. */
int fuse_image_grid(const struct fct_fuse_view *v, const struct geo *G)
{
	if (!v->depth || v->cam.kind != FCT_CAMERA_PINHOLE)
		return 0;
	const struct fct_camera *cam = &v->cam;
	double inv[12];
	fct_pose_invert(v->pose, inv);
	size_t w = (size_t)cam->width, h = (size_t)cam->height, k = 0;
	for (size_t y = 0; y < h; y++)
		for (size_t x = 0; x < w; x++) {
			float d = v->depth[y * w + x];
			if (!has_data(d))
				continue;
			if (k == G->nv)
				return 0;
			double c[3];
			fct_pose_apply(inv, &G->xyz[3 * k++], c);
			double tol = 1e-3 * c[2];
			if (!(fabs(c[2] - d) <= 1e-5 * d && fabs(c[0] * cam->fx - ((double)x - cam->cx) * c[2]) <= tol &&
			      fabs(c[1] * cam->fy - ((double)y - cam->cy) * c[2]) <= tol))
				return 0;
		}
	return k == G->nv;
}

/* Projective fuse_candidates of a view given as a depth image (fuse_image_grid), in
 * place of the triangle pass over its mesh: a pass over the image's pixel
 * cells (the square between four pixel centres), each standing for the
 * triangles of the mesh it holds, whichever they are (a triangle joins
 * three corners of one cell).  A cell whose corners with data (three or
 * four) are not all in one block adds the box of those corners, clipped
 * to the blocks they span, when it is more than a voxel and at most
 * BOX_TRIANGLE voxels across; a larger cell adds each three of its corners
 * whose box is so.  A triangle's box is within its cell's box or is one of
 * the threes, over the same blocks or more (and a box within one block
 * along an axis is within that block's extent there), so the fuse_candidates
 * hold the triangle pass's, and the voxels written hold those it would
 * have written (put_depth's test is the voxel's own), but for one kind:
 * the samples the triangle pass takes inside a triangle over BOX_TRIANGLE
 * voxels across.  Such a triangle joins pixels whose points lie more than
 * four voxels apart (a depth jump the mesher bridged, or a surface seen
 * edge-on): its inside is the mesher's interpolation, which no pixel
 * measured; a voxel by it reads its distance from a corner's pixel all
 * the same, and those near the corners stay fuse_candidates through the
 * vertices' boxes (vertex_boxes, as for any mesh).  The gain: each pixel's
 * point is scaled once, not once per triangle corner, and a run of cells
 * over the same blocks goes into them once (on the room at 1 cm about two
 * thirds of the cells cross blocks, the floor lying on a block face, and
 * some 40 thousand add_spans take their 110 thousand boxes).  0 or -1. */
static int image_cells(struct cand *c, const struct fct_fuse_view *v, const struct geo *G)
{
	size_t w = (size_t)v->cam.width, h = (size_t)v->cam.height;
	struct pixpoint *row = fct_alloc_array(w ? 2 * w : 1, sizeof *row, c->err);   /* two rows */
	unsigned char *has = fct_alloc_array(w ? 2 * w : 1, 1, c->err);
	int rc = -1;
	if (!row || !has)
		goto done;
	struct pixpoint *p0 = row, *p1 = row + w;
	unsigned char *h0 = has, *h1 = has + w;
	const double *xyz = G->xyz;
	struct pending P = { .any = 0 };
	for (size_t y = 0; y < h; y++) {
		const float *d = &v->depth[y * w];
		for (size_t x = 0; x < w; x++) {
			h1[x] = has_data(d[x]);
			if (!h1[x])
				continue;
			struct pixpoint *q = &p1[x];
			if (cell_of(c, xyz, q->s, q->cell))
				goto done;
			xyz += 3;   /* the next pixel with data has the next vertex */
			q->key = block_key(fct_vox_block_of(q->cell[0]), fct_vox_block_of(q->cell[1]),
			                   fct_vox_block_of(q->cell[2]));
		}
		for (size_t x = 0; y > 0 && x + 1 < w; x++) {
			if (h0[x] + h0[x + 1] + h1[x] + h1[x + 1] < 3)
				continue;
			const struct pixpoint *q[4];
			int n = 0;
			if (h0[x])
				q[n++] = &p0[x];
			if (h0[x + 1])
				q[n++] = &p0[x + 1];
			if (h1[x])
				q[n++] = &p1[x];
			if (h1[x + 1])
				q[n++] = &p1[x + 1];
			uint64_t k0 = q[0]->key;
			if (q[1]->key == k0 && q[2]->key == k0 && (n == 3 || q[3]->key == k0))
				continue;   /* within one block's vertex box */
			int big = corner_box(c, &P, q, n);
			if (big < 0)
				goto done;
			for (int skip = 0; big && n == 4 && skip < 4; skip++) {
				const struct pixpoint *t[3];
				for (int m = 0, j = 0; m < 4; m++)
					if (m != skip)
						t[j++] = q[m];
				if ((t[1]->key != t[0]->key || t[2]->key != t[0]->key) && corner_box(c, &P, t, 3) < 0)
					goto done;
			}
		}
		struct pixpoint *tp = p0;
		p0 = p1, p1 = tp;
		unsigned char *th = h0;
		h0 = h1, h1 = th;
	}
	rc = pending_flush(c, &P);
done:
	free(row);
	free(has);
	return rc;
}

/* The candidate blocks of G for a band of band metres into s, each with
 * its block of g: created (fresh) when g did not have it, in the order of
 * s.  Projective: the voxels of the box of the surface's cells per block
 * (vertices, triangles over a voxel and across blocks: one within a
 * block adds nothing to its vertices'), grown by ceil(band / vox) and one
 * for the cells' far corners; every voxel in front is written.  True
 * distance: only the voxels within band of a block's box of surface
 * points in every axis and of its slab across the normal (a voxel farther
 * than that from all the points in one direction is farther in space).
 * For that every point of a triangle is in one block's box and slab: a
 * triangle whose vertices are in one block is in that block's; one across
 * blocks is put whole into its first vertex's (which then reaches past
 * the block by a triangle's size at most); a sampled one adds its samples
 * grown by half a voxel (each of its points is that close to a sample in
 * every axis) to their blocks.  img: a projective view given as a depth
 * image whose pixel cells stand for the triangles (image_cells), or NULL. */
int fuse_candidates(struct scratch *s, struct fct_voxgrid *g, const struct geo *G,
                      const struct fct_fuse_view *img, double vox, double band, int proj,
                      struct fct_err *err)
{
	struct cand c = { { 0 }, 1 / vox, err };
	int rc = -1;
	double h = proj ? 0 : 0.5;
	struct sblock **vb = fct_alloc_array(G->nv ? G->nv : 1, sizeof *vb, err);   /* a vertex's block */
	if (!vb)
		return -1;
	if (vertex_boxes(&c, G, vb))
		goto done;
	if (!proj)
		vertex_slabs(&c, G, vb);
	if (img && image_cells(&c, img, G))
		goto done;
	for (size_t t = 0; !img && t < G->nt; t++) {
		const uint32_t *tv = &G->tv[3 * t];
		/* A triangle whose corners are in one block is in that block's
		 * box (and slab) already: its points lie in its corners' box,
		 * and so do its samples, which are kept to it. */
		if (vb[tv[0]] == vb[tv[1]] && vb[tv[0]] == vb[tv[2]])
			continue;
		const double *a = &G->xyz[3 * tv[0]], *b = &G->xyz[3 * tv[1]], *cc = &G->xyz[3 * tv[2]];
		double tlo[3], thi[3], e = 0;   /* the corners' box, its largest side */
		for (int k = 0; k < 3; k++) {
			tlo[k] = dmin3(a[k], b[k], cc[k]), thi[k] = dmax3(a[k], b[k], cc[k]);
			e = dmax(thi[k] - tlo[k], e);
		}
		if (proj && !(e > vox))
			continue;
		if (!proj && e <= BOX_TRIANGLE * vox) {
			/* Into the box of one of its blocks, whole: the box may
			 * reach past the block, a triangle's size at most.  Its
			 * corners in that block are in its box and slab already
			 * (the same products, vertex_boxes and vertex_slabs). */
			struct sblock *b0 = vb[tv[0]];
			const double *v3[3] = { a, b, cc };
			for (int m = 1; m < 3; m++) {
				if (vb[tv[m]] == b0)
					continue;
				double sv[3];
				to_voxels(&c, v3[m], sv);
				box_add(b0->plo, b0->phi, sv, sv);
				slab_extend(b0, sv, sv);
			}
			continue;
		}
		if (e <= BOX_TRIANGLE * vox) {
			double sa[3], sb[3], sc[3], lo[3], hi[3];
			int32_t ia[3], ib[3], ic[3], clo[3], chi[3];
			if (cell_of(&c, a, sa, ia) || cell_of(&c, b, sb, ib) || cell_of(&c, cc, sc, ic))
				goto done;
			for (int k = 0; k < 3; k++) {
				lo[k] = dmin3(sa[k], sb[k], sc[k]), hi[k] = dmax3(sa[k], sb[k], sc[k]);
				clo[k] = ia[k] < ib[k] ? ia[k] : ib[k];
				clo[k] = ic[k] < clo[k] ? ic[k] : clo[k];
				chi[k] = ia[k] > ib[k] ? ia[k] : ib[k];
				chi[k] = ic[k] > chi[k] ? ic[k] : chi[k];
			}
			if (add_span(&c, lo, hi, clo, chi))
				goto done;
			continue;
		}
		double n = ceil(2 * e / vox);
		if (!(n < 1e5)) {
			fct_fail(err, "triangle %zu is %g m across: too large for the voxel size", t, e);
			goto done;
		}
		for (double i = 0; i <= n; i++)
			for (double j = 0; i + j <= n; j++) {
				double p[3];
				for (int k = 0; k < 3; k++)   /* within the corners' box, whatever the rounding */
					p[k] = dmin(dmax(a[k] + (b[k] - a[k]) * (i / n) + (cc[k] - a[k]) * (j / n), tlo[k]), thi[k]);
				if (add_point(&c, p, h))
					goto done;
			}
	}
	/* Projective: r voxels (at most 100); true distance: the kept band
	 * in voxels, a little more for rounding. */
	double r = ceil(band / vox), rb = band_kept(band, vox) / vox;
	r = r < 100 ? r : 100;
	rb = rb < 100 ? rb : 100;
	rb += 1e-6 * (1 + rb);
	for (size_t bi = 0; bi < c.cells.n; bi++) {
		const struct sblock *cb = c.cells.blk[bi];
		int32_t lo[3], hi[3];
		int32_t base[3] = { cb->bx * FCT_VOXBLOCK, cb->by * FCT_VOXBLOCK, cb->bz * FCT_VOXBLOCK };
		for (int k = 0; k < 3; k++) {
			if (proj) {
				/* The cells: a box clipped at the block's far edge
				 * (8 B + 8) ends in cell 8 B + 7. */
				int32_t cl = (int32_t)floor(cb->plo[k]), ch = (int32_t)floor(cb->phi[k]);
				ch = ch < base[k] + FCT_VOXBLOCK - 1 ? ch : base[k] + FCT_VOXBLOCK - 1;
				lo[k] = cl - (int32_t)r;
				hi[k] = ch + 1 + (int32_t)r;
			} else {
				lo[k] = (int32_t)ceil(cb->plo[k] - rb);
				hi[k] = (int32_t)floor(cb->phi[k] + rb);
			}
		}
		if (proj ? add_box(s, lo, hi, err) : add_rows(s, cb, lo, hi, rb, err))
			goto done;
	}
	for (size_t bi = 0; bi < s->n; bi++) {
		struct sblock *b = s->blk[bi];
		if (!proj)
			rows_box(b);
		long gi = fct_voxgrid_index(g, b->bx, b->by, b->bz);
		b->fresh = gi < 0;
		b->vb = gi >= 0 ? fct_voxgrid_at(g, (size_t)gi) : fct_voxgrid_block(g, b->bx, b->by, b->bz, 1, err);
		if (!b->vb)
			goto done;
	}
	rc = 0;
done:
	free(vb);
	fuse_scratch_free(&c.cells);
	return rc;
}

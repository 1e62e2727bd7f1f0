/* voxgrid.c - the sparse block volume: blocks allocated from slabs, found
 * through an open-addressing hash (linear probing, load at most 1/2) whose
 * slots hold the key, so that a lookup touches one cache line before the
 * block itself. */
#include "fusion/voxgrid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Blocks per allocation: a slab fills most of 2 MB, which the kernel may
 * back with one huge page (one fault instead of one per block or two).
 * Measured on a 2-vCPU VM (Linux 6.18, THP "madvise", defrag "madvise"):
 * faulting in 80 MB took 3.5 ms with MADV_HUGEPAGE and 26 ms without;
 * the room's four views at 1 cm took 53 ms per view of one core's CPU
 * time with it, 60 without (projective; 183 and 189 true distance), fresh
 * slabs for every run.  Slow runs came with and without it alike (the
 * worst of 31: 82 ms with, 84 without; a fault that waits for the kernel
 * to compact memory costs 4-5 ms a slab, but the shared machine's load
 * swings more), so the advice stays.  Faulting slabs in ahead
 * (MADV_POPULATE_WRITE) or mapping them without the memset changed
 * nothing measurable: the kernel's clearing of the page is the cost, paid
 * once either way. */
#define SLAB_BLOCKS ((size_t)(SLAB_BYTES / sizeof(struct fct_voxblock)))
#define SLAB_BYTES ((size_t)2 << 20)

struct slot {
	int32_t bx, by, bz;
	uint32_t idx;           /* block index + 1; 0 = empty */
};

struct fct_voxgrid {
	double voxel;
	int colour;
	size_t limit;           /* bytes, 0 = none */

	size_t n;               /* blocks */
	struct fct_voxblock **blocks;   /* creation order */
	size_t blocks_cap;
	size_t used;            /* slab places handed out (blocks and spares) */
	struct fct_voxblock *spare;     /* dropped blocks, zeroed, for reuse: a list
	                                 * linked through the first bytes of sdf */

	struct fct_voxblock **slabs;    /* SLAB_BLOCKS blocks each */
	float **rgb_slabs;              /* 3 * 512 * SLAB_BLOCKS floats each, with colour */
	size_t nslabs, slabs_cap, rgb_cap;

	struct slot *hash;
	size_t hcap;            /* power of two */
};

/* A zeroed slab of SLAB_BLOCKS blocks (huge pages where there are);
 * NULL when out of memory.  Freed with free(). */
static struct fct_voxblock *slab_alloc(void)
{
	void *p = fct_alloc_big(1, SLAB_BYTES, NULL);
	if (p)
		memset(p, 0, SLAB_BLOCKS * sizeof(struct fct_voxblock));
	return p;
}

static inline size_t hash_key(int32_t bx, int32_t by, int32_t bz)
{
	uint64_t h = (uint64_t)(uint32_t)bx * 0x9E3779B97F4A7C15u;
	h ^= (uint64_t)(uint32_t)by * 0xC2B2AE3D27D4EB4Fu;
	h ^= (uint64_t)(uint32_t)bz * 0x165667B19E3779F9u;
	h ^= h >> 29;
	return (size_t)h;
}

struct fct_voxgrid *fct_voxgrid_new(double voxel_size, int with_colour, struct fct_err *err)
{
	if (!(voxel_size > 0) || !isfinite(voxel_size)) {
		fct_fail(err, "voxel size %g is not a positive number", voxel_size);
		return NULL;
	}
	struct fct_voxgrid *g = calloc(1, sizeof *g);
	if (!g) {
		fct_fail(err, "out of memory");
		return NULL;
	}
	g->voxel = voxel_size;
	g->colour = with_colour != 0;
	g->hcap = 64;
	g->hash = calloc(g->hcap, sizeof *g->hash);
	if (!g->hash) {
		free(g);
		fct_fail(err, "out of memory");
		return NULL;
	}
	return g;
}

void fct_voxgrid_free(struct fct_voxgrid *g)
{
	if (!g)
		return;
	for (size_t s = 0; s < g->nslabs; s++) {
		free(g->slabs[s]);
		if (g->colour)
			free(g->rgb_slabs[s]);
	}
	free(g->slabs);
	free(g->rgb_slabs);
	free(g->blocks);
	free(g->hash);
	free(g);
}

double fct_voxgrid_voxel(const struct fct_voxgrid *g)
{
	return g->voxel;
}

int fct_voxgrid_has_colour(const struct fct_voxgrid *g)
{
	return g->colour;
}

size_t fct_voxgrid_count(const struct fct_voxgrid *g)
{
	return g->n;
}

struct fct_voxblock *fct_voxgrid_at(const struct fct_voxgrid *g, size_t i)
{
	return i < g->n ? g->blocks[i] : NULL;
}

size_t fct_voxgrid_block_bytes(int with_colour)
{
	/* the block, its share of a hash at load 1/4..1/2 (say 3 slots), its
	 * pointer in the creation-order array (amortised doubling: 2) */
	return sizeof(struct fct_voxblock) + 3 * sizeof(struct slot) + 2 * sizeof(void *) +
	       (with_colour ? 3 * FCT_VOXBLOCK_N * sizeof(float) : 0);
}

/* Bytes held for nslabs slabs, a blocks array of bcap and a hash of hcap. */
static size_t bytes_for(const struct fct_voxgrid *g, size_t nslabs, size_t bcap, size_t hcap)
{
	size_t slab = SLAB_BLOCKS * (sizeof(struct fct_voxblock) +
	                             (g->colour ? 3 * FCT_VOXBLOCK_N * sizeof(float) : 0));
	return nslabs * slab + bcap * sizeof(void *) + hcap * sizeof(struct slot) +
	       sizeof *g;
}

size_t fct_voxgrid_bytes(const struct fct_voxgrid *g)
{
	return bytes_for(g, g->nslabs, g->blocks_cap, g->hcap);
}

void fct_voxgrid_set_limit(struct fct_voxgrid *g, size_t max_bytes)
{
	g->limit = max_bytes;
}

/* Slot of key, or the empty slot where it would go. */
static inline struct slot *probe(const struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz)
{
	size_t mask = g->hcap - 1, h = hash_key(bx, by, bz) & mask;
	for (;;) {
		struct slot *s = &g->hash[h];
		if (!s->idx || (s->bx == bx && s->by == by && s->bz == bz))
			return s;
		h = (h + 1) & mask;
	}
}

static int rehash(struct fct_voxgrid *g, size_t ncap, struct fct_err *err)
{
	struct slot *nh = fct_alloc_array(ncap, sizeof *nh, err);
	if (!nh)
		return -1;
	memset(nh, 0, ncap * sizeof *nh);
	struct slot *old = g->hash;
	size_t ocap = g->hcap;
	g->hash = nh;
	g->hcap = ncap;
	for (size_t i = 0; i < ocap; i++)
		if (old[i].idx)
			*probe(g, old[i].bx, old[i].by, old[i].bz) = old[i];
	free(old);
	return 0;
}

static int over_limit(const struct fct_voxgrid *g, size_t nslabs, size_t bcap, size_t hcap,
                      struct fct_err *err)
{
	if (!g->limit)
		return 0;
	size_t need = bytes_for(g, nslabs, bcap, hcap);
	if (need <= g->limit)
		return 0;
	return fct_fail(err, "voxel grid: %zu blocks of %g-unit voxels need %.1f MB, over the limit of %.1f MB",
	                g->n + 1, g->voxel, need / 1e6, g->limit / 1e6);
}

static struct fct_voxblock *create(struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz,
                                   struct fct_err *err)
{
	if (g->n >= UINT32_MAX - 1) {
		fct_fail(err, "voxel grid: too many blocks");
		return NULL;
	}
	/* capacities after this insertion, checked against the limit first */
	size_t hcap = g->hcap;
	while (2 * (g->n + 1) > hcap)
		hcap *= 2;
	size_t place = g->spare ? 0 : g->used + 1;   /* slab places needed */
	size_t nslabs = (place + SLAB_BLOCKS - 1) / SLAB_BLOCKS;
	nslabs = nslabs > g->nslabs ? nslabs : g->nslabs;
	size_t bcap = g->blocks_cap;
	if (g->n + 1 > bcap)
		bcap = bcap ? 2 * bcap : 64;
	if (over_limit(g, nslabs, bcap, hcap, err))
		return NULL;
	if (hcap != g->hcap && rehash(g, hcap, err))
		return NULL;
	if (fct_grow((void **)&g->blocks, &g->blocks_cap, g->n + 1, sizeof *g->blocks, err))
		return NULL;
	if (nslabs > g->nslabs) {
		size_t rc = g->rgb_cap;
		if (fct_grow((void **)&g->slabs, &g->slabs_cap, nslabs, sizeof *g->slabs, err) ||
		    (g->colour && fct_grow((void **)&g->rgb_slabs, &rc, nslabs, sizeof *g->rgb_slabs, err)))
			return NULL;
		g->rgb_cap = rc;
		struct fct_voxblock *slab = slab_alloc();
		float *rgb = NULL;
		if (slab && g->colour)
			rgb = calloc((size_t)SLAB_BLOCKS * 3 * FCT_VOXBLOCK_N, sizeof *rgb);
		if (!slab || (g->colour && !rgb)) {
			free(slab);
			fct_fail(err, "voxel grid: out of memory at %zu blocks (%.1f MB)", g->n,
			         fct_voxgrid_bytes(g) / 1e6);
			return NULL;
		}
		g->slabs[g->nslabs] = slab;
		if (g->colour)
			g->rgb_slabs[g->nslabs] = rgb;
		g->nslabs++;
	}
	struct fct_voxblock *b = g->spare;
	if (b) {
		memcpy(&g->spare, b->sdf, sizeof g->spare);
		memset(b->sdf, 0, sizeof g->spare);
	} else {
		size_t s = g->used / SLAB_BLOCKS, k = g->used % SLAB_BLOCKS;
		b = &g->slabs[s][k];
		b->rgb = g->colour ? g->rgb_slabs[s] + k * 3 * FCT_VOXBLOCK_N : NULL;
		g->used++;
	}
	b->bx = bx, b->by = by, b->bz = bz;
	g->blocks[g->n] = b;
	struct slot *sl = probe(g, bx, by, bz);
	sl->bx = bx, sl->by = by, sl->bz = bz;
	sl->idx = (uint32_t)(g->n + 1);
	g->n++;
	return b;
}

/* Empty slot h, closing the gap by moving later entries of its probe run
 * back (deletion under linear probing). */
static void unslot(struct fct_voxgrid *g, size_t h)
{
	size_t mask = g->hcap - 1;
	for (size_t j = h;;) {
		j = (j + 1) & mask;
		struct slot *s = &g->hash[j];
		if (!s->idx)
			break;
		size_t home = hash_key(s->bx, s->by, s->bz) & mask;
		/* The entry at j may fill the gap at h unless its home lies
		 * cyclically in (h, j]. */
		if (h <= j ? (home > h && home <= j) : (home > h || home <= j))
			continue;
		g->hash[h] = *s;
		h = j;
	}
	g->hash[h].idx = 0;
}

void fct_voxgrid_drop(struct fct_voxgrid *g, size_t from, const unsigned char *keep)
{
	size_t j = from;
	for (size_t i = from; i < g->n; i++) {
		struct fct_voxblock *b = g->blocks[i];
		struct slot *s = probe(g, b->bx, b->by, b->bz);
		if (keep && keep[i - from]) {
			s->idx = (uint32_t)(j + 1);
			g->blocks[j++] = b;
			continue;
		}
		unslot(g, (size_t)(s - g->hash));
		memset(b->sdf, 0, sizeof b->sdf);
		memset(b->weight, 0, sizeof b->weight);
		if (b->rgb)
			memset(b->rgb, 0, 3 * FCT_VOXBLOCK_N * sizeof *b->rgb);
		memcpy(b->sdf, &g->spare, sizeof g->spare);
		g->spare = b;
	}
	g->n = j;
}

struct fct_voxblock *fct_voxgrid_block(struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz,
                                       int create_it, struct fct_err *err)
{
	struct slot *s = probe(g, bx, by, bz);
	if (s->idx)
		return g->blocks[s->idx - 1];
	return create_it ? create(g, bx, by, bz, err) : NULL;
}

long fct_voxgrid_index(const struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz)
{
	return (long)probe(g, bx, by, bz)->idx - 1;
}

struct fct_voxblock *fct_voxgrid_voxel_at(struct fct_voxgrid *g, int32_t i, int32_t j, int32_t k,
                                          int create_it, int *local, struct fct_err *err)
{
	int32_t bx = fct_vox_block_of(i), by = fct_vox_block_of(j), bz = fct_vox_block_of(k);
	*local = (int)(i - 8 * bx) + 8 * ((int)(j - 8 * by) + 8 * (int)(k - 8 * bz));
	return fct_voxgrid_block(g, bx, by, bz, create_it, err);
}

int fct_voxgrid_get(const struct fct_voxgrid *g, int32_t i, int32_t j, int32_t k,
                    float *sdf, float *weight)
{
	int local;
	struct fct_voxblock *b = fct_voxgrid_voxel_at((struct fct_voxgrid *)g, i, j, k, 0, &local, NULL);
	if (!b) {
		*sdf = *weight = 0;
		return 0;
	}
	*sdf = b->sdf[local];
	*weight = b->weight[local];
	return 1;
}

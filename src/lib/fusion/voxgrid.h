/* voxgrid.h - a sparse volume of signed distances: 8x8x8 voxel blocks in a
 * hash, allocated only where something is written, so that memory follows
 * the surface rather than the bounding box (the volume of Sun et al. Sec. 3,
 * stored the way VDB-style fusion stores it).
 *
 * The lattice.  Voxel (i, j, k), with 32-bit signed global indices, is the
 * sample at the world point (i, j, k) * voxel_size: samples sit on the
 * lattice, there is no origin and no half-voxel offset.  Two grids with the
 * same voxel size therefore share their lattice, whatever region each one
 * covers, which is what lets --bbox tiles be fused independently and joined
 * (see mcubes.h).  Voxel (i, j, k) lives in block (floor(i/8), floor(j/8),
 * floor(k/8)) at local index x + 8*(y + 8*z), x = i - 8*floor(i/8), ...
 *
 * Voxel contents.  sdf is the signed distance in world units (metres),
 * positive in free space, negative behind the surface; weight is its
 * accumulated confidence, 0 meaning never observed (marching cubes ignores
 * such voxels).  When the grid has colour, rgb holds 3 floats per voxel,
 * the weighted AVERAGE colour in 0..255 (same averaging as sdf; r, g, b of
 * voxel v at rgb[3v], rgb[3v+1], rgb[3v+2]).  A new block has sdf = 0,
 * weight = 0, rgb = 0 everywhere.
 *
 * Order.  Blocks are numbered in the order they were created
 * (fct_voxgrid_at), never in hash order, so everything computed by walking
 * the blocks is deterministic for a deterministic sequence of writes.
 *
 * Threads.  Lookups with create == 0 only read and may run concurrently;
 * creating blocks must not overlap any other call on the same grid.  Writing
 * voxel values of distinct blocks from different threads is fine.
 *
 * Memory.  A block costs fct_voxgrid_block_bytes() (about 4.1 KB without
 * colour, 10.3 KB with it, hash slots included); fct_voxgrid_set_limit caps
 * the total so that block creation fails with a message giving the figure
 * instead of exhausting the machine. */
#ifndef FCT_VOXGRID_H
#define FCT_VOXGRID_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"

#define FCT_VOXBLOCK 8                      /* voxels per block side */
#define FCT_VOXBLOCK_N 512                  /* voxels per block */

struct fct_voxblock {
	int32_t bx, by, bz;                 /* block coordinates */
	float sdf[FCT_VOXBLOCK_N];          /* index x + 8*(y + 8*z) */
	float weight[FCT_VOXBLOCK_N];       /* 0 = unobserved */
	float *rgb;                         /* 3 * 512 average colour, or NULL without colour */
};

struct fct_voxgrid;

/* A new empty grid of voxel_size world units per voxel (finite, > 0), with
 * colour or not.  NULL on bad size or out of memory (err set).  No limit on
 * memory until fct_voxgrid_set_limit. */
struct fct_voxgrid *fct_voxgrid_new(double voxel_size, int with_colour, struct fct_err *err);
/* Free the grid and all its blocks; g may be NULL. */
void fct_voxgrid_free(struct fct_voxgrid *g);

double fct_voxgrid_voxel(const struct fct_voxgrid *g);
int fct_voxgrid_has_colour(const struct fct_voxgrid *g);

/* The block at block coordinates (bx, by, bz).  When absent: NULL if
 * create == 0 (err untouched), else a new zeroed block appended to the
 * creation order; NULL with err set when the memory limit or the machine
 * refuses it.  The pointer stays valid until fct_voxgrid_free. */
struct fct_voxblock *fct_voxgrid_block(struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz,
                                       int create, struct fct_err *err);

/* Remove the blocks from .. count-1 whose keep[i - from] is 0 (all of them
 * when keep is NULL), the others
 * keeping their order (and moving down over the gaps: block indices from
 * `from` on change).  The storage of a removed block is zeroed and goes to
 * the next blocks created, so that a caller may create the blocks it might
 * write, write them in place, and drop those it did not write at the cost
 * of neither a copy nor fresh memory. */
void fct_voxgrid_drop(struct fct_voxgrid *g, size_t from, const unsigned char *keep);

/* Number of blocks, and the i-th block in creation order (i < count). */
size_t fct_voxgrid_count(const struct fct_voxgrid *g);
struct fct_voxblock *fct_voxgrid_at(const struct fct_voxgrid *g, size_t i);

/* Creation index of block (bx, by, bz), or -1 when absent (a read-only
 * lookup; fct_voxgrid_at(g, index) is the block). */
long fct_voxgrid_index(const struct fct_voxgrid *g, int32_t bx, int32_t by, int32_t bz);

/* Bytes one block costs, hash slots and the block-pointer array included
 * (an estimate for refusing before allocating: n blocks cost about
 * n * fct_voxgrid_block_bytes(c)). */
size_t fct_voxgrid_block_bytes(int with_colour);
/* Bytes the grid holds now (blocks, slabs, hash). */
size_t fct_voxgrid_bytes(const struct fct_voxgrid *g);
/* Refuse to grow beyond max_bytes (0 = no limit). */
void fct_voxgrid_set_limit(struct fct_voxgrid *g, size_t max_bytes);

/* Voxel helpers ----------------------------------------------------------- */

/* floor(i / 8) for any int32 (well defined for negatives). */
static inline int32_t fct_vox_block_of(int32_t i)
{
	return i >= 0 ? i / FCT_VOXBLOCK : ~(~i / FCT_VOXBLOCK);
}
/* i - 8 * floor(i / 8), in 0..7. */
static inline int fct_vox_local_of(int32_t i)
{
	return (int)(i - FCT_VOXBLOCK * fct_vox_block_of(i));
}

/* The voxel (i, j, k): its block (created when create != 0) and its local
 * index in *local.  NULL as fct_voxgrid_block. */
struct fct_voxblock *fct_voxgrid_voxel_at(struct fct_voxgrid *g, int32_t i, int32_t j, int32_t k,
                                          int create, int *local, struct fct_err *err);

/* Read voxel (i, j, k): 1 and *sdf, *weight when its block exists (weight
 * may still be 0), 0 (and sdf = weight = 0) when it does not. */
int fct_voxgrid_get(const struct fct_voxgrid *g, int32_t i, int32_t j, int32_t k,
                    float *sdf, float *weight);

#endif

/* fusepriv.h - what the fusion files share: fuse.c (one view's fusion
 * and its triangles), fuseraster.c (its raster and range image),
 * fusecand.c (its candidate voxels), fusetrue.c (true signed distance),
 * fuseplane.c (true distance by a depth image's planes) and fuseproj.c
 * (projective distance); the lookups their voxel loops
 * make are inline here.  Not for other callers: the interface is fuse.h. */
#ifndef FCT_FUSEPRIV_H
#define FCT_FUSEPRIV_H

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <string.h>

#include "fusion/fuse.h"

/* Minima and maxima as comparisons, without a libm call: b unless a is
 * strictly smaller (larger), so equal operands and a NaN give b. */
static inline double dmin(double a, double b)
{
	return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
	return a > b ? a : b;
}

static inline double dmin3(double a, double b, double c)
{
	return dmin(dmin(a, b), c);
}

static inline double dmax3(double a, double b, double c)
{
	return dmax(dmax(a, b), c);
}

/* The box pl..ph (a point: pl = ph) into the box lo..hi. */
static inline void box_add(double lo[3], double hi[3], const double pl[3], const double ph[3])
{
	lo[0] = dmin(pl[0], lo[0]), lo[1] = dmin(pl[1], lo[1]), lo[2] = dmin(pl[2], lo[2]);
	hi[0] = dmax(ph[0], hi[0]), hi[1] = dmax(ph[1], hi[1]), hi[2] = dmax(ph[2], hi[2]);
}

/* Per-view scratch: a hash of 8^3 blocks, the candidate voxels of a view
 * (lo..hi, local coordinates) and their results. */
struct sblock {
	int32_t bx, by, bz;
	int8_t lo[3], hi[3];     /* box of voxels that may be in the band (lo > hi: none) */
	size_t nvox, nborder;    /* voxels with a value, voxels skipped on a border */
	struct fct_voxblock *vb; /* the volume's block, updated in place (each block is one thread's) */
	int fresh;               /* vb was created for this view: dropped again if nothing is put */
	double plo[3], phi[3];   /* fuse_candidates' surface blocks: box of their points, voxel units */
	double sn[3], slo, shi;  /* and the slab of their points: sn . p in [slo, shi] (sn 0: none) */
	uint8_t row[FCT_VOXBLOCK * FCT_VOXBLOCK];   /* true distance: the fuse_candidates of row y + 8 z,
	                                              * bit x */
};

/* Voxel l of vb gets distance d with weight w: the weighted average.  A
 * fresh block holds 0 with weight 0 and each voxel is put once per view, so
 * the average is 0 + d (d w / w is exact in double); a weight that is
 * not positive leaves such a voxel unobserved. */
static inline void put_value(struct fct_voxblock *vb, int fresh, int l, float d, float w)
{
	if (fresh && w < INFINITY) {
		if (w > 0)
			vb->sdf[l] = d + 0.0f, vb->weight[l] = w;   /* + 0: as 0 + d, -0 is 0 */
		return;
	}
	double W = (double)vb->weight[l] + w;
	vb->sdf[l] = (float)(vb->sdf[l] + ((double)d - vb->sdf[l]) * w / W);
	vb->weight[l] = (float)W;
}

/* put_value into voxel l of b's block, counted. */
static inline void put(struct sblock *b, int l, float d, float w)
{
	b->nvox++;
	put_value(b->vb, b->fresh, l, d, w);
}

struct scratch {
	uint64_t *keys;          /* UINT64_MAX: empty slot */
	uint32_t *slot;          /* block index of a key */
	size_t cap, n;           /* hash capacity (power of two), blocks */
	struct sblock **blk;
	size_t blkcap;
	struct sblock *last;     /* the block found last (most lookups repeat it) */
	struct sblock *recent[16];   /* and blocks found lately, by recent_slot */
};

/* A range image's mesh in its own camera: every vertex on a pixel centre
 * and every triangle half of a pixel cell (the square between four pixel
 * centres), at most one on each half.  Such a mesh needs no raster: the
 * triangle under an image point is read off its cell, and the triangles
 * around a vertex are in the four cells around its pixel. */
struct pixgrid {
	int32_t *cell;           /* 2 per cell (x, y) at x + y w: the halves; -1: none */
	uint8_t *diag;           /* per cell: DIAG_DOWN or DIAG_UP, the diagonal that splits it */
	const int32_t *at;       /* per vertex: its pixel x, y (-1: none) */
	size_t w, h;             /* pixels; cells (x, y) for x < w - 1, y < h - 1 */
	double xend, yend;       /* w - 1 and h - 1: the cells' extent, for the lookups */
};

enum { DIAG_NONE, DIAG_DOWN, DIAG_UP };   /* DOWN: corners (0, 0)-(1, 1); UP: (1, 0)-(0, 1) */

struct geo {
	size_t nt, nv;
	const double *xyz;
	const uint32_t *tv;      /* 3 per triangle */
	uint32_t *tvown;
	float *tn;               /* unit normal n and n . a, 4 per triangle; NaN: degenerate
	                          * (float: half the memory the search has to bring in);
	                          * NULL: not made (a depth image fused by its planes) */
	uint32_t *vfs, *vf;      /* faces of vertex v: vf[vfs[v] .. vfs[v + 1]), in face order */
	const struct pixgrid *grid;   /* instead of vfs and vf when the mesh is a grid */
	const struct fct_mesh *m;    /* the triangles as a mesh: the input or tris */
	struct fct_mesh tris;    /* the triangulated mesh when the input has polygons */
	atomic_size_t nproper;   /* triangles with a normal */
	double nondegen;         /* a cross product squared above it: not degenerate */
	int own;
};

static inline int in_clip(const struct fct_fuse_params *p, int32_t i, int32_t j, int32_t k)
{
	return !p->has_clip || (i >= p->clip_lo[0] && i <= p->clip_hi[0] && j >= p->clip_lo[1] &&
	                        j <= p->clip_hi[1] && k >= p->clip_lo[2] && k <= p->clip_hi[2]);
}

/* A view's raster of triangle ids: the triangle seen at each sample of the
 * sensor image, S samples per sensor pixel, nearest first (ties: the lower
 * triangle).  Sample (x, y) is sensor pixel (u0 + x / S, v0 + y / S). */
struct raster {
	const struct fct_fuse_view *v;
	double inv[12];          /* world-to-sensor */
	double S, u0, v0;
	int w, h;
	float *z;                /* depth; INFINITY: nothing */
	const float *depth;      /* what projective fusion reads: z, or the view's depth
	                          * image (fuse_raster_image; nothing where not > 0) */
	int32_t *id;             /* -1: nothing; only with proper (the searches start from
	                          * the triangles; projective fusion and range images
	                          * need the depths alone) */
	float *zf;               /* true distance: the farthest triangle too */
	int32_t *idf;
	double *sp;              /* per vertex: sample x, y, depth (1/depth for pinholes);
	                          * sensor u, v, depth until the raster's extent is known */
	int32_t *at;             /* one sample per pixel or fewer: per vertex, x and y of the
	                          * sample it lies on (within 1e-3), or -1 and -1 */
	float *zv;               /* and the depth a triangle gives there */
	uint32_t *gen;           /* with at: the triangles that are not grid triangles */
	size_t ngen, gencap;
	struct pixgrid grid;     /* instead of z, id, zf and idf when grid.cell is set */
	const struct geo *G;
	int proper;              /* only triangles with a normal */
	int nthreads;
};

/* Sensor pixel (u, v) and depth of world point p; 0 when it has none. */
static inline int sensor_project(const struct raster *R, const double p[3], double *u, double *v,
                                 double *depth)
{
	const double *M = R->inv;
	double c[3] = { M[0] * p[0] + M[1] * p[1] + M[2] * p[2] + M[3],
	                M[4] * p[0] + M[5] * p[1] + M[6] * p[2] + M[7],
	                M[8] * p[0] + M[9] * p[1] + M[10] * p[2] + M[11] };
	const struct fct_camera *cam = &R->v->cam;
	if (cam->kind == FCT_CAMERA_PINHOLE) {
		if (!(c[2] > 0))
			return 0;
		*u = cam->fx * c[0] / c[2] + cam->cx;
		*v = cam->fy * c[1] / c[2] + cam->cy;
		*depth = c[2];
		return 1;
	}
	if (cam->kind == FCT_CAMERA_NONE) {
		*u = c[0] / R->v->ortho_step;
		*v = c[1] / R->v->ortho_step;
		*depth = -c[2];
		return 1;
	}
	return fct_camera_project(cam, c, u, v, depth);
}

/* Sample coordinates of p (continuous) and its depth; 0 when none. */
static inline int sample_of(const struct raster *R, const double p[3], double *x, double *y,
                            double *depth)
{
	double u, v;
	if (!sensor_project(R, p, &u, &v, depth))
		return 0;
	*x = (u - R->u0) * R->S;
	*y = (v - R->v0) * R->S;
	return 1;
}

/* The sample nearest (x, y), or -1 outside. */
static inline long sample_index(const struct raster *R, double x, double y)
{
	if (!(x > -0.5 && y > -0.5 && x < R->w - 0.5 && y < R->h - 0.5))
		return -1;
	return (long)(y + 0.5) * R->w + (long)(x + 0.5);
}

/* The corners of a pixel cell that triangle tv takes, as bits x + 2 y of
 * the cell (cx, cy) (at: per vertex, its sample's x and y, or -1), when its
 * vertices lie on three distinct corners of one cell: 7, 11, 13 or 14.
 * 0 when they do not (a vertex off the samples, a triangle larger than a
 * cell or degenerate in the image).  Tested without branches, as the
 * diagonals of a range image follow its data. */
static inline unsigned cell_corners(const int32_t *at, const uint32_t tv[3], int32_t *cx, int32_t *cy)
{
	const int32_t *a = &at[2 * tv[0]], *b = &at[2 * tv[1]], *d = &at[2 * tv[2]];
	if ((a[0] | b[0] | d[0]) < 0)
		return 0;
	int32_t x = a[0] < b[0] ? a[0] : b[0], y = a[1] < b[1] ? a[1] : b[1];
	x = d[0] < x ? d[0] : x, y = d[1] < y ? d[1] : y;
	int32_t ax = a[0] - x, ay = a[1] - y, bx = b[0] - x, by = b[1] - y, dx = d[0] - x, dy = d[1] - y;
	if ((ax | ay | bx | by | dx | dy) > 1)
		return 0;   /* not within one cell */
	unsigned corners = 1u << (ax + 2 * ay) | 1u << (bx + 2 * by) | 1u << (dx + 2 * dy);
	*cx = x, *cy = y;
	return 0x6880u >> corners & 1 ? corners : 0;
}

/* The cell of the grid under sample point (x, y), or -1. */
static inline long grid_cell_at(const struct pixgrid *P, double x, double y)
{
	if (!(x >= 0 && y >= 0 && x < P->xend && y < P->yend))
		return -1;
	return (long)y * (long)P->w + (long)x;
}

/* The triangle of the grid under sample point (x, y), or -1.  The half is
 * chosen without a branch: the diagonals and the points' sides of them
 * come in no order a branch could guess (a quarter of the mispredicted
 * branches of a view's fusion, by cachegrind). */
static inline int32_t grid_seen(const struct pixgrid *P, double x, double y)
{
	long c = grid_cell_at(P, x, y);
	if (c < 0)
		return -1;
	double fx = x - (double)(long)x, fy = y - (double)(long)y;
	int up = P->diag[c] == DIAG_UP;
	int half = (up & (fx + fy > 1)) | (!up & (fy > fx));
	return P->cell[2 * c + half];
}

/* Ask for the memory that tells the triangle seen at sample point (x, y). */
static inline void prefetch_seen(const struct raster *R, double x, double y)
{
	if (R->grid.cell) {
		long c = grid_cell_at(&R->grid, x, y);
		if (c >= 0) {
			__builtin_prefetch(&R->grid.cell[2 * c]);
			__builtin_prefetch(&R->grid.diag[c]);
		}
		return;
	}
	long si = sample_index(R, x, y);
	if (si >= 0) {
		__builtin_prefetch(&R->id[si]);
		__builtin_prefetch(&R->idf[si]);
	}
}

/* The triangle seen at sample point (x, y) in layer id (the grid's, when
 * there is one), or -1. */
static inline int32_t seen(const struct raster *R, const int32_t *id, double x, double y)
{
	if (R->grid.cell)
		return grid_seen(&R->grid, x, y);
	long i = sample_index(R, x, y);
	return i >= 0 ? id[i] : -1;
}

/* The band that true distance keeps: a thousandth of a voxel over the
 * band, so that a layer of voxels at the band's distance (a wall on a
 * voxel plane, as the floor at z = 0) is kept whole rather than half, as
 * the rounding of float depths and planes would fall. */
static inline double band_kept(double band, double vox)
{
	return band + 1e-3 * vox;
}

/* A depth image's view: per sample of its grid the tangent plane of the
 * vertex there (fuseplane.c). */
struct plane {
	float n[3], off;         /* unit normal n and n . p, p the vertex; n[0] NaN: no vertex */
	float depth;             /* p's depth in the sensor */
	float weight;            /* of a distance to it (the view's at p, by its sigma with a
	                          * noise model); -1: p is on the data's border */
};

struct planes {
	struct plane *pl;        /* sample (x, y) at x + y w */
	size_t w, h;
	/* Floats, as the voxels' arithmetic (fuseplane.c). */
	float reach;             /* a foot's depth may differ from its sample's by this
	                          * times that depth (and by a voxel) */
	float ax, bx, ay, by;    /* x = ax c0 / c2 + bx of camera point c, likewise y: its
	                          * sample's coordinates from the corner of sample 0
	                          * (from its centre minus a half) */
};

/* Fusion of one view, block by block on the threads. */
struct fctx {
	const struct geo *G;
	const struct raster *R;
	const struct fct_fuse_view *v;
	const struct fct_fuse_params *p;
	const struct scratch *s;
	double vox;
	double band;             /* band_kept */
	const struct planes *T;  /* a depth image's planes (NULL: search the mesh) */
};

/* The weight of a distance whose nearest point q has normal n, seen by v
 * (p->weight). */
double fuse_view_weight(const struct fct_fuse_view *v, const struct fct_fuse_params *p,
                        const double q[3], const double n[3]);

/* The view's noise at a point of sigma metres as a weight: 1 / (1 +
 * (2 sigma / voxel)^2), the inverse of the sensor's variance plus
 * (voxel / 2)^2 (what the volume resolves anyway) over the latter: 1 for
 * data far more precise than the voxels, falling as 1 / sigma^2 for
 * noisier data (fuse.h). */
static inline double sigma_weight(double sigma, double vox)
{
	double r = 2 * sigma / vox;
	return 1 / (1 + r * r);
}

/* fuse.c: the view's triangles (polygons fan-triangulated), with topo
 * their unit normals too (fuse_geo_normals, also later); freed by
 * fuse_geo_free.  0 or -1. */
int fuse_geo_build(struct geo *G, const struct fct_mesh *m, int topo, int nthreads,
                   struct fct_err *err);
int fuse_geo_normals(struct geo *G, int nthreads, struct fct_err *err);
void fuse_geo_free(struct geo *G);

/* fuseraster.c: the raster of G seen by v with S samples per sensor pixel
 * (fewer when more than max_samples would be needed); for true distance
 * the pixel grid of a range image's mesh instead when it is one (else the
 * raster, with G's normals made first when it has none); for a view
 * given as a depth image, the image itself.  0 or -1. */
int fuse_raster_build(struct raster *R, const struct fct_fuse_view *v, const struct geo *G,
                      double S, int proper, size_t max_samples, int nthreads, struct fct_err *err);
int fuse_raster_true(struct raster *R, const struct fct_fuse_view *v, struct geo *G,
                     size_t max_samples, int nthreads, struct fct_err *err);
int fuse_raster_image(struct raster *R, const struct fct_fuse_view *v, struct fct_err *err);
void fuse_raster_free(struct raster *R);

/* fusecand.c: the candidate blocks of a view (fuse_candidates, each with
 * its block of g), whether a view given as a depth image has its pixel
 * grid for a mesh (fuse_image_grid), and the scratch's release. */
int fuse_candidates(struct scratch *s, struct fct_voxgrid *g, const struct geo *G,
                    const struct fct_fuse_view *img, double vox, double band, int proj,
                    struct fct_err *err);
int fuse_image_grid(const struct fct_fuse_view *v, const struct geo *G);
void fuse_scratch_free(struct scratch *s);

/* fusetrue.c and fuseproj.c: blocks lo..hi of F->s (F a struct fctx),
 * for fct_par_run: the true signed distance of their candidates, or the
 * projective depth difference. */
void fuse_true_blocks(void *ctx, size_t lo, size_t hi, int worker);

void fuse_projective_blocks(void *ctx, size_t lo, size_t hi, int worker);

/* fuseplane.c: the planes of a depth image's view whose mesh is R's grid
 * (fuse_planes_build, vox the voxel size; 0 or -1), and blocks lo..hi of
 * F->s by them (fuse_plane_blocks, for fct_par_run). */
int fuse_planes_build(struct planes *T, const struct raster *R, const struct fct_fuse_view *v,
                      const struct fct_fuse_params *p, double vox, struct fct_err *err);
void fuse_planes_free(struct planes *T);
void fuse_plane_blocks(void *ctx, size_t lo, size_t hi, int worker);

#endif

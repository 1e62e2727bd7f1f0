/* carve.c - space carving after fusion: Sun, Paik, Koschan and Abidi,
 * sec. 3.  A voxel that no view observed (weight 0) but some view saw
 * through (its depth below the range its pixel holds) is empty; the
 * boundary between empty and never-seen space closes the occlusion holes
 * (see fct_carve in fuse.h).  The box's states are bitsets: observed (K),
 * carved (C), searched by the bubble search (V). */
#include "fusion/fuse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t fct_carve_bytes(const int32_t lo[3], const int32_t hi[3])
{
	double words = ceil((hi[0] - (double)lo[0] + 1) / 64) * (hi[1] - (double)lo[1] + 1) *
	               (hi[2] - (double)lo[2] + 1);
	double bytes = 3 * 8 * words;   /* observed, carved, visited by the bubble search */
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

static inline int bit_get(const uint64_t *b, size_t v)
{
	return (int)(b[v / 64] >> (v % 64) & 1);
}

/* The reach of a bubble: unknown voxels within BUBBLE_REACH voxels (each
 * axis) of where the search began.  Tiles carve boxes that reach 3 voxels
 * plus the band beyond their own box, so a bubble this small that touches a
 * tile is seen whole by it, and tiles and the whole agree. */
enum { BUBBLE_REACH = 3 };

/* Bubbles: unknown voxels (neither observed, K, nor carved, C) that form a
 * small 6-connected component which touches neither an observed voxel
 * behind a surface (sdf <= 0, 26-neighbourhood) nor the box's outermost
 * layer.  No view saw into them, yet carved space and the free side of the
 * band enclose them: they lie between the rays of the views (at grazing
 * angles, between pixels).  Left unknown, each would come out of
 * marching cubes as a closed speck floating in the room; they are carved.
 * A component is given up (kept) as soon as it reaches further than
 * BUBBLE_REACH voxels from its first voxel in scan order.  V (zeroed, the
 * size of C) marks the voxels searched.  Returns the voxels carved. */
static size_t carve_bubbles(const struct fct_voxgrid *g, const int32_t lo[3], uint64_t *C,
                            const uint64_t *K, uint64_t *V, size_t nx, size_t ny, size_t nz, size_t nw)
{
	enum { R = BUBBLE_REACH, S = 2 * BUBBLE_REACH + 1, MAXN = S * S * (BUBBLE_REACH + 1) };
	size_t list[MAXN];
	uint32_t stamp[BUBBLE_REACH + 1][S][S], id = 0;   /* in this search: stamp == id */
	memset(stamp, 0, sizeof stamp);
	static const int step[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
	                                { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
	const size_t row = nw * 64, plane = row * ny;   /* strides of the bit index */
	size_t filled = 0;
	for (size_t k = 1; k + 1 < nz; k++)
		for (size_t j = 1; j + 1 < ny; j++)
			for (size_t i = 1; i + 1 < nx; i++) {
				size_t v0 = k * plane + j * row + i;
				if (bit_get(K, v0) || bit_get(C, v0) || bit_get(V, v0))
					continue;
				if (++id == 0) {   /* wrapped: every old stamp must go */
					memset(stamp, 0, sizeof stamp);
					id = 1;
				}
				size_t n = 0, head = 0;
				int keep = 0;
				list[n++] = v0;
				V[v0 / 64] |= 1ull << (v0 % 64);
				stamp[0][R][R] = id;
				while (head < n && !keep) {
					size_t v = list[head++];
					size_t x = v % row, y = v / row % ny, z = v / plane;
					for (int dz = -1; dz <= 1 && !keep; dz++)
						for (int dy = -1; dy <= 1 && !keep; dy++)
							for (int dx = -1; dx <= 1 && !keep; dx++) {
								float sdf, w;
								keep = bit_get(K, v + (size_t)dz * plane + (size_t)dy * row +
								                      (size_t)dx) &&
								       fct_voxgrid_get(g, lo[0] + (int32_t)x + dx,
								                       lo[1] + (int32_t)y + dy,
								                       lo[2] + (int32_t)z + dz, &sdf, &w) &&
								       !(sdf > 0);
							}
					for (int d = 0; d < 6 && !keep; d++) {
						size_t ux = x + (size_t)step[d][0], uy = y + (size_t)step[d][1],
						       uz = z + (size_t)step[d][2];
						size_t u = uz * plane + uy * row + ux;
						if (bit_get(K, u) || bit_get(C, u))
							continue;
						/* the outermost layer, or beyond the reach (z < k
						 * would be an earlier, searched start) */
						long lx = (long)ux - (long)i + R, ly = (long)uy - (long)j + R,
						     lz = (long)uz - (long)k;
						if (ux == 0 || uy == 0 || uz == 0 || ux + 1 >= nx || uy + 1 >= ny ||
						    uz + 1 >= nz || lx < 0 || ly < 0 || lz < 0 || lx >= S || ly >= S ||
						    lz > R) {
							keep = 1;
							break;
						}
						if (stamp[lz][ly][lx] == id)
							continue;   /* already in this search */
						if (bit_get(V, u)) {
							keep = 1;   /* searched before, and given up */
							break;
						}
						stamp[lz][ly][lx] = id;
						V[u / 64] |= 1ull << (u % 64);
						list[n++] = u;
					}
				}
				if (keep)
					continue;
				for (size_t q = 0; q < n; q++)
					C[list[q] / 64] |= 1ull << (list[q] % 64);
				filled += n;
			}
	return filled;
}

/* The box lo..hi in c: its extent in voxels and words. */
static int carve_box(struct fct_carving *c, const int32_t lo[3], const int32_t hi[3], struct fct_err *err)
{
	if (hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2])
		return fct_fail(err, "carving box is empty");
	memcpy(c->lo, lo, sizeof c->lo);
	c->nx = (size_t)(hi[0] - lo[0] + 1), c->ny = (size_t)(hi[1] - lo[1] + 1), c->nz = (size_t)(hi[2] - lo[2] + 1);
	c->nw = (c->nx + 63) / 64;
	size_t rows;
	if (fct_mul_size(c->ny, c->nz, &rows) || fct_mul_size(rows, c->nw, &c->words))
		return fct_fail(err, "carving box too large");
	return 0;
}

/* K: the observed voxels of g (weight above 0) in the box. */
static void observed_bits(const struct fct_voxgrid *g, const struct fct_carving *x, uint64_t *K)
{
	const int32_t *lo = x->lo;
	for (size_t bi = 0; bi < fct_voxgrid_count(g); bi++) {
		const struct fct_voxblock *b = fct_voxgrid_at(g, bi);
		for (int l = 0; l < FCT_VOXBLOCK_N; l++) {
			if (!(b->weight[l] > 0))
				continue;
			int64_t i = (int64_t)b->bx * 8 + l % 8 - lo[0], j = (int64_t)b->by * 8 + l / 8 % 8 - lo[1],
			        k = (int64_t)b->bz * 8 + l / 64 - lo[2];
			if (i < 0 || j < 0 || k < 0 || i >= (int64_t)x->nx || j >= (int64_t)x->ny || k >= (int64_t)x->nz)
				continue;
			K[((size_t)k * x->ny + (size_t)j) * x->nw + (size_t)i / 64] |= 1ull << (i % 64);
		}
	}
}

/* C: the voxels of the box that range image r saw through (depth below
 * the range its pixel holds), the outermost layer never. */
static void seen_through(const struct fct_range_image *r, double vox, const struct fct_carving *x, uint64_t *C)
{
	const struct fct_camera *cam = &r->view.cam;
	const double *M = r->inv;
	const int32_t *lo = x->lo;
	size_t nx = x->nx, ny = x->ny, nz = x->nz, nw = x->nw;
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

/* Mark the empty and unknown voxels next to a change of state: sdf +band
 * (empty, C) or -band (unknown) with weight mark_weight.  A and B: 3 nw
 * words each of scratch.  0 or -1. */
static int mark_changes(struct fct_voxgrid *g, const struct fct_carving *x, const uint64_t *C,
                        const uint64_t *K, uint64_t *A, uint64_t *B, double band, float mark_weight,
                        struct fct_err *err)
{
	const int32_t *lo = x->lo;
	size_t nx = x->nx, ny = x->ny, nz = x->nz, nw = x->nw;
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
							return -1;
						b->sdf[l] = (float)(s ? band : -band);
						b->weight[l] = mark_weight;
					}
			}
		}
	return 0;
}

int fct_carving_init(struct fct_carving *c, const int32_t lo[3], const int32_t hi[3], double vox,
                      struct fct_err *err)
{
	memset(c, 0, sizeof *c);
	if (carve_box(c, lo, hi, err))
		return -1;
	c->vox = vox;
	if (!(c->seen = calloc(c->words, 8)))
		return fct_fail(err, "out of memory for the carving bitsets (%zu MB)", 3 * c->words * 8 >> 20);
	return 0;
}

void fct_carving_add(struct fct_carving *c, const struct fct_range_image *r)
{
	seen_through(r, c->vox, c, c->seen);
}

int fct_carving_finish(struct fct_carving *c, struct fct_voxgrid *g, double band, float mark_weight,
                       size_t *carved, struct fct_err *err)
{
	size_t nw = c->nw, words = c->words;
	uint64_t *C = c->seen;
	uint64_t *K = calloc(words, 8), *V = calloc(words, 8), *A = calloc(3 * nw, 8), *B = calloc(3 * nw, 8);
	int rc = -1;
	if (!K || !V || !A || !B) {
		fct_fail(err, "out of memory for the carving bitsets (%zu MB)", 3 * words * 8 >> 20);
		goto done;
	}
	observed_bits(g, c, K);
	size_t ncarved = 0;
	for (size_t w = 0; w < words; w++) {
		C[w] &= ~K[w];
		ncarved += (size_t)__builtin_popcountll(C[w]);
	}
	ncarved += carve_bubbles(g, c->lo, C, K, V, c->nx, c->ny, c->nz, nw);
	if (carved)
		*carved = ncarved;
	rc = mark_changes(g, c, C, K, A, B, band, mark_weight, err);
done:
	free(K);
	free(V);
	free(A);
	free(B);
	return rc;
}

void fct_carving_free(struct fct_carving *c)
{
	free(c->seen);
	memset(c, 0, sizeof *c);
}

int fct_carve(struct fct_voxgrid *g, const struct fct_range_image *views, size_t nviews,
              const int32_t lo[3], const int32_t hi[3], double band, float mark_weight,
              size_t *carved, struct fct_err *err)
{
	struct fct_carving c;
	if (fct_carving_init(&c, lo, hi, fct_voxgrid_voxel(g), err))
		return -1;
	for (size_t vi = 0; vi < nviews; vi++)
		fct_carving_add(&c, &views[vi]);
	int rc = fct_carving_finish(&c, g, band, mark_weight, carved, err);
	fct_carving_free(&c);
	return rc;
}

/* fuseplane.c - true signed distance for a noisy depth image's view: to
 * the tangent plane of the pixel under the voxel's foot (Hilton's implicit
 * surface, fuse.h, the surface near a pixel taken as its plane).
 *
 * fusetrue.c searches the view's mesh for each voxel's nearest point and
 * walks downhill to it.  On a depth image under a sensor's noise that walk
 * is long and its goal is the noise: the nearest of many jittered
 * triangles is biased towards the voxel, and a quantised sensor's single
 * triangles have normals anywhere.  Here each vertex of the image's grid
 * (one every step pixels, fct_fuse_depth_step) gets a plane: its normal the
 * sum of the cross products of the four cells' triangles about it (their
 * normals weighted by area), through the mean of the nine vertices about
 * it, which averages the noise.  A voxel goes to the plane of the sample
 * it projects to, to the foot of the perpendicular there, to the plane of
 * the sample under the foot, and so on until the sample stays or the
 * distance changes by SETTLED voxels at most (PLANE_MOVES moves at most):
 * on a plane that is the exact distance, on a curved surface or at a
 * crease the distance to the plane where its foot lands.  A voxel whose
 * foot leaves the data (no vertex on its sample, or one whose depth its
 * plane could not reach within half a sample) or ends at a border vertex
 * (one whose triangles are not all there) is left alone, as fusetrue.c
 * leaves voxels whose nearest point is on a border; one whose next plane
 * is farther than its last by more than a voxel (another surface, off a
 * silhouette) keeps the plane it has.
 *
 * Per voxel: two projections and lookups in an array of one plane per
 * sample, mostly; per view: a pass over the samples.  Where the noise is
 * at least a tenth of a voxel (fct_fuse_depth_step), this is closer to the
 * true surface than the search and costs a small part of it; bench/NOTES.md
 * has the figures. */
#include "fusion/fusepriv.h"

#include <stdlib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "depth/depthmesh.h"
#include "geom/geom.h"

void fuse_planes_free(struct planes *T)
{
	free(T->pl);
	memset(T, 0, sizeof *T);
}

/* Moves from plane to plane under the foot. */
enum { PLANE_MOVES = 4 };

/* A move that changes the distance by at most this many voxels ends the
 * moves: neighbouring samples of one surface, their planes apart by the
 * noise alone. */
#define SETTLED 0.5

/* Per cell of the grid: the sum of its triangles' cross products (their
 * normals weighted by twice their area), and which of its corners have
 * all of the cell's triangles about them. */
struct cellsum {
	float n[3];
	uint8_t ring;            /* bit q: corner q (x + 2 y in the cell); 15: both halves */
};

/* Row cy of the grid's cells into cs (w of them).  A half holds the two
 * corners on the diagonal, which the other half holds too, and the one
 * opposite the corner it leaves out: alone, it closes that corner only. */
static void cell_row(const struct raster *R, size_t cy, struct cellsum *cs)
{
	const struct pixgrid *P = &R->grid;
	const struct geo *G = R->G;
	for (size_t cx = 0; cx < P->w; cx++) {
		double sum[3] = { 0, 0, 0 };
		unsigned corners = 0;
		int halves = 0;
		for (int k = 0; k < 2; k++) {
			int32_t t = P->cell[2 * (cy * P->w + cx) + k], tx, ty;
			if (t < 0)
				continue;
			const uint32_t *tv = &G->tv[3 * (size_t)t];
			const double *a = &G->xyz[3 * tv[0]], *b = &G->xyz[3 * tv[1]], *d = &G->xyz[3 * tv[2]];
			double e1[3], e2[3], n[3];
			fct_v3_sub(e1, b, a);
			fct_v3_sub(e2, d, a);
			fct_v3_cross(n, e1, e2);
			fct_v3_add(sum, sum, n);
			corners = cell_corners(P->at, tv, &tx, &ty);
			halves++;
		}
		for (int k = 0; k < 3; k++)
			cs[cx].n[k] = (float)sum[k];
		cs[cx].ring = (uint8_t)(halves == 2 ? 15 : halves == 1 ? 1u << (3 - __builtin_ctz(~corners & 15)) : 0);
	}
}

/* The vertex on each sample of the grid, or -1. */
static int32_t *sample_vertices(const struct raster *R, struct fct_err *err)
{
	const struct pixgrid *P = &R->grid;
	int32_t *sv = fct_alloc_array(P->w * P->h, sizeof *sv, err);
	if (!sv)
		return NULL;
	memset(sv, 0xff, P->w * P->h * sizeof *sv);
	for (size_t i = 0; i < R->G->nv; i++)
		if (P->at[2 * i] >= 0)
			sv[(size_t)P->at[2 * i + 1] * P->w + (size_t)P->at[2 * i]] = (int32_t)i;
	return sv;
}

/* The plane of the vertex on sample (x, y): the sum of the cross
 * products of the four cells about it (rows y - 1 and y: above and here,
 * NULL out of the grid), through the mean of the nine samples' vertices
 * when those cells are whole (one surface, the mesh being cut at depth
 * jumps) and the nine span at most `most` metres (the band: a mean
 * over more blurs what the band resolves; on a coarse image, 160x120 at
 * 2 cm voxels, the planar model made from it lost 0.5 dB at held-out
 * views), else through the vertex.  *inside: the triangles about the
 * vertex are all there (it is on no border).  0 when its normal is none. */
static int vertex_plane(const struct raster *R, const struct cellsum *above, const struct cellsum *here,
                        const int32_t *sv, size_t x, size_t y, double most, double n[3], double p[3], int *inside)
{
	const struct pixgrid *P = &R->grid;
	size_t w = P->w;
	n[0] = n[1] = n[2] = 0;
	int in = above && here && x > 0 && x + 1 < w && y + 1 < P->h, whole = in;
	const struct cellsum *rows[2] = { above, here };
	for (int r = 0; r < 2; r++)
		for (size_t cx = x - 1; rows[r] && cx <= x; cx++) {
			if (cx >= w)   /* also x - 1 below 0 */
				continue;
			const struct cellsum *c = &rows[r][cx];
			n[0] += c->n[0], n[1] += c->n[1], n[2] += c->n[2];
			/* The vertex is corner 3 of the cell above left, 2 above
			 * right, 1 left and 0 right. */
			int q = (cx == x ? 0 : 1) + (r == 0 ? 2 : 0);
			in &= c->ring >> q & 1;
			whole &= c->ring == 15;
		}
	*inside = in;
	double len = sqrt(fct_v3_dot(n, n));
	if (!(len > 0) || !isfinite(len))
		return 0;
	for (int k = 0; k < 3; k++)
		n[k] /= len;
	/* The nine samples span two sample widths (depth / (f S) each). */
	double span = 2 / (R->sp[3 * (size_t)sv[y * w + x] + 2] * R->v->cam.fx * R->S);
	if (!whole || span > most) {
		memcpy(p, &R->G->xyz[3 * (size_t)sv[y * w + x]], 3 * sizeof *p);
		return 1;
	}
	/* The noise of one sample averaged over nine. */
	p[0] = p[1] = p[2] = 0;
	for (size_t sy = y - 1; sy <= y + 1; sy++)
		for (size_t sx = x - 1; sx <= x + 1; sx++)
			fct_v3_add(p, p, &R->G->xyz[3 * (size_t)sv[sy * w + sx]]);
	for (int k = 0; k < 3; k++)
		p[k] *= 1.0 / 9;
	return 1;
}

int fuse_planes_build(struct planes *T, const struct raster *R, const struct fct_fuse_view *v,
                      const struct fct_fuse_params *fp, double vox, struct fct_err *err)
{
	memset(T, 0, sizeof *T);
	const struct pixgrid *P = &R->grid;
	size_t w = P->w, h = P->h;
	T->w = w, T->h = h;
	T->pl = fct_alloc_array(w * h, sizeof *T->pl, err);
	struct cellsum *cs = T->pl ? fct_alloc_array(2 * w, sizeof *cs, err) : NULL;   /* two rows */
	int32_t *sv = cs ? sample_vertices(R, err) : NULL;
	if (!sv) {
		free(cs);
		fuse_planes_free(T);
		return -1;
	}
	/* Half a sample of a plane as steep as the mesher's jump test lets
	 * a surface be (FCT_DEFAULT_MAX_JUMP: 10 times the lateral step). */
	const struct fct_camera *cam = &v->cam;
	T->reach = 0.5 * FCT_DEFAULT_MAX_JUMP / (dmin(cam->fx, cam->fy) * R->S);
	T->ax = cam->fx * R->S, T->bx = (cam->cx - R->u0) * R->S;
	T->ay = cam->fy * R->S, T->by = (cam->cy - R->v0) * R->S;
	const double *M = R->inv;
	for (size_t y = 0; y < h; y++) {
		struct cellsum *here = &cs[(y & 1) * w], *above = y > 0 ? &cs[((y - 1) & 1) * w] : NULL;
		cell_row(R, y, here);
		for (size_t x = 0; x < w; x++) {
			size_t si = y * w + x;
			struct plane *pl = &T->pl[si];
			double n[3], p[3];
			int inside;
			pl->n[0] = NAN;
			if (sv[si] < 0 || !vertex_plane(R, above, here, sv, x, y, fp->band, n, p, &inside))
				continue;
			/* In the camera's frame, where the voxels' feet are
			 * projected. */
			double nc[3], pc[3];
			for (int k = 0; k < 3; k++) {
				nc[k] = M[4 * k] * n[0] + M[4 * k + 1] * n[1] + M[4 * k + 2] * n[2];
				pc[k] = M[4 * k] * p[0] + M[4 * k + 1] * p[1] + M[4 * k + 2] * p[2] + M[4 * k + 3];
			}
			for (int k = 0; k < 3; k++)
				pl->n[k] = (float)nc[k];
			pl->off = (float)fct_v3_dot(nc, pc);
			pl->depth = (float)pc[2];
			/* The weight at the plane's point stands for the weight
			 * anywhere on its sample: the ray and the depth change
			 * little within it. */
			double wt = fuse_view_weight(v, fp, p, n);
			if (v->sigma)
				wt *= sigma_weight(v->sigma[sv[si]], vox);
			pl->weight = inside ? (float)wt : -1;
		}
	}
	free(sv);
	free(cs);
	return 0;
}

static inline double plane_at(const struct plane *pl, const double c[3])
{
	return c[0] * pl->n[0] + c[1] * pl->n[1] + c[2] * pl->n[2] - pl->off;
}

/* The sample nearest camera point c, or -1 (off the grid, or c behind the
 * camera); s gets c's sample coordinates and 1 / depth. */
static inline long sample_at(const struct planes *T, const double c[3], double s[3])
{
	if (!(c[2] > 0))
		return -1;
	double iz = 1 / c[2], sx = T->ax * c[0] * iz + T->bx, sy = T->ay * c[1] * iz + T->by;
	s[0] = sx, s[1] = sy, s[2] = iz;
	if (!(sx > -0.5 && sy > -0.5 && sx < (double)T->w - 0.5 && sy < (double)T->h - 0.5))
		return -1;
	return (long)(sy + 0.5) * (long)T->w + (long)(sx + 0.5);
}

/* The plane of sample si, or NULL (none there). */
static inline const struct plane *plane_of(const struct planes *T, long si)
{
	return si >= 0 && !isnan(T->pl[si].n[0]) ? &T->pl[si] : NULL;
}

/* A voxel on its way to its plane: its camera point, the plane it is at
 * and its distance to it, and the sample under its foot there. */
struct walker {
	double c[3], d;
	double s[3];             /* the voxel's sample coordinates and 1 / depth */
	const struct plane *pl;
	long foot;
	int l;                   /* the voxel in its block */
};

/* The foot of w on its plane: its sample, asked for. */
static inline void foot_sample(const struct planes *T, struct walker *w)
{
	const float *n = w->pl->n;
	double f[3] = { w->c[0] - w->d * n[0], w->c[1] - w->d * n[1], w->c[2] - w->d * n[2] };
	double fs[3];
	w->foot = sample_at(T, f, fs);
	if (w->foot >= 0)
		__builtin_prefetch(&T->pl[w->foot]);
}

/* Whether the foot of w on its first plane is on the voxel's own sample,
 * by a bound on how far it is from the voxel in the image: |d| times the
 * derivative of the projection along the normal, over 1 - |d| / depth
 * (at most 2 where this answers).  Voxels near their surface skip the
 * foot's projection. */
static inline int foot_stays(const struct planes *T, const struct walker *w)
{
	double ad = fabs(w->d), iz = w->s[2];
	if (!(ad * iz <= 0.5))
		return 0;
	const float *n = w->pl->n;
	double u = w->c[0] * iz, v = w->c[1] * iz, k = 2 * ad * iz, nz = fabs(n[2]);
	double mx = T->ax * k * (fabs(n[0]) + fabs(u) * nz), my = T->ay * k * (fabs(n[1]) + fabs(v) * nz);
	double fx = w->s[0] - floor(w->s[0] + 0.5), fy = w->s[1] - floor(w->s[1] + 0.5);
	return mx < 0.5 - fabs(fx) && my < 0.5 - fabs(fy);
}

/* One move of w to the plane under its foot: 1 when it moves on, 0 when
 * its plane is final, -1 when its foot leaves the data (no sample there,
 * or one whose point is farther from the foot in depth than its plane
 * could take it within half a sample: a plane seen edge-on, whose foot
 * can be anywhere along the ray). */
static inline int foot_move(const struct fctx *F, struct walker *w)
{
	const struct planes *T = F->T;
	const struct plane *next = plane_of(T, w->foot);
	double fz = w->c[2] - w->d * w->pl->n[2];
	if (!next || !(fabs(fz - next->depth) <= dmax(F->vox, T->reach * next->depth)))
		return -1;
	if (next == w->pl)
		return 0;
	double dn = plane_at(next, w->c);
	if (fabs(dn) > fabs(w->d) + F->vox)
		return 0;   /* another surface: w keeps its plane */
	int settled = fabs(dn - w->d) <= SETTLED * F->vox;
	w->pl = next, w->d = dn;
	return !settled;
}

/* Voxels taken through the stages together, so that the loads of one
 * wait beside the others' (a voxel's own loads depend on each other). */
enum { PLANE_BATCH = 64 };

/* The walkers W[0 .. n) of block b: their moves, the first of every
 * walker side by side, the rare later ones one walker at a time; then
 * their distances put. */
static void plane_batch(const struct fctx *F, struct sblock *b, struct walker *W, int n)
{
	const struct planes *T = F->T;
	double band = F->band, cap = F->p->band;
	int go[PLANE_BATCH];
	for (int i = 0; i < n; i++) {
		struct walker *w = &W[i];
		w->pl = plane_of(T, w->foot);
		go[i] = w->pl != NULL;
		if (!go[i])
			continue;
		w->d = plane_at(w->pl, w->c);
		/* Far in front of the surface seen: out of the band of any
		 * surface the foot could reach. */
		go[i] = !(w->d > band + 2 * F->vox);
		if (go[i] && !foot_stays(T, w))
			foot_sample(T, w);
	}
	for (int i = 0; i < n; i++) {
		if (!go[i])
			continue;
		struct walker *w = &W[i];
		int m = foot_move(F, w);
		for (int k = 1; m > 0 && k < PLANE_MOVES; k++) {
			foot_sample(T, w);
			m = foot_move(F, w);
		}
		if (m < 0 || !(fabs(w->d) <= band))
			continue;
		if (w->pl->weight < 0) {
			b->nborder++;
			continue;
		}
		put(b, w->l, (float)dmax(-cap, dmin(w->d, cap)), w->pl->weight);
	}
}

/* The samples under walkers W[a .. b), from their camera points: sample
 * coordinates and 1 / depth into s, the sample into foot (-1: none), and
 * its plane asked for.  Two at a time where there is SSE2 (the division
 * was a third of the voxels' time): the same operations as sample_at. */
static void walkers_seen(const struct planes *T, struct walker *W, int a, int b)
{
	int i = a;
#if defined(__SSE2__)
	const __m128d one = _mm_set1_pd(1), AX = _mm_set1_pd(T->ax), BX = _mm_set1_pd(T->bx),
	              AY = _mm_set1_pd(T->ay), BY = _mm_set1_pd(T->by);
	for (; i + 1 < b; i += 2) {
		struct walker *u = &W[i], *v = &W[i + 1];
		__m128d iz = _mm_div_pd(one, _mm_set_pd(v->c[2], u->c[2]));
		__m128d sx = _mm_add_pd(_mm_mul_pd(_mm_mul_pd(AX, _mm_set_pd(v->c[0], u->c[0])), iz), BX);
		__m128d sy = _mm_add_pd(_mm_mul_pd(_mm_mul_pd(AY, _mm_set_pd(v->c[1], u->c[1])), iz), BY);
		double z[2], x[2], y[2];
		_mm_storeu_pd(z, iz), _mm_storeu_pd(x, sx), _mm_storeu_pd(y, sy);
		struct walker *p[2] = { u, v };
		for (int k = 0; k < 2; k++) {
			struct walker *w = p[k];
			w->s[0] = x[k], w->s[1] = y[k], w->s[2] = z[k];
			w->foot = w->c[2] > 0 && x[k] > -0.5 && y[k] > -0.5 && x[k] < (double)T->w - 0.5 &&
			          y[k] < (double)T->h - 0.5 ? (long)(y[k] + 0.5) * (long)T->w + (long)(x[k] + 0.5) : -1;
		}
	}
#endif
	for (; i < b; i++)
		W[i].foot = sample_at(T, W[i].c, W[i].s);
	for (i = a; i < b; i++)
		if (W[i].foot >= 0)
			__builtin_prefetch(&T->pl[W[i].foot]);
}

void fuse_plane_blocks(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	const struct fctx *F = ctx;
	const struct planes *T = F->T;
	const double *M = F->R->inv;
	double vox = F->vox;
	/* Camera coordinates along a row of voxels by adding a step. */
	double dx[3] = { M[0] * vox, M[4] * vox, M[8] * vox };
	struct walker W[PLANE_BATCH];
	for (size_t bi = lo; bi < hi; bi++) {
		struct sblock *b = F->s->blk[bi];
		int32_t o[3] = { b->bx * FCT_VOXBLOCK, b->by * FCT_VOXBLOCK, b->bz * FCT_VOXBLOCK };
		int n = 0;
		for (int z = b->lo[2]; z <= b->hi[2]; z++)
			for (int y = b->lo[1]; y <= b->hi[1]; y++) {
				unsigned row = b->row[y + FCT_VOXBLOCK * z];
				if (!row)
					continue;
				if (n + FCT_VOXBLOCK > PLANE_BATCH)
					plane_batch(F, b, W, n), n = 0;
				double X = o[0] * vox, Y = (o[1] + y) * vox, Z = (o[2] + z) * vox, c0[3];
				for (int a = 0; a < 3; a++)
					c0[a] = M[4 * a] * X + M[4 * a + 1] * Y + M[4 * a + 2] * Z + M[4 * a + 3];
				int first = n;
				for (; row; row &= row - 1) {
					int xx = __builtin_ctz(row);
					if (!in_clip(F->p, o[0] + xx, o[1] + y, o[2] + z))
						continue;
					struct walker *w = &W[n++];
					for (int a = 0; a < 3; a++)
						w->c[a] = c0[a] + xx * dx[a];
					w->l = xx + FCT_VOXBLOCK * (y + FCT_VOXBLOCK * z);
				}
				walkers_seen(T, W, first, n);
			}
		plane_batch(F, b, W, n);
	}
}

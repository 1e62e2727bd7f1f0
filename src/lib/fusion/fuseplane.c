/* fuseplane.c - true signed distance for a depth image's view: to the
 * tangent plane of the pixel under the voxel's foot (Hilton's implicit
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
 * it, which averages the noise (through the vertex itself when the noise
 * is under a tenth of a voxel).  A voxel goes to the plane of the sample
 * it projects to, to the foot of the perpendicular there, to the plane of
 * the sample under the foot, and so on until the sample stays or the
 * distance changes by SETTLED voxels at most (PLANE_MOVES moves at most):
 * on a plane that is the exact distance, on a curved surface or at a
 * crease the distance to the plane where its foot lands.  A voxel whose
 * foot leaves the data (no vertex on its sample, or one whose depth its
 * plane could not reach within half a sample) or ends at a border vertex
 * (one whose triangles are not all there) is left alone, as fusetrue.c
 * leaves voxels whose nearest point is on a border, and so is one farther
 * than the band and two voxels from the plane of its own sample, in front
 * or behind (out of the band of any surface the foot could reach, nearly
 * always: its sample sees another surface); one whose next plane
 * is farther than its last by more than a voxel (another surface, off a
 * silhouette) keeps the plane it has.
 *
 * Per voxel: two projections and lookups in an array of one plane per
 * sample, mostly, four voxels side by side in floats; per view: a pass
 * over the samples, its sums kept by column.  It costs a small part of
 * the search; where the noise is at least a tenth of a voxel it is closer
 * to the true surface than the search too, with less it is a little less
 * complete at silhouettes (fct_fuse_depth_step; bench/NOTES.md has the
 * figures). */
#include "fusion/fusepriv.h"

#include <stdlib.h>

#include "core/lanes.h"
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
			double n[3];
			fct_triangle_cross(n, a, b, d);
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

/* Per sample x of a row y, sums the planes of the row's vertices are
 * made of: the cross products of cells x of rows y - 1 and y (a vertex's
 * four cells are its column's and the one's to its left), and the
 * vertices on the sample and on those above and below it (a vertex's nine
 * are three columns'). */
struct column {
	float n[3];
	uint8_t ring;            /* bits 0, 1: the cell above has its corners 2, 3 closed
	                          * (those on this row); 2, 3: the cell here its 0, 1;
	                          * 4: both cells whole */
	double p[3];             /* NaN: a vertex of the three missing */
};

/* Row y's columns (w of them, cells x of rows y - 1 and y: above and here,
 * NULL out of the grid) into cols. */
static void column_row(const struct raster *R, const struct cellsum *above, const struct cellsum *here,
                       const int32_t *sv, size_t y, struct column *cols)
{
	const struct pixgrid *P = &R->grid;
	size_t w = P->w;
	int inner = above && y + 1 < P->h;   /* rows y - 1 and y + 1 exist */
	for (size_t x = 0; x < w; x++) {
		struct column *c = &cols[x];
		const struct cellsum *u = above ? &above[x] : NULL, *d = &here[x];
		for (int k = 0; k < 3; k++)
			c->n[k] = d->n[k] + (u ? u->n[k] : 0);
		/* The vertex (x, y) is corner 2 of the cell above and 0 of the
		 * cell here; (x + 1, y) their corners 3 and 1. */
		c->ring = (uint8_t)((u ? (u->ring >> 2 & 3) | (u->ring == 15) << 4 : 0) | (d->ring & 3) << 2);
		c->ring &= (uint8_t)(d->ring == 15 ? 0xff : 0x0f);
		const int32_t *v = &sv[y * w + x];
		if (!inner || v[-(ptrdiff_t)w] < 0 || v[0] < 0 || v[w] < 0) {
			c->p[0] = c->p[1] = c->p[2] = NAN;
			continue;
		}
		const double *a = &R->G->xyz[3 * (size_t)v[-(ptrdiff_t)w]], *b = &R->G->xyz[3 * (size_t)v[0]],
		             *e = &R->G->xyz[3 * (size_t)v[w]];
		for (int k = 0; k < 3; k++)
			c->p[k] = a[k] + b[k] + e[k];
	}
}

/* The plane of the vertex on sample (x, y) from its row's columns: the
 * sum of the cross products of the four cells about it, through the mean
 * of the nine samples' vertices when the view has noise to average
 * (plane_mean), those cells are whole (one surface, the mesh being cut at
 * depth jumps) and the nine span at most `most` metres (the band: a mean
 * over more blurs what the band resolves; on a coarse image, 160x120 at 2
 * cm voxels, the planar model made from it lost 0.5 dB at held-out
 * views), else through the vertex (without noise the mean of nine cuts
 * the corner of a crease: 0.23 mm from the true surface against 0.14 on
 * mkscene's room without noise).  *inside: the
 * triangles about the vertex are all there (it is on no border).  0 when
 * its normal is none. */
static int vertex_plane(const struct raster *R, const struct column *cols, const int32_t *sv, size_t x, size_t y,
                        double most, double n[3], double p[3], int *inside)
{
	const struct pixgrid *P = &R->grid;
	size_t w = P->w;
	if (x == 0 || x + 1 >= w) {
		/* On the grid's edge: its cells on one side only. */
		const struct column *c = &cols[x == 0 ? 0 : x - 1];
		for (int k = 0; k < 3; k++)
			n[k] = c->n[k];
		*inside = 0;
	} else {
		const struct column *l = &cols[x - 1], *r = &cols[x];
		for (int k = 0; k < 3; k++)
			n[k] = (double)l->n[k] + r->n[k];
		/* Closed in all four cells: corners 3 above left (bit 1), 2
		 * above right (bit 0), 1 here left (bit 3), 0 here right
		 * (bit 2). */
		*inside = (l->ring & 0x0a) == 0x0a && (r->ring & 0x05) == 0x05;
	}
	double len = sqrt(fct_v3_dot(n, n));
	if (!(len > 0) || !isfinite(len))
		return 0;
	for (int k = 0; k < 3; k++)
		n[k] /= len;
	size_t vi = (size_t)sv[y * w + x];
	/* The nine samples span two sample widths (depth / (f S) each). */
	int whole = *inside && (cols[x - 1].ring & cols[x].ring & 0x10) && !isnan(cols[x - 1].p[0]) &&
	            !isnan(cols[x].p[0]) && !isnan(cols[x + 1].p[0]);
	if (!whole || !R->v->plane_mean || 2 / (R->sp[3 * vi + 2] * R->v->cam.fx * R->S) > most) {
		memcpy(p, &R->G->xyz[3 * vi], 3 * sizeof *p);
		return 1;
	}
	/* The noise of one sample averaged over nine. */
	for (int k = 0; k < 3; k++)
		p[k] = (cols[x - 1].p[k] + cols[x].p[k] + cols[x + 1].p[k]) * (1.0 / 9);
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
	struct column *cols = cs ? fct_alloc_array(w, sizeof *cols, err) : NULL;
	int32_t *sv = cols ? sample_vertices(R, err) : NULL;
	if (!sv) {
		free(cols);
		free(cs);
		fuse_planes_free(T);
		return -1;
	}
	/* Half a sample of a plane as steep as the mesher's jump test lets
	 * a surface be (FCT_DEFAULT_MAX_JUMP: 10 times the lateral step). */
	const struct fct_camera *cam = &v->cam;
	T->reach = (float)(0.5 * FCT_DEFAULT_MAX_JUMP / (dmin(cam->fx, cam->fy) * R->S));
	T->ax = (float)(cam->fx * R->S), T->bx = (float)((cam->cx - R->u0) * R->S + 0.5);
	T->ay = (float)(cam->fy * R->S), T->by = (float)((cam->cy - R->v0) * R->S + 0.5);
	const double *M = R->inv;
	for (size_t y = 0; y < h; y++) {
		struct cellsum *here = &cs[(y & 1) * w], *above = y > 0 ? &cs[((y - 1) & 1) * w] : NULL;
		cell_row(R, y, here);
		column_row(R, above, here, sv, y, cols);
		for (size_t x = 0; x < w; x++) {
			size_t si = y * w + x;
			struct plane *pl = &T->pl[si];
			double n[3], p[3];
			int inside;
			pl->n[0] = NAN;
			if (sv[si] < 0 || !vertex_plane(R, cols, sv, x, y, fp->band, n, p, &inside))
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
	free(cols);
	free(cs);
	return 0;
}

/* Four voxels at once (lanes.h).  Floats: in the camera's frame a voxel's
 * coordinates are metres from the sensor, where a float's rounding (a
 * tenth of a micrometre at 5 m) is far below any voxel, and the planes
 * are floats. */

/* The samples nearest camera points (x, y, z): their indices, -1 where
 * off the grid or behind the camera. */
static inline v4i samples4(const struct planes *T, v4f x, v4f y, v4f z)
{
	v4i front = z > 0;
	v4f iz = 1 / select4(front, z, (v4f){ 1, 1, 1, 1 });
	v4f sx = T->ax * x * iz + T->bx, sy = T->ay * y * iz + T->by;
	v4i in = front & (sx > 0) & (sy > 0) & (sx < (float)T->w) & (sy < (float)T->h);
	/* Out of the grid the coordinates may be anything: not converted. */
	v4i ix = __builtin_convertvector(select4(in, sx, (v4f){ 0 }), v4i);
	v4i iy = __builtin_convertvector(select4(in, sy, (v4f){ 0 }), v4i);
	return ((iy * (int32_t)T->w + ix) & in) | ~in;
}

/* The plane of sample si, or NULL (none there). */
static inline const struct plane *plane_of(const struct planes *T, int32_t si)
{
	return si >= 0 && !isnan(T->pl[si].n[0]) ? &T->pl[si] : NULL;
}

/* Voxels of a block on their way to their planes, taken together so that
 * the loads of one wait beside the others' (a voxel's own loads depend on
 * each other) and their arithmetic goes by fours.  Room for a batch
 * rounded up to four. */
enum { PLANE_BATCH = 64 };

struct walkers {
	float x[PLANE_BATCH], y[PLANE_BATCH], z[PLANE_BATCH];   /* camera points */
	float d[PLANE_BATCH];                  /* distance to its plane */
	float fz[PLANE_BATCH];                 /* its foot's depth on that plane */
	int32_t at[PLANE_BATCH];               /* the sample under the voxel, then under its foot */
	int32_t l[PLANE_BATCH];                /* the voxel in its block */
	const struct plane *pl[PLANE_BATCH];   /* its plane; NULL: left alone */
	int n;
};

/* The sample under the foot of walker i on its plane, and the foot's
 * depth: samples4 in all four lanes, the same arithmetic as the first
 * moves' (later moves are rare: 0.9 M of them for 10 M voxels near their
 * planes on mkscene's noisy room). */
static inline void foot_sample(const struct planes *T, struct walkers *W, int i)
{
	const struct plane *pl = W->pl[i];
	float d = W->d[i], fx = W->x[i] - d * pl->n[0], fy = W->y[i] - d * pl->n[1], fz = W->z[i] - d * pl->n[2];
	W->at[i] = samples4(T, (v4f){ fx, fx, fx, fx }, (v4f){ fy, fy, fy, fy }, (v4f){ fz, fz, fz, fz })[0];
	W->fz[i] = fz;
}

/* One move of walker i to the plane under its foot: 1 when it moves on, 0
 * when its plane is final, -1 when its foot leaves the data (no sample
 * there, or one whose point is farther from the foot in depth than its
 * plane could take it within half a sample: a plane seen edge-on, whose
 * foot can be anywhere along the ray). */
static inline int foot_move(const struct fctx *F, struct walkers *W, int i)
{
	const struct planes *T = F->T;
	const struct plane *next = plane_of(T, W->at[i]);
	float vox = (float)F->vox, reach = T->reach * (next ? next->depth : 0);
	if (!next || !(fabsf(W->fz[i] - next->depth) <= (reach > vox ? reach : vox)))
		return -1;
	if (next == W->pl[i])
		return 0;
	float d = W->d[i], dn = W->x[i] * next->n[0] + W->y[i] * next->n[1] + W->z[i] * next->n[2] - next->off;
	if (fabsf(dn) > fabsf(d) + vox)
		return 0;   /* another surface: the walker keeps its plane */
	W->pl[i] = next, W->d[i] = dn;
	return !(fabsf(dn - d) <= (float)SETTLED * vox);
}

/* The walkers of block b: each to the plane of its sample, then to the
 * plane under its foot there, four side by side; the rare later moves one
 * walker at a time; then their distances put. */
static void plane_batch(const struct fctx *F, struct sblock *b, struct walkers *W)
{
	const struct planes *T = F->T;
	int n = W->n, n4 = (n + 3) & ~3;
	for (int i = n; i < n4; i++)   /* behind the camera: no sample */
		W->x[i] = W->y[i] = W->z[i] = 0;
	for (int i = 0; i < n4; i += 4) {
		v4i at = samples4(T, load4(&W->x[i]), load4(&W->y[i]), load4(&W->z[i]));
		memcpy(&W->at[i], &at, sizeof at);
		for (int k = 0; k < 4; k++)
			if (at[k] >= 0)
				__builtin_prefetch(&T->pl[at[k]]);
	}
	/* Each walker's plane, its normal and offset gathered by fours (no
	 * plane: NaN, which no test passes). */
	float nx[PLANE_BATCH], ny[PLANE_BATCH], nz[PLANE_BATCH], off[PLANE_BATCH];
	for (int i = 0; i < n4; i++) {
		const struct plane *pl = W->pl[i] = plane_of(T, W->at[i]);
		nx[i] = pl ? pl->n[0] : 0, ny[i] = pl ? pl->n[1] : 0, nz[i] = pl ? pl->n[2] : 0;
		off[i] = pl ? pl->off : NAN;
	}
	/* Far in front of the surface seen, or far behind it: out of the
	 * band of any surface the foot could reach (behind a silhouette,
	 * nearly always: fewer than one in a hundred of those voxels behind
	 * ended in another surface's band, on the 7-Scenes frames and
	 * mkscene's noisy room, where 14% and 6% of the
	 * candidates are such). */
	float far = (float)(F->band + 2 * F->vox);
	for (int i = 0; i < n4; i += 4) {
		v4f x = load4(&W->x[i]), y = load4(&W->y[i]), z = load4(&W->z[i]);
		v4f a = load4(&nx[i]), c = load4(&ny[i]), e = load4(&nz[i]);
		v4f d = x * a + y * c + z * e - load4(&off[i]);
		v4i go = (d <= far) & (d >= -far);
		v4f fx = x - d * a, fy = y - d * c, fz = z - d * e;
		v4i at = samples4(T, fx, fy, fz) | ~go;
		store4(&W->d[i], d), store4(&W->fz[i], fz);
		memcpy(&W->at[i], &at, sizeof at);
		for (int k = 0; k < 4; k++) {
			if (!go[k])
				W->pl[i + k] = NULL;
			else if (at[k] >= 0)
				__builtin_prefetch(&T->pl[at[k]]);
		}
	}
	float band = (float)F->band, cap = (float)F->p->band;
	for (int i = 0; i < n; i++) {
		if (!W->pl[i])
			continue;
		int m = foot_move(F, W, i);
		for (int k = 1; m > 0 && k < PLANE_MOVES; k++) {
			foot_sample(T, W, i);
			m = foot_move(F, W, i);
		}
		if (m < 0 || !(fabsf(W->d[i]) <= band))
			continue;
		if (W->pl[i]->weight < 0) {
			b->nborder++;
			continue;
		}
		float d = W->d[i];
		put(b, W->l[i], d < -cap ? -cap : d > cap ? cap : d, W->pl[i]->weight);
	}
	W->n = 0;
}

void fuse_plane_blocks(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	const struct fctx *F = ctx;
	const double *M = F->R->inv;
	double vox = F->vox;
	/* Camera coordinates along a row of voxels by adding a step. */
	double dx[3] = { M[0] * vox, M[4] * vox, M[8] * vox };
	struct walkers W;
	W.n = 0;
	for (size_t bi = lo; bi < hi; bi++) {
		struct sblock *b = F->s->blk[bi];
		int32_t o[3] = { b->bx * FCT_VOXBLOCK, b->by * FCT_VOXBLOCK, b->bz * FCT_VOXBLOCK };
		for (int z = b->lo[2]; z <= b->hi[2]; z++)
			for (int y = b->lo[1]; y <= b->hi[1]; y++) {
				unsigned row = b->row[y + FCT_VOXBLOCK * z];
				if (!row)
					continue;
				if (W.n + FCT_VOXBLOCK > PLANE_BATCH)
					plane_batch(F, b, &W);
				double X = o[0] * vox, Y = (o[1] + y) * vox, Z = (o[2] + z) * vox, c0[3];
				for (int a = 0; a < 3; a++)
					c0[a] = M[4 * a] * X + M[4 * a + 1] * Y + M[4 * a + 2] * Z + M[4 * a + 3];
				for (; row; row &= row - 1) {
					int xx = __builtin_ctz(row);
					if (!in_clip(F->p, o[0] + xx, o[1] + y, o[2] + z))
						continue;
					int i = W.n++;
					W.x[i] = (float)(c0[0] + xx * dx[0]);
					W.y[i] = (float)(c0[1] + xx * dx[1]);
					W.z[i] = (float)(c0[2] + xx * dx[2]);
					W.l[i] = xx + FCT_VOXBLOCK * (y + FCT_VOXBLOCK * z);
				}
			}
		plane_batch(F, b, &W);
	}
}

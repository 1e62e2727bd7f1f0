/* fuseraster.c - a view's raster for fusion: the triangle seen at each
 * sample of its sensor image (nearest and farthest), or the pixel grid of
 * a range image's mesh, which needs none; and the range image carving and
 * colour read (fct_range_image_make).
 *
 * A second rasteriser beside raster.c's: that one draws pinhole pictures
 * (meshshot) with exact coverage on a 1/256-pixel grid and perspective
 * barycentrics for shading.  Fusion needs what it does not have:
 * cylindrical and orthographic sensors, two samples per pixel, the
 * farthest triangle beside the nearest, the depths of a range image's
 * vertices on their own pixels (one splat per grid triangle instead of a
 * scan), and the grid's cells in place of a raster; its rule (pixel
 * centres within 1e-9 of the edges, the lower triangle at equal depth)
 * is the one the fused volumes were made with. */
#include "fusion/fusepriv.h"

#include <stdlib.h>

#include "core/par.h"

void fct_range_image_free(struct fct_range_image *r)
{
	if (r) {
		free(r->range);
		r->range = NULL;
	}
}

void fuse_raster_free(struct raster *R)
{
	free(R->z);
	free(R->id);
	free(R->zf);
	free(R->idf);
	free(R->sp);
	free(R->at);
	free(R->zv);
	free(R->gen);
	free(R->grid.cell);
	free(R->grid.diag);
	memset(R, 0, sizeof *R);
}

/* The projection of G's vertices into R's sensor: R->sp in sensor
 * coordinates (u, v, depth; NaN: not seen) and the box of those seen, per
 * worker (merged after: minima and maxima, the same in any order). */
struct projection {
	struct raster *R;
	double lo[FCT_PAR_MAX][2], hi[FCT_PAR_MAX][2];
};

static void project_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	struct projection *P = ctx;
	const struct raster *R = P->R;
	const double *xyz = R->G->xyz;
	double *restrict sp = R->sp;   /* no store to it changes R's matrix */
	int ortho = R->v->cam.kind == FCT_CAMERA_NONE;
	/* The chunk's box, merged into the worker's: minima and maxima, the
	 * same in any order (but for the sign of a zero, which the frame
	 * does not see: floor(-0) - 1 = floor(0) - 1); in locals, as stores
	 * through the worker's slot would go to memory for every vertex. */
	double blo[2] = { P->lo[worker][0], P->lo[worker][1] }, bhi[2] = { P->hi[worker][0], P->hi[worker][1] };
	for (size_t i = lo; i < hi; i++) {
		double u, v, d;
		double *o = &sp[3 * i];
		/* In double: a range image's vertices lie on pixel centres, and
		 * a border vertex rounded off its centre would lose its pixel. */
		if (sensor_project(R, &xyz[3 * i], &u, &v, &d) && (d > 0 || ortho) && isfinite(u) &&
		    isfinite(v) && isfinite(d)) {
			o[0] = u, o[1] = v, o[2] = d;
			blo[0] = dmin(u, blo[0]), bhi[0] = dmax(u, bhi[0]);
			blo[1] = dmin(v, blo[1]), bhi[1] = dmax(v, bhi[1]);
		} else {
			o[0] = o[1] = o[2] = NAN;
		}
	}
	P->lo[worker][0] = blo[0], P->lo[worker][1] = blo[1];
	P->hi[worker][0] = bhi[0], P->hi[worker][1] = bhi[1];
}

/* The depth the raster keeps for vertex i (sp: sample coordinates). */
static inline float vertex_depth(const struct raster *R, size_t i)
{
	double d = R->sp[3 * i + 2];
	return (float)(R->v->cam.kind == FCT_CAMERA_PINHOLE ? 1 / d : d);
}

/* Vertices from sensor to sample coordinates (x, y, depth or 1/depth for
 * pinholes; NaN: not seen), in place; with R->at, the sample each lies on,
 * and with R->zv its depth. */
static void samples_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	struct raster *R = ctx;
	int pin = R->v->cam.kind == FCT_CAMERA_PINHOLE;
	for (size_t i = lo; i < hi; i++) {
		double *sp = &R->sp[3 * i];
		sp[0] = (sp[0] - R->u0) * R->S;
		sp[1] = (sp[1] - R->v0) * R->S;
		sp[2] = pin ? 1 / sp[2] : sp[2];
		if (R->at) {
			/* The nearest sample, floor(sp + 0.5), when it is in the
			 * raster: there sp + 0.5 is not negative and its floor is
			 * its truncation (floor is a call without SSE4.1). */
			double hx = sp[0] + 0.5, hy = sp[1] + 0.5;
			int on = hx >= 0 && hy >= 0 && hx < R->w && hy < R->h;
			double x = on ? (double)(long)hx : -1, y = on ? (double)(long)hy : -1;
			on = on && fabs(sp[0] - x) < 1e-3 && fabs(sp[1] - y) < 1e-3;
			R->at[2 * i] = on ? (int32_t)x : -1;
			R->at[2 * i + 1] = on ? (int32_t)y : -1;
		}
		if (R->zv)
			R->zv[i] = vertex_depth(R, i);
	}
}

/* The depths of R's vertices, when its frame was made without them. */
static void depths_chunk(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	struct raster *R = ctx;
	for (size_t i = lo; i < hi; i++)
		R->zv[i] = vertex_depth(R, i);
}

/* A triangle of a range image's grid (its vertices on three corners of a
 * pixel cell, one sample per pixel) covers no sample but its vertices: the
 * raster's depth is the vertex's there (barycentric weights 1, 0, 0). */
static inline int grid_triangle(const struct raster *R, const uint32_t tv[3])
{
	int32_t cx, cy;
	return cell_corners(R->at, tv, &cx, &cy) != 0;
}

/* Triangle f at depth zf on sample s.  Every sample takes the nearest
 * triangle's depth and id (at equal depth the lower id), and the farthest's
 * with idf: a minimum, so the order in which triangles come does not
 * matter.  Without ids, the nearest depth alone (a minimum without a
 * branch: the depths of a range image come in no order a branch could
 * guess). */
static inline void raster_put(struct raster *R, size_t s, float zf, int32_t f)
{
	if (!R->id) {
		R->z[s] = zf < R->z[s] ? zf : R->z[s];
		return;
	}
	if (zf < R->z[s] || (zf == R->z[s] && f < R->id[s])) {
		R->z[s] = zf;
		R->id[s] = f;
	}
	if (R->idf && (zf > R->zf[s] || (zf == R->zf[s] && f < R->idf[s]))) {
		R->zf[s] = zf;
		R->idf[s] = f;
	}
}

/* Vertex v on its sample (with at) at its depth, as triangle f's corner. */
static inline void vertex_splat(struct raster *R, uint32_t v, int32_t f, int ortho)
{
	size_t s = (size_t)R->at[2 * v + 1] * (size_t)R->w + (size_t)R->at[2 * v];
	float zf = R->zv[v];
	if (zf > 0 || ortho)
		raster_put(R, s, zf, f);
}

/* With at: the grid triangles, each a splat of its corners' depths on
 * their samples, in one pass; the others go to the list gen.  Without ids
 * a sample takes the nearest depth whichever triangle brings it, so the
 * pass only marks the corners and each is splatted once after it (a
 * third of the splats).  0 or -1. */
static int raster_grid(struct raster *R, struct fct_err *err)
{
	const struct geo *G = R->G;
	int ortho = R->v->cam.kind == FCT_CAMERA_NONE;
	uint8_t *corner = NULL;   /* without ids: per vertex, 1 when a grid triangle's corner */
	if (!R->id && !(corner = calloc(G->nv ? G->nv : 1, 1)))
		return fct_fail(err, "out of memory");
	int rc = -1;
	for (size_t f = 0; f < G->nt; f++) {
		const uint32_t *tv = &G->tv[3 * f];
		if (!grid_triangle(R, tv)) {
			if (fct_grow((void **)&R->gen, &R->gencap, R->ngen + 1, sizeof *R->gen, err))
				goto done;
			R->gen[R->ngen++] = (uint32_t)f;
			continue;
		}
		if (R->proper && isnan(G->tn[4 * f]))
			continue;
		for (int k = 0; k < 3; k++) {
			if (corner)
				corner[tv[k]] = 1;
			else
				vertex_splat(R, tv[k], (int32_t)f, ortho);
		}
	}
	for (size_t v = 0; corner && v < G->nv; v++)
		if (corner[v])
			vertex_splat(R, (uint32_t)v, -1, ortho);
	rc = 0;
done:
	free(corner);
	return rc;
}

/* Rows lo..hi of the raster: every triangle (with at: those of gen),
 * clipped to them. */
static void raster_rows(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	struct raster *R = ctx;
	const struct geo *G = R->G;
	int pin = R->v->cam.kind == FCT_CAMERA_PINHOLE, cyl = R->v->cam.kind == FCT_CAMERA_CYLINDRICAL,
	    ortho = R->v->cam.kind == FCT_CAMERA_NONE;
	double ylo = (double)lo, yhi = (double)hi - 1, seam = R->S * R->v->cam.width / 2.0;
	const double *sp = R->sp;
	size_t nt = R->at ? R->ngen : G->nt;
	for (size_t i = 0; i < nt; i++) {
		size_t f = R->at ? R->gen[i] : i;
		const uint32_t *tv = &G->tv[3 * f];
		const double *a = &sp[3 * tv[0]], *b = &sp[3 * tv[1]], *c = &sp[3 * tv[2]];
		double vmin = dmin3(a[1], b[1], c[1]), vmax = dmax3(a[1], b[1], c[1]);
		if (!(vmax >= ylo - 1e-9 && vmin <= yhi + 1e-9))
			continue;   /* also NaN: not seen */
		if (R->proper && isnan(G->tn[4 * f]))
			continue;
		double umin = dmin3(a[0], b[0], c[0]), umax = dmax3(a[0], b[0], c[0]);
		if (cyl && umax - umin > seam)
			continue;   /* across the seam */
		double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
		if (!(fabs(area) > 1e-12) || !(umax >= -1 && umin <= R->w))
			continue;   /* also NaN */
		double fu0 = ceil(umin - 1e-9), fu1 = floor(umax + 1e-9);
		double fv0 = ceil(vmin - 1e-9), fv1 = floor(vmax + 1e-9);
		int u0 = fu0 > 0 ? (int)fu0 : 0, u1 = fu1 < R->w - 1 ? (int)fu1 : R->w - 1;
		int v0 = fv0 > ylo ? (int)fv0 : (int)lo, v1 = fv1 < yhi ? (int)fv1 : (int)hi - 1;
		double ia = 1 / area;
		/* Barycentric weights of b and c, affine in the sample. */
		double bx = (c[1] - a[1]) * ia, by = -(c[0] - a[0]) * ia;
		double cx = -(b[1] - a[1]) * ia, cy = (b[0] - a[0]) * ia;
		/* Depth is affine in the image for orthographic views; for
		 * perspective ones 1/depth is (sp holds it). */
		double za = a[2], zb = b[2], zc = c[2];
		for (int y = v0; y <= v1; y++)
			for (int x = u0; x <= u1; x++) {
				double wb = (x - a[0]) * bx + (y - a[1]) * by;
				double wc = (x - a[0]) * cx + (y - a[1]) * cy;
				double wa = 1 - wb - wc;
				if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9)
					continue;
				double z = wa * za + wb * zb + wc * zc;
				if (pin)
					z = 1 / z;
				size_t s = (size_t)y * (size_t)R->w + (size_t)x;
				float zf = (float)z;
				if (!(zf > 0 || ortho))
					continue;
				raster_put(R, s, zf, (int32_t)f);
			}
	}
}

/* G's vertices in the sample coordinates of v with S samples per sensor
 * pixel (fewer when more than max_samples would be needed): R's extent and
 * sp, and at S <= 1 as asked at (and zv unless proper).  0 or -1; R->w is 0 when
 * nothing is seen. */
static int raster_frame(struct raster *R, const struct fct_fuse_view *v, const struct geo *G,
                        double S, int proper, size_t max_samples, int nthreads, struct fct_err *err)
{
	memset(R, 0, sizeof *R);
	double asked = S;   /* halved below when too large: then no grid */
	R->v = v;
	R->G = G;
	R->proper = proper;
	R->nthreads = nthreads;
	fct_pose_invert(v->pose, R->inv);
	if (v->cam.kind == FCT_CAMERA_NONE && !(v->ortho_step > 0))
		return fct_fail(err, "orthographic view without a pixel size");
	R->sp = fct_alloc_array(G->nv ? G->nv : 1, 3 * sizeof *R->sp, err);
	if (!R->sp)
		return -1;
	struct projection *P = malloc(sizeof *P);
	if (!P)
		return fct_fail(err, "out of memory");
	P->R = R;
	for (int t = 0; t < FCT_PAR_MAX; t++)
		P->lo[t][0] = P->lo[t][1] = HUGE_VAL, P->hi[t][0] = P->hi[t][1] = -HUGE_VAL;
	fct_par_run(nthreads, G->nv, 0, project_chunk, P);
	double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
	for (int t = 0; t < FCT_PAR_MAX; t++)
		for (int k = 0; k < 2; k++)
			lo[k] = dmin(P->lo[t][k], lo[k]), hi[k] = dmax(P->hi[t][k], hi[k]);
	free(P);
	if (!(lo[0] <= hi[0] && lo[1] <= hi[1])) {
		R->w = R->h = 0;
		return 0;   /* nothing seen */
	}
	if (v->cam.kind != FCT_CAMERA_NONE) {
		/* Keep to the image, with one image of margin around it. */
		double W = v->cam.width, H = v->cam.height;
		lo[0] = fmax(lo[0], -W), hi[0] = fmin(hi[0], 2 * W);
		lo[1] = fmax(lo[1], -H), hi[1] = fmin(hi[1], 2 * H);
		if (v->cam.kind == FCT_CAMERA_CYLINDRICAL)
			lo[0] = -0.5, hi[0] = W - 0.5;
		if (!(lo[0] <= hi[0] && lo[1] <= hi[1])) {
			R->w = R->h = 0;
			return 0;
		}
	}
	for (;;) {
		/* Offsets keep the samples off a pixel grid's vertices and
		 * diagonals, so that every triangle of it owns a sample. */
		/* Below one sample per pixel (a depth image meshed at a step
		 * of 1 / S pixels) the origin is on a vertex's pixel too. */
		double px = S < 1 ? floor(1 / S + 0.5) : 1;
		R->u0 = px * (floor(lo[0] / px) - 1) + (S > 1 ? 0.25 : 0);
		R->v0 = px * (floor(lo[1] / px) - 1) + (S > 1 ? 0.125 : 0);
		double w = ceil((hi[0] - R->u0) * S) + 2, h = ceil((hi[1] - R->v0) * S) + 2;
		if (w * h <= (double)max_samples) {
			R->w = (int)w, R->h = (int)h;
			break;
		}
		if (S < 1e-3)
			return fct_fail(err, "range image of %.0f x %.0f pixels is too large", w, h);
		S /= 2;
	}
	R->S = S;
	if (S <= 1 && S == asked) {
		/* A true-distance frame is for a pixel grid first, which needs
		 * no depths: raster_fill makes them if it comes to a raster. */
		R->at = fct_alloc_array(G->nv ? G->nv : 1, 2 * sizeof *R->at, err);
		if (!R->at || (!proper && !(R->zv = fct_alloc_array(G->nv ? G->nv : 1, sizeof *R->zv, err))))
			return -1;
	}
	fct_par_run(nthreads, G->nv, 0, samples_chunk, R);
	return 0;
}

/* The raster of R's frame: nearest depths; with R->proper the nearest
 * and farthest triangles too.  0 or -1. */
static int raster_fill(struct raster *R, struct fct_err *err)
{
	size_t n = (size_t)R->w * (size_t)R->h;
	R->z = fct_alloc_array(n, sizeof *R->z, err);
	if (!R->z)
		return -1;
	for (size_t i = 0; i < n; i++)
		R->z[i] = INFINITY;
	R->depth = R->z;
	if (R->proper) {
		R->id = fct_alloc_array(n, sizeof *R->id, err);
		if (!R->id)
			return -1;
		memset(R->id, 0xff, n * sizeof *R->id);
		R->zf = fct_alloc_array(n, sizeof *R->zf, err);
		R->idf = fct_alloc_array(n, sizeof *R->idf, err);
		if (!R->zf || !R->idf)
			return -1;
		for (size_t i = 0; i < n; i++)
			R->zf[i] = -INFINITY;
		memset(R->idf, 0xff, n * sizeof *R->idf);
	}
	if (R->at && !R->zv) {
		if (!(R->zv = fct_alloc_array(R->G->nv ? R->G->nv : 1, sizeof *R->zv, err)))
			return -1;
		fct_par_run(R->nthreads, R->G->nv, 0, depths_chunk, R);
	}
	if (R->at && raster_grid(R, err))
		return -1;
	/* Each thread its own rows: the same raster for any thread count. */
	fct_par_run(R->nthreads, (size_t)R->h, (size_t)R->nthreads, raster_rows, R);
	return 0;
}

/* The raster of G seen by v with S samples per sensor pixel (fewer when
 * more than max_samples would be needed).  0 or -1. */
int fuse_raster_build(struct raster *R, const struct fct_fuse_view *v, const struct geo *G,
                        double S, int proper, size_t max_samples, int nthreads, struct fct_err *err)
{
	if (raster_frame(R, v, G, S, proper, max_samples, nthreads, err))
		return -1;
	return R->w > 0 ? raster_fill(R, err) : 0;
}

/* For projective fusion of a view given as a depth image: the image is
 * the raster, one sample per pixel, sample (x, y) on pixel (x, y); no
 * projection of the mesh and no raster to fill.  0 or -1. */
int fuse_raster_image(struct raster *R, const struct fct_fuse_view *v, struct fct_err *err)
{
	memset(R, 0, sizeof *R);
	if (v->cam.kind == FCT_CAMERA_NONE || v->cam.width < 1 || v->cam.height < 1)
		return fct_fail(err, "a depth image needs a camera with its size");
	R->v = v;
	fct_pose_invert(v->pose, R->inv);
	R->S = 1;
	R->w = v->cam.width, R->h = v->cam.height;
	R->depth = v->depth;
	return 0;
}

/* R's proper triangles as a pixel grid, when they are one (R's frame at
 * one sample per pixel): 1; 0 when they are not; -1 out of memory. */
static int grid_cells(struct raster *R, struct fct_err *err)
{
	const struct geo *G = R->G;
	struct pixgrid *P = &R->grid;
	P->w = (size_t)R->w, P->h = (size_t)R->h, P->at = R->at;
	P->xend = (double)(P->w - 1), P->yend = (double)(P->h - 1);
	size_t n = P->w * P->h;
	P->cell = fct_alloc_array(n, 2 * sizeof *P->cell, err);
	P->diag = calloc(n, 1);
	if (!P->cell || !P->diag) {
		if (P->cell)
			fct_fail(err, "out of memory");
		return -1;
	}
	memset(P->cell, 0xff, 2 * n * sizeof *P->cell);
	/* The half a triangle takes, by the corner of its cell it leaves out
	 * (x + 2 y): its diagonal, and its slot (DOWN: x >= y first; UP:
	 * x + y <= 1 first). */
	static const uint8_t diag[4] = { DIAG_UP, DIAG_DOWN, DIAG_DOWN, DIAG_UP };
	static const uint8_t slot[4] = { 1, 1, 0, 0 };
	/* In locals: the stores to cd (bytes) would have the compiler load
	 * every pointer and size again for each triangle. */
	const float *tn = G->tn;
	const uint32_t *tvs = G->tv;
	const int32_t *at = R->at;
	int32_t *cell = P->cell;
	uint8_t *cd = P->diag;
	size_t nt = G->nt, w = P->w, h = P->h;
	/* The normals are read only when some triangle has none: a range
	 * image's mesh mostly has them all, and the test would bring in 16
	 * bytes per triangle to fail every time.  Without normals (fused by
	 * planes) every triangle takes its half. */
	int some_degenerate = tn && G->nproper < nt;
	for (size_t f = 0; f < nt; f++) {
		if (some_degenerate && isnan(tn[4 * f]))
			continue;
		int32_t cx, cy;
		unsigned corners = cell_corners(at, &tvs[3 * f], &cx, &cy);
		if (!corners || (size_t)cx + 1 >= w || (size_t)cy + 1 >= h)
			goto not_grid;
		int out = __builtin_ctz(~corners & 15);
		size_t c = (size_t)cy * w + (size_t)cx;
		/* Not on a cell split the other way (DIAG_DOWN and DIAG_UP are
		 * bits), nor on a half taken. */
		if ((cd[c] & ~diag[out]) | (cell[2 * c + slot[out]] >= 0))
			goto not_grid;
		cd[c] = diag[out];
		cell[2 * c + slot[out]] = (int32_t)f;
	}
	return 1;
not_grid:
	free(P->cell);
	free(P->diag);
	memset(P, 0, sizeof *P);
	return 0;
}

/* For true distance: the grid of G seen by v when it is one (one sample
 * per v->step pixels, a vertex on each), else the raster at two samples
 * per pixel along each axis, so that every triangle of a range image's
 * grid owns one.  0 or -1. */
int fuse_raster_true(struct raster *R, const struct fct_fuse_view *v, struct geo *G,
                       size_t max_samples, int nthreads, struct fct_err *err)
{
	double S = v->step > 1 ? 1.0 / v->step : 1;
	if (raster_frame(R, v, G, S, 1, max_samples, nthreads, err))
		return -1;
	if (R->w == 0)
		return 0;
	int grid = R->S == S ? grid_cells(R, err) : 0;
	if (grid)
		return grid > 0 ? 0 : -1;
	/* The raster keeps proper triangles only, and the search needs
	 * their normals. */
	if (!G->tn && fuse_geo_normals(G, nthreads, err))
		return -1;
	if (v->cam.kind == FCT_CAMERA_NONE)
		return raster_fill(R, err);
	fuse_raster_free(R);
	return fuse_raster_build(R, v, G, 2, 1, max_samples, nthreads, err);
}

/* The range image is the raster of one sample per pixel, kept to the
 * camera's image (orthographic views: to the mesh, as the raster is). */
int fct_range_image_make(struct fct_range_image *r, const struct fct_fuse_view *v,
                         size_t max_pixels, struct fct_err *err)
{
	memset(r, 0, sizeof *r);
	r->view = *v;
	fct_pose_invert(v->pose, r->inv);
	int ortho = v->cam.kind == FCT_CAMERA_NONE;
	if (!ortho) {
		r->width = v->cam.width;
		r->height = v->cam.height;
		if (r->width < 1 || r->height < 1 ||
		    (double)r->width * (double)r->height > (double)max_pixels)
			return fct_fail(err, "camera of %d x %d pixels: no range image", r->width, r->height);
	}
	struct geo G;
	struct raster R;
	memset(&R, 0, sizeof R);
	if (fuse_geo_build(&G, v->mesh, 0, 1, err))
		return -1;
	int rc = -1;
	if (fuse_raster_build(&R, v, &G, 1, 0, max_pixels, 1, err))
		goto done;
	if (R.w > 0 && R.S != 1) {
		fct_fail(err, "range image of more than %zu pixels: too large", max_pixels);
		goto done;
	}
	if (ortho) {
		if (R.w == 0) {
			fct_fail(err, "empty view");
			goto done;
		}
		r->u0 = R.u0, r->v0 = R.v0;
		r->width = R.w, r->height = R.h;
	}
	size_t np = (size_t)r->width * (size_t)r->height;
	r->range = calloc(np, sizeof *r->range);
	if (!r->range) {
		fct_fail(err, "out of memory");
		goto done;
	}
	/* Pixel (x, y) is raster sample (x - u0, y - v0), u0 and v0 whole
	 * numbers at one sample per pixel (orthographic: the same pixel). */
	int ox = ortho ? 0 : (int)R.u0, oy = ortho ? 0 : (int)R.v0;
	for (int y = 0; y < r->height; y++) {
		int ry = y - oy;
		if (ry < 0 || ry >= R.h)
			continue;
		for (int x = 0; x < r->width; x++) {
			int rx = x - ox;
			if (rx < 0 || rx >= R.w)
				continue;
			float z = R.z[(size_t)ry * (size_t)R.w + (size_t)rx];
			if (z > 0 && z < INFINITY)
				r->range[(size_t)y * (size_t)r->width + (size_t)x] = z;
		}
	}
	rc = 0;
done:
	fuse_raster_free(&R);
	fuse_geo_free(&G);
	if (rc)
		fct_range_image_free(r);
	return rc;
}

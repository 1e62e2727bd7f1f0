/* fusetrue.c - the true signed distance of a view's band voxels: Sun,
 * Paik, Koschan and Abidi, sec. 3 (Hilton's implicit surface; see fuse.h).
 *
 * Nearest points.  Hilton finds each band voxel's nearest point on the
 * view's mesh with a k-D tree.  A range-image mesh is organised by its own
 * sensor, so here the search starts in the view's image.  Each candidate
 * voxel (within the band of its block's box and slab of surface points) is
 * projected, goes to the foot of the perpendicular on the plane of the
 * triangle seen there, and again from the triangle seen at the foot until
 * it stays (on a grid the foot is then the nearest point), then walks
 * downhill on the mesh (across the edge or around the vertex where its
 * closest point lies) to the local minimum.  Voxels in front of the
 * surface they see but out of its band also try the surfaces a band's
 * width away in the image (around silhouettes and in concave corners).
 * The triangle seen at a point of the image: for a range image's grid
 * (every vertex on a pixel centre) that of its pixel cell, which also
 * gives the triangles around a vertex; for other meshes a raster at two
 * samples per pixel (the nearest and the farthest triangle of each
 * sample).  Cost: a few lookups and closest-point tests per candidate
 * voxel, nothing per triangle but the cells or the raster.  The lookups
 * wait on memory more than they compute, so a batch of a block's voxels
 * are projected and their triangles looked up for all of them before any
 * is searched.  Blocks are shared out among threads and each writes only its
 * own results, so the volume is the same for any thread count. */
#include "fusion/fusepriv.h"

#include "geom/geom.h"

/* The faces around vertex v: *f[0 .. count), in face order unless the
 * grid has them (then in the order of its cells). */
static inline size_t ring(const struct geo *G, uint32_t v, uint32_t buf[8], const uint32_t **f)
{
	const struct pixgrid *P = G->grid;
	if (!P) {
		*f = &G->vf[G->vfs[v]];
		return G->vfs[v + 1] - G->vfs[v];
	}
	*f = buf;
	int32_t x = P->at[2 * (size_t)v], y = P->at[2 * (size_t)v + 1];
	if (x < 0)
		return 0;
	size_t n = 0;
	for (int32_t cy = y - 1; cy <= y; cy++)
		for (int32_t cx = x - 1; cx <= x; cx++) {
			if (cx < 0 || cy < 0 || (size_t)cx + 1 >= P->w || (size_t)cy + 1 >= P->h)
				continue;
			const int32_t *c = &P->cell[2 * ((size_t)cy * P->w + (size_t)cx)];
			for (int k = 0; k < 2; k++) {
				if (c[k] < 0)
					continue;
				const uint32_t *w = &G->tv[3 * (size_t)c[k]];
				if (w[0] == v || w[1] == v || w[2] == v)
					buf[n++] = (uint32_t)c[k];
			}
		}
	return n;
}

/* The grid's faces that may have edge (a, b): those of the cells on
 * either side of it (of the one it splits, for a diagonal).  Their count. */
static inline size_t grid_edge(const struct geo *G, uint32_t a, uint32_t b, uint32_t buf[4])
{
	const struct pixgrid *P = G->grid;
	int32_t ax = P->at[2 * (size_t)a], ay = P->at[2 * (size_t)a + 1];
	int32_t bx = P->at[2 * (size_t)b], by = P->at[2 * (size_t)b + 1];
	if (ax < 0 || bx < 0)
		return 0;
	int32_t x = ax < bx ? ax : bx, y = ay < by ? ay : by;
	/* Cells (x, y) and the one before it across the edge: along x for a
	 * vertical edge, along y for a horizontal one; none for a diagonal. */
	int32_t cx[2] = { x, ax == bx ? x - 1 : x }, cy[2] = { y, ay == by ? y - 1 : y };
	int ncell = ax != bx && ay != by ? 1 : 2;
	size_t n = 0;
	for (int i = 0; i < ncell; i++) {
		if (cx[i] < 0 || cy[i] < 0 || (size_t)cx[i] + 1 >= P->w || (size_t)cy[i] + 1 >= P->h)
			continue;
		const int32_t *c = &P->cell[2 * ((size_t)cy[i] * P->w + (size_t)cx[i])];
		for (int k = 0; k < 2; k++)
			if (c[k] >= 0)
				buf[n++] = (uint32_t)c[k];
	}
	return n;
}

static inline void tri_normal(const struct geo *G, size_t t, double n[3])
{
	const float *tn = &G->tn[4 * t];
	n[0] = tn[0], n[1] = tn[1], n[2] = tn[2];
}

static inline double tri_closest(const struct geo *G, size_t t, const double x[3], double q[3],
                                 enum fct_tri_region *r)
{
	const uint32_t *v = &G->tv[3 * t];
	return fct_closest_on_triangle_nd(x, &G->xyz[3 * v[0]], &G->xyz[3 * v[1]], &G->xyz[3 * v[2]], q, r);
}

/* The triangle across edge (a, b) of t: >= 0; -1 on a border (no other
 * proper triangle has that edge); -2 when several have it. */
static int32_t across(const struct geo *G, size_t t, uint32_t a, uint32_t b)
{
	int32_t o = -1;
	uint32_t buf[8];
	const uint32_t *fa;
	size_t n = G->grid ? grid_edge(G, a, b, buf) : ring(G, a, buf, &fa);
	if (G->grid)
		fa = buf;
	for (size_t i = 0; i < n; i++) {
		uint32_t f = fa[i];
		if (f == t || isnan(G->tn[4 * (size_t)f]))
			continue;
		const uint32_t *w = &G->tv[3 * (size_t)f];
		if ((w[0] == b || w[1] == b || w[2] == b) && (w[0] == a || w[1] == a || w[2] == a)) {
			if (o != -1)
				return -2;
			o = (int32_t)f;
		}
	}
	return o;
}

/* 1 when vertex v is on a border; else 0 and its angle-weighted
 * pseudo-normal (Baerentzen and Aanaes) in vn. */
static int vertex_normal(const struct geo *G, uint32_t v, double vn[3])
{
	vn[0] = vn[1] = vn[2] = 0;
	uint32_t buf[8];
	const uint32_t *fv;
	size_t n = ring(G, v, buf, &fv);
	for (size_t i = 0; i < n; i++) {
		uint32_t f = fv[i];
		if (isnan(G->tn[4 * (size_t)f]))
			continue;
		const uint32_t *w = &G->tv[3 * (size_t)f];
		int k = w[0] == v ? 0 : w[1] == v ? 1 : 2;
		uint32_t qv = w[(k + 1) % 3], rv = w[(k + 2) % 3];
		if (across(G, f, v, qv) == -1 || across(G, f, rv, v) == -1)
			return 1;
		const double *p = &G->xyz[3 * v], *q = &G->xyz[3 * qv], *r = &G->xyz[3 * rv];
		double u[3], s[3];
		fct_v3_sub(u, q, p);
		fct_v3_sub(s, r, p);
		double c = fct_v3_dot(u, s) / sqrt(fct_v3_dot(u, u) * fct_v3_dot(s, s));
		double ang = acos(c < -1 ? -1 : c > 1 ? 1 : c);
		double n[3];
		tri_normal(G, f, n);
		fct_v3_axpy(vn, vn, ang, n);
	}
	return 0;
}

/* Walk from triangle t downhill to the triangle nearest x: across the edge
 * or around the vertex where the closest point lies.  Returns the triangle;
 * *d2 its squared distance, q the point, *r its region; -1 when it is
 * still going after WALK_STEPS steps, or when t is already farther than
 * the band (squared: band2).  Walks from out of the band crawl along
 * borders and silhouettes a small triangle a step, trying every triangle
 * around each vertex they pass: on the room at 2 cm they cost 17% of the
 * fusion for 0.55% of its voxels, all at the band's edge, and the bunny
 * comes out nearer its reference without them (0.0628 / 0.0467 mm, not
 * 0.0641 / 0.0482). */
enum { WALK_STEPS = 12 };

static int32_t walk(const struct geo *G, int32_t t, const double x[3], double band2, double *d2out,
                    double q[3], enum fct_tri_region *r)
{
	double best = tri_closest(G, (size_t)t, x, q, r);
	if ((float)best > band2)
		return -1;
	for (int step = 0;; step++) {
		int32_t next = -1;
		double nd = best, nq[3];
		enum fct_tri_region nr = *r;
		const uint32_t *tv = &G->tv[3 * (size_t)t];
		if (*r == FCT_TRI_AB || *r == FCT_TRI_BC || *r == FCT_TRI_CA) {
			int k = *r == FCT_TRI_AB ? 0 : *r == FCT_TRI_BC ? 1 : 2;
			int32_t o = across(G, (size_t)t, tv[k], tv[(k + 1) % 3]);
			if (o >= 0) {
				double d = tri_closest(G, (size_t)o, x, nq, &nr);
				if (d < nd)
					nd = d, next = o;
			}
		} else if (*r == FCT_TRI_A || *r == FCT_TRI_B || *r == FCT_TRI_C) {
			uint32_t v = tv[*r == FCT_TRI_A ? 0 : *r == FCT_TRI_B ? 1 : 2];
			uint32_t buf[8];
			const uint32_t *fv;
			size_t n = ring(G, v, buf, &fv);
			for (size_t i = 0; i < n; i++) {
				uint32_t o = fv[i];
				if ((int32_t)o == t || isnan(G->tn[4 * (size_t)o]))
					continue;
				double qq[3];
				enum fct_tri_region rr;
				double d = tri_closest(G, o, x, qq, &rr);
				if (d < nd) {
					nd = d, next = (int32_t)o, nr = rr;
					memcpy(nq, qq, sizeof qq);
				}
			}
		}
		if (next < 0)
			break;
		if (step == WALK_STEPS)
			return -1;
		t = next, best = nd, *r = nr;
		memcpy(q, nq, sizeof nq);
	}
	*d2out = best;
	return t;
}

double fuse_view_weight(const struct fct_fuse_view *v, const struct fct_fuse_params *p,
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

/* The view's noise at triangle tv as a weight: the mean sigma of its
 * corners. */
static inline double noise_weight(const struct fctx *F, const uint32_t *tv)
{
	const float *s = F->v->sigma;
	return sigma_weight(((double)s[tv[0]] + s[tv[1]] + s[tv[2]]) / 3, F->vox);
}

/* The triangle seen at sample (x, y), or at one of its 8 neighbours. */
static int32_t seen_at(const struct raster *R, const int32_t *id, double x, double y)
{
	int32_t t = seen(R, id, x, y);
	for (int dy = -1; dy <= 1 && t < 0; dy++)
		for (int dx = -1; dx <= 1 && t < 0; dx++)
			t = seen(R, id, x + dx, y + dy);
	return t;
}

static inline double plane_dist(const struct geo *G, int32_t t, const double x[3])
{
	const float *n = &G->tn[4 * (size_t)t];
	return x[0] * n[0] + x[1] * n[1] + x[2] * n[2] - n[3];
}

/* The triangle under sample point (px, py), by walking across the edges
 * of the image-space triangles from t (t itself when that fails). */
static int32_t locate(const struct raster *R, int32_t t, double px, double py)
{
	const struct geo *G = R->G;
	for (int step = 0; step < 8; step++) {
		const uint32_t *tv = &G->tv[3 * (size_t)t];
		const double *p[3] = { &R->sp[3 * tv[0]], &R->sp[3 * tv[1]], &R->sp[3 * tv[2]] };
		double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
		int out = -1;
		double worst = 0;
		for (int k = 0; k < 3; k++) {
			const double *a = p[k], *b = p[(k + 1) % 3];
			double e = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) * area;
			if (e < worst)
				worst = e, out = k;
		}
		if (out < 0)
			return t;
		int32_t o = across(G, (size_t)t, tv[out], tv[(out + 1) % 3]);
		if (o < 0)
			return t;
		t = o;
	}
	return t;
}

/* The search for the triangle nearest x, from triangle t seen at x's
 * sample in layer id: to the foot of x on the plane of t, and again from
 * the triangle seen at the foot, until it stays; then downhill on the
 * mesh.  Its state between the steps of the first part, so that a
 * batch of voxels can take those steps side by side (search_step's chain of
 * dependent loads and a division is long, the voxels' chains are
 * independent). */
struct foot {
	double s;                /* x's distance to the plane of t */
	double f[3], sx, sy;     /* the foot on that plane and its sample */
	int32_t t;               /* -1: out of the band, given up */
	int32_t back;            /* the triangle before t */
	int8_t it, stays, done;
};

static inline void search_begin(const struct fctx *F, int32_t t, const double x[3], struct foot *S)
{
	S->s = plane_dist(F->G, t, x);
	S->t = t, S->back = -1, S->it = 0, S->stays = 0, S->done = 0;
	/* In front of the surface seen, the distance to its plane bounds the
	 * distance (for convex surfaces); behind it the nearest point may be
	 * anywhere, around a silhouette. */
	if (S->s > F->band + 2 * F->vox)
		S->t = -1, S->done = 1;
}

/* A move in three parts, so that a batch of voxels can ask for the memory
 * of the next part before any of them uses it.  step_foot: the foot on
 * the plane of t and its sample (0 and S->done when it has none). */
static inline int step_foot(const struct fctx *F, const double x[3], struct foot *S)
{
	double depth;
	const float *n = &F->G->tn[4 * (size_t)S->t];
	double *f = S->f, s = S->s;
	f[0] = x[0] - s * n[0], f[1] = x[1] - s * n[1], f[2] = x[2] - s * n[2];
	S->done = 1;
	return sample_of(F->R, f, &S->sx, &S->sy, &depth);
}

/* step_seen: the triangle seen at the foot's sample (S->done when none or
 * the same: S->stays then); 1 when it is another one. */
static inline int step_seen(const struct fctx *F, const int32_t *id, struct foot *S, int32_t *ts)
{
	*ts = seen(F->R, id, S->sx, S->sy);
	return !(*ts < 0 || (S->stays = *ts == S->t));
}

/* step_move: onto ts, unless its plane is farther (off a silhouette);
 * S->done when the moves end: after 8, or on a move back to the triangle
 * before (two triangles whose feet fall on each other, as across a fold
 * of the noise: the moves would go back and forth to the eighth, and the
 * walk finds the nearer point from either). */
static inline void step_move(const struct fctx *F, const double x[3], struct foot *S, int32_t ts)
{
	double s2 = plane_dist(F->G, ts, x);
	if (fabs(s2) > fabs(S->s) + F->vox)
		return;
	S->done = ++S->it == 8 || ts == S->back;
	S->back = S->t, S->t = ts, S->s = s2;
}

/* One move to the triangle seen at the foot; S->done when it stays or the
 * moves end. */
static inline void search_step(const struct fctx *F, const int32_t *id, const double x[3],
                               struct foot *S)
{
	int32_t ts;
	if (step_foot(F, x, S) && step_seen(F, id, S, &ts))
		step_move(F, x, S, ts);
}

/* The triangle nearest x from a search's state, or -1 when x is out of
 * the band. */
static int32_t search_end(const struct fctx *F, const int32_t *id, const double x[3], struct foot *S,
                          double *d2, double q[3], enum fct_tri_region *r)
{
	if (S->t < 0)
		return -1;
	while (!S->done)
		search_step(F, id, x, S);
	double band = F->band, s = S->s;
	int32_t t = S->t;
	/* Far from the plane seen, on either side: the walk would start out
	 * of the band and give up (surfaces behind another are the far
	 * layer's); this spares it, and locate. */
	if (fabs(s) > band + 0.5 * F->vox)
		return -1;
	if (S->stays && F->R->grid.cell) {
		/* A grid's cell is exact: the foot is on t, so it is the point
		 * of t nearest x, inside it, and a walk would stop there. */
		*d2 = s * s, *r = FCT_TRI_FACE;
		memcpy(q, S->f, sizeof S->f);
		return *d2 <= band * band ? t : -1;
	}
	/* A raster's sample is the nearest one, not the triangle under the
	 * foot: find that one in the image first (cheaper than walking
	 * around vertices in space). */
	if (S->stays)
		t = locate(F->R, t, S->sx, S->sy);
	t = walk(F->G, t, x, band * band, d2, q, r);
	return t >= 0 && *d2 <= band * band ? t : -1;
}

static int32_t search(const struct fctx *F, const int32_t *id, int32_t t, const double x[3],
                      double *d2, double q[3], enum fct_tri_region *r)
{
	struct foot S;
	search_begin(F, t, x, &S);
	return search_end(F, id, x, &S, d2, q, r);
}

/* The point of a view's mesh nearest a voxel: its triangle (-1: none in
 * the band), squared distance, the point and its region there. */
struct hit {
	int32_t t;
	enum fct_tri_region r;
	double d2, q[3];
};

/* h: the nearer of h and the search from triangle ts in layer id. */
static void search_nearer(const struct fctx *F, const int32_t *id, int32_t ts, const double x[3],
                          struct hit *h)
{
	struct hit o;
	o.t = search(F, id, ts, x, &o.d2, o.q, &o.r);
	if (o.t >= 0 && (h->t < 0 || o.d2 < h->d2))
		*h = o;
}

/* A batch of a block's voxels, in stages: each voxel is projected and the
 * sample it falls on asked for; then the triangle seen there is looked up
 * and its plane and corners asked for; then the voxels are searched; those
 * in front of the surface seen but out of its band probe beside it; then
 * the distances are put.  Each search's or probe's loads depend on each
 * other, the voxels' do not, so the memory is read for many voxels at
 * once. */
struct seen {
	double x[3], sx, sy;
	int32_t t;               /* -1: nothing seen (or out of the clip box) */
	int16_t l;               /* the voxel in its block */
	struct foot S;           /* the search from t */
	struct hit h;            /* its outcome */
};

/* Voxels taken through the stages together: enough that many loads are
 * in flight at once, few enough that their states (152 bytes each, 19 KB)
 * stay in the first-level cache from one stage to the next.  A whole block
 * (512, 78 KB) did not: on the room's four depth images at 2 cm, by
 * cachegrind, half of the run's first-level misses were these states (41
 * M in all, 21 M in batches).  The same voxels, searched alike, so the
 * same volume. */
enum { TRUE_BATCH = 128 };

/* e's search, ended, and the far layer's where there is one (the far side
 * of a closed object, a surface behind another). */
static void search_seen(const struct fctx *F, struct seen *e)
{
	const struct raster *R = F->R;
	struct hit *h = &e->h;
	h->t = search_end(F, R->id, e->x, &e->S, &h->d2, h->q, &h->r);
	int32_t tf = R->idf ? seen_at(R, R->idf, e->sx, e->sy) : -1;
	if (tf >= 0 && tf != e->t)
		search_nearer(F, R->idf, tf, e->x, h);
}

/* Probes: a voxel in front of the surface seen but out of its band may be
 * near a surface beside, around a silhouette or in a concave corner.  It
 * looks for one along the image's four axes, half a band's width away and
 * then a band's: the first other surface met in a direction is the one to
 * search (the one farther out is mostly the same surface again, and most
 * probers find nothing, so a probe that saw another surface ends that
 * direction).  The samples are asked for, then the triangles seen there
 * with their planes, for all of a batch's probers, before any is used. */
enum { PROBES = 8 };   /* 4 directions, 2 reaches */

struct prober {
	struct seen *e;
	double s0;               /* e's distance to the plane of the triangle it sees */
	double px[PROBES], py[PROBES];
	int32_t ts[PROBES];      /* the triangle seen at each probe */
};

/* p's probe samples; 0 when the band's reach leaves the view. */
static int probe_samples(const struct fctx *F, struct prober *p)
{
	const struct seen *e = p->e;
	const double *P = F->v->pose, *x = e->x;
	double r = F->band + F->vox;
	double end[3] = { x[0] + r * P[0], x[1] + r * P[4], x[2] + r * P[8] }, ex, ey, ed;
	if (!sample_of(F->R, end, &ex, &ey, &ed))
		return 0;
	double rp = hypot(ex - e->sx, ey - e->sy);
	static const double dir[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
	for (int di = 0; di < 4; di++)
		for (int halves = 1; halves <= 2; halves++) {
			double reach = 0.5 * halves * rp;
			int k = 2 * di + halves - 1;
			p->px[k] = e->sx + reach * dir[di][0], p->py[k] = e->sy + reach * dir[di][1];
			prefetch_seen(F->R, p->px[k], p->py[k]);
		}
	return 1;
}

/* The triangles seen at p's probes, and their planes asked for. */
static void probe_look(const struct fctx *F, struct prober *p)
{
	for (int k = 0; k < PROBES; k++) {
		p->ts[k] = seen(F->R, F->R->id, p->px[k], p->py[k]);
		if (p->ts[k] >= 0)
			__builtin_prefetch(&F->G->tn[4 * (size_t)p->ts[k]]);
	}
}

/* In each direction, the first surface other than p's own, searched
 * when its plane is within the band. */
static void probe_search(const struct fctx *F, struct prober *p)
{
	struct seen *e = p->e;
	for (int di = 0; di < 4; di++)
		for (int halves = 1; halves <= 2; halves++) {
			int32_t ts = p->ts[2 * di + halves - 1];
			if (ts < 0)
				continue;
			double sp = plane_dist(F->G, ts, e->x);
			if (ts == e->t || fabs(sp - p->s0) <= F->vox)
				continue;   /* the surface seen: maybe another farther out */
			if (fabs(sp) <= F->band)
				search_nearer(F, F->R->id, ts, e->x, &e->h);
			break;
		}
}

/* The probes of a batch's voxels V[0 .. n) that need them. */
static void probe_block(const struct fctx *F, struct seen *V, int n)
{
	struct prober P[TRUE_BATCH];
	int np = 0;
	for (int v = 0; v < n; v++) {
		struct seen *e = &V[v];
		if (e->t < 0 || e->h.t >= 0)
			continue;
		double s0 = plane_dist(F->G, e->t, e->x);
		if (!(s0 > 0))
			continue;
		P[np].e = e, P[np].s0 = s0;
		np += probe_samples(F, &P[np]);
	}
	for (int i = 0; i < np; i++)
		probe_look(F, &P[i]);
	for (int i = 0; i < np; i++)
		probe_search(F, &P[i]);
}

/* Voxel l of block b, at x, whose nearest point is h: its signed distance
 * (by the normal there: the face's, or the mean of the faces' at an edge
 * or a corner) into b, unless that point is on a border. */
static void put_true(const struct fctx *F, struct sblock *b, int l, const double x[3], const struct hit *h)
{
	const struct geo *G = F->G;
	int32_t t = h->t;
	enum fct_tri_region r = h->r;
	double n[3], xq[3];
	tri_normal(G, t, n);
	fct_v3_sub(xq, x, h->q);
	double d;
	if (r == FCT_TRI_FACE) {
		d = fct_v3_dot(xq, n);
	} else if (r == FCT_TRI_A || r == FCT_TRI_B || r == FCT_TRI_C) {
		uint32_t vv = G->tv[3 * (size_t)t + (r == FCT_TRI_A ? 0 : r == FCT_TRI_B ? 1 : 2)];
		double vn[3];
		if (vertex_normal(G, vv, vn)) {
			b->nborder++;
			return;
		}
		d = copysign(sqrt(h->d2), fct_v3_dot(xq, vn));
	} else {
		int e = r == FCT_TRI_AB ? 0 : r == FCT_TRI_BC ? 1 : 2;
		const uint32_t *tv = &G->tv[3 * (size_t)t];
		int32_t o = across(G, (size_t)t, tv[e], tv[(e + 1) % 3]);
		if (o == -1) {
			b->nborder++;
			return;
		}
		double pn[3];
		if (o >= 0) {
			tri_normal(G, o, pn);
			fct_v3_add(pn, n, pn);
		} else {
			memcpy(pn, n, sizeof pn);
		}
		d = copysign(sqrt(h->d2), fct_v3_dot(xq, pn));
	}
	/* The kept band's extra thousandth of a voxel is not a distance. */
	d = dmax(-F->p->band, dmin(d, F->p->band));
	double w = fuse_view_weight(F->v, F->p, h->q, n);
	if (F->v->sigma)
		w *= noise_weight(F, G->tv + 3 * (size_t)t);
	put(b, l, (float)d, (float)w);
}

/* Voxels V[0 .. n) of block b, a batch: their stages one after another
 * (struct seen). */
static void true_batch(const struct fctx *F, struct sblock *b, struct seen *V, int n)
{
	const struct raster *R = F->R;
	const struct geo *G = F->G;
	for (int v = 0; v < n; v++) {
		struct seen *e = &V[v];
		e->t = seen_at(R, R->id, e->sx, e->sy);
		if (e->t >= 0) {
			__builtin_prefetch(&G->tn[4 * (size_t)e->t]);
			__builtin_prefetch(&G->tv[3 * (size_t)e->t]);
		}
	}
	for (int v = 0; v < n; v++)
		if (V[v].t >= 0)
			search_begin(F, V[v].t, V[v].x, &V[v].S);
	/* Every move of the searches here, the voxels still moving (act)
	 * side by side, until none is: on noisy views many move more than
	 * twice, and a move taken alone (search_end) waits on each of its
	 * loads in turn. */
	int act[TRUE_BATCH], na = 0;
	for (int v = 0; v < n; v++)
		if (V[v].t >= 0 && !V[v].S.done)
			act[na++] = v;
	while (na > 0) {
		int8_t go[TRUE_BATCH];
		int32_t ts[TRUE_BATCH];
		for (int i = 0; i < na; i++) {
			struct seen *e = &V[act[i]];
			go[i] = step_foot(F, e->x, &e->S);
			if (go[i])
				prefetch_seen(R, e->S.sx, e->S.sy);
		}
		for (int i = 0; i < na; i++) {
			struct seen *e = &V[act[i]];
			go[i] = go[i] && step_seen(F, R->id, &e->S, &ts[i]);
			if (go[i])
				__builtin_prefetch(&G->tn[4 * (size_t)ts[i]]);
		}
		int still = 0;
		for (int i = 0; i < na; i++) {
			struct seen *e = &V[act[i]];
			if (go[i])
				step_move(F, e->x, &e->S, ts[i]);
			if (!e->S.done)
				act[still++] = act[i];
		}
		na = still;
	}
	for (int v = 0; v < n; v++)
		if (V[v].t >= 0)
			search_seen(F, &V[v]);
	probe_block(F, V, n);
	for (int v = 0; v < n; v++)
		if (V[v].t >= 0 && V[v].h.t >= 0)
			put_true(F, b, V[v].l, V[v].x, &V[v].h);
}

void fuse_true_blocks(void *ctx, size_t lo, size_t hi, int worker)
{
	(void)worker;
	const struct fctx *F = ctx;
	const struct raster *R = F->R;
	double vox = F->vox;
	struct seen V[TRUE_BATCH];
	for (size_t bi = lo; bi < hi; bi++) {
		struct sblock *b = F->s->blk[bi];
		int n = 0;
		/* The fuse_candidates, by the bits of their rows (all in the box). */
		for (int z = b->lo[2]; z <= b->hi[2]; z++)
			for (int y = b->lo[1]; y <= b->hi[1]; y++)
				for (unsigned row = b->row[y + FCT_VOXBLOCK * z]; row; row &= row - 1) {
					int xx = __builtin_ctz(row);
					int32_t i = b->bx * FCT_VOXBLOCK + xx, j = b->by * FCT_VOXBLOCK + y,
					        k = b->bz * FCT_VOXBLOCK + z;
					struct seen *e = &V[n];
					double depth;
					e->x[0] = i * vox, e->x[1] = j * vox, e->x[2] = k * vox;
					if (!in_clip(F->p, i, j, k) || !sample_of(R, e->x, &e->sx, &e->sy, &depth))
						continue;
					prefetch_seen(R, e->sx, e->sy);
					e->l = (int16_t)(xx + FCT_VOXBLOCK * (y + FCT_VOXBLOCK * z));
					if (++n == TRUE_BATCH)
						true_batch(F, b, V, n), n = 0;
				}
		true_batch(F, b, V, n);
	}
}

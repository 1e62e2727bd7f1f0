/* mcubes.c - marching cubes over the sparse block grid.
 *
 * Lorensen and Cline, "Marching Cubes: A High Resolution 3D Surface
 * Construction Algorithm", SIGGRAPH 1987; ambiguous faces by the asymptotic
 * decider (Nielson and Hamann, "The Asymptotic Decider", Visualization
 * 1991); the surface-extraction step of Sun et al. Sec. 3.
 *
 * No case table is copied: the table is derived at run time from the rule
 * the whole extraction follows.  On each cube face the crossings are joined
 * by segments (two crossings: one segment; four: the face is ambiguous and
 * the segments cut off the two corners of the sign that is not joined),
 * each segment directed so that, seen from outside the cube, the positive
 * side is on its left.  Every crossing then has one segment in and one out,
 * the segments close into loops, and a loop triangulated as a fan (or
 * around its centroid, when it uses two segments of one face, so that no
 * fan diagonal can lie on a face and meet the neighbour's) gives triangles
 * facing the positive side.  The 256 sign patterns with every ambiguous face
 * joining its positive diagonal are tabulated; a cube whose decider says
 * otherwise on some face is built by the same routine on the spot.
 *
 * Two passes over the blocks.  Pass 1 reads each block and its upper
 * neighbours into 9x9 rows of sign and "observed" bits, marks the crossing
 * lattice edges each voxel owns (the edges from it towards +x, +y, +z) in
 * three 512-bit masks, and creates their vertices, numbered by block, axis
 * and voxel; a vertex's number is then the block's base plus a popcount in
 * its masks, so pass 2 finds the vertices of a cube's twelve edges, in its
 * own block or the upper neighbours, without any per-edge table.  Pass 2
 * emits the triangles of every active cube.  Vertices that no triangle
 * uses (crossings at the edge of the observed region) are dropped last. */
#include "mcubes.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cube geometry ----------------------------------------------------------- */

/* Corner c is at (c & 1, c >> 1 & 1, c >> 2 & 1).  Edge e has axis e / 4
 * and its lower end at the corner given by edge_lo; faces f = 2 * axis +
 * side, side 1 being the face at coordinate 1. */
struct geom {
	uint8_t edge_lo[12], edge_hi[12];
	uint8_t face_edges[6][4];
	uint8_t face_corners[6][4];     /* in cyclic order */
};

static int corner_coord(int c, int a)
{
	return (c >> a) & 1;
}

static void geom_init(struct geom *G)
{
	for (int e = 0; e < 12; e++) {
		int a = e / 4, q = e % 4, lo;
		if (a == 0)
			lo = 2 * (q & 1) + 4 * (q >> 1);
		else if (a == 1)
			lo = (q & 1) + 4 * (q >> 1);
		else
			lo = (q & 1) + 2 * (q >> 1);
		G->edge_lo[e] = (uint8_t)lo;
		G->edge_hi[e] = (uint8_t)(lo | 1 << a);
	}
	for (int f = 0; f < 6; f++) {
		int a = f / 2, s = f % 2, n = 0;
		for (int e = 0; e < 12; e++)
			if (e / 4 != a && corner_coord(G->edge_lo[e], a) == s)
				G->face_edges[f][n++] = (uint8_t)e;
		/* cyclic corner order: the two other axes u < v, (0,0) (1,0) (1,1) (0,1) */
		int u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
		static const int cu[4] = { 0, 1, 1, 0 }, cv[4] = { 0, 0, 1, 1 };
		for (int k = 0; k < 4; k++)
			G->face_corners[f][k] = (uint8_t)(s << a | cu[k] << u | cv[k] << v);
	}
}

/* A cube's contour: loops of crossed edges, in order. */
struct mc_case {
	uint8_t nloops;
	uint8_t len[4];
	uint8_t centre[4];      /* 1: triangulate around the loop's centroid */
	uint8_t edge[12];       /* the loops' edges back to back */
	uint8_t amb;            /* faces with four crossings */
	uint16_t emask;         /* crossed edges */
};

/* Build the contour of sign pattern cfg (bit c set: corner c negative),
 * joining the negative diagonal on the ambiguous faces in joinneg (a face
 * mask) and the positive one on the others.  Aborts on an inconsistency
 * (the rule guarantees one segment in and one out at each crossing). */
static void build_case(const struct geom *G, int cfg, int joinneg, struct mc_case *mc)
{
	memset(mc, 0, sizeof *mc);
	int next[12], segface[12];
	for (int e = 0; e < 12; e++) {
		next[e] = segface[e] = -1;
		if (((cfg >> G->edge_lo[e]) ^ (cfg >> G->edge_hi[e])) & 1)
			mc->emask |= (uint16_t)(1u << e);
	}
	for (int f = 0; f < 6; f++) {
		int a = f / 2, s = f % 2, cross[4], nc = 0;
		for (int k = 0; k < 4; k++)
			if (mc->emask >> G->face_edges[f][k] & 1)
				cross[nc++] = G->face_edges[f][k];
		int seg[2][2], nseg = 0;
		if (nc == 2) {
			seg[0][0] = cross[0], seg[0][1] = cross[1], nseg = 1;
		} else if (nc == 4) {
			mc->amb |= (uint8_t)(1u << f);
			int cutneg = !(joinneg >> f & 1);       /* joined positive: cut negatives off */
			for (int k = 0; k < 4; k++) {
				int c = G->face_corners[f][k];
				if ((cfg >> c & 1) != cutneg)
					continue;
				int m = 0;
				for (int j = 0; j < 4; j++)
					if (G->edge_lo[cross[j]] == c || G->edge_hi[cross[j]] == c)
						seg[nseg][m++] = cross[j];
				if (m != 2)
					abort();
				nseg++;
			}
			if (nseg != 2)
				abort();
		} else if (nc != 0) {
			abort();
		}
		for (int i = 0; i < nseg; i++) {
			int u = seg[i][0], v = seg[i][1], r;
			if (G->edge_lo[u] == G->edge_lo[v] || G->edge_lo[u] == G->edge_hi[v])
				r = G->edge_lo[u];
			else if (G->edge_hi[u] == G->edge_lo[v] || G->edge_hi[u] == G->edge_hi[v])
				r = G->edge_hi[u];
			else
				r = G->edge_lo[u];
			int pu[3], pv[3], n[3] = { 0, 0, 0 }, d[3], rr[3], left[3];
			for (int k = 0; k < 3; k++) {
				pu[k] = corner_coord(G->edge_lo[u], k) + corner_coord(G->edge_hi[u], k);
				pv[k] = corner_coord(G->edge_lo[v], k) + corner_coord(G->edge_hi[v], k);
				d[k] = pv[k] - pu[k];
				rr[k] = 2 * corner_coord(r, k) - pu[k];
			}
			n[a] = s ? 1 : -1;
			left[0] = n[1] * d[2] - n[2] * d[1];
			left[1] = n[2] * d[0] - n[0] * d[2];
			left[2] = n[0] * d[1] - n[1] * d[0];
			int side = left[0] * rr[0] + left[1] * rr[1] + left[2] * rr[2];
			if (side == 0)
				abort();
			int rpos = !(cfg >> r & 1);
			if ((side > 0) != rpos)
				u = seg[i][1], v = seg[i][0];
			if (next[u] >= 0)
				abort();
			next[u] = v;
			segface[u] = f;
		}
	}
	int seen = 0, n = 0;
	for (int e = 0; e < 12; e++) {
		if (!(mc->emask >> e & 1) || (seen >> e & 1))
			continue;
		if (mc->nloops >= 4)
			abort();
		int len = 0, faces = 0, centre = 0;
		for (int x = e; !(seen >> x & 1); x = next[x]) {
			if (x < 0)
				abort();
			seen |= 1 << x;
			mc->edge[n + len++] = (uint8_t)x;
			centre |= faces >> segface[x] & 1;
			faces |= 1 << segface[x];
		}
		if (len < 3 || next[mc->edge[n + len - 1]] != e)
			abort();
		mc->len[mc->nloops] = (uint8_t)len;
		mc->centre[mc->nloops] = (uint8_t)centre;
		mc->nloops++;
		n += len;
	}
}

/* Pass-1 results of one block ------------------------------------------------ */

struct aux {
	uint64_t bits[24];      /* crossing edges owned, axis * 8 + z, bit x + 8 y */
	uint32_t pre[24];       /* vertices before each word, from the block's base */
	uint32_t base;          /* first vertex of the block */
	uint16_t neg[9][9];     /* [z][y]: bit x (0..8) set when negative */
	uint8_t active[8][8];   /* [z][y]: bit x set when cube (x,y,z) is extracted */
	int any_active;
};

struct ctx {
	const struct fct_voxgrid *g;
	float thr;
	int colour;
	double voxel;
	const int32_t *lo, *hi;
	struct geom G;
	struct mc_case table[256];

	/* the current block and its 26 neighbours, looked up on demand */
	const struct fct_voxblock *nb[27];
	unsigned nb_done;
	int32_t bx, by, bz;

	/* vertices */
	size_t nv, vcap, ncap, ccap;
	double *xyz;
	float *nrm;
	uint8_t *rgb;
	/* triangles */
	size_t nt, tcap;
	uint32_t *tri;

	struct fct_mcubes_stats st;
};

static void ctx_block(struct ctx *c, const struct fct_voxblock *b)
{
	c->bx = b->bx, c->by = b->by, c->bz = b->bz;
	c->nb_done = 1u << 13;
	memset(c->nb, 0, sizeof c->nb);
	c->nb[13] = b;
}

/* Neighbour block (dx, dy, dz) in -1..1 of the current block. */
static inline const struct fct_voxblock *ctx_nb(struct ctx *c, int dx, int dy, int dz)
{
	int k = (dx + 1) + 3 * ((dy + 1) + 3 * (dz + 1));
	if (!(c->nb_done >> k & 1)) {
		c->nb_done |= 1u << k;
		c->nb[k] = fct_voxgrid_block((struct fct_voxgrid *)c->g, c->bx + dx, c->by + dy,
		                             c->bz + dz, 0, NULL);
	}
	return c->nb[k];
}

static inline int observed(const struct ctx *c, float s, float w)
{
	return w >= c->thr && fabsf(s) <= FLT_MAX;
}

/* Voxel at local coordinates (x, y, z) in -8..15 of the current block: its
 * block (NULL when absent) and index. */
static inline const struct fct_voxblock *ctx_voxel(struct ctx *c, int x, int y, int z, int *v)
{
	int dx = (x + 8) / 8 - 1, dy = (y + 8) / 8 - 1, dz = (z + 8) / 8 - 1;
	*v = ((x + 8) & 7) + 8 * (((y + 8) & 7) + 8 * ((z + 8) & 7));
	return ctx_nb(c, dx, dy, dz);
}

/* Value of local voxel (x, y, z) when observed (return 1), else 0. */
static inline int ctx_sample(struct ctx *c, int x, int y, int z, float *s)
{
	int v;
	const struct fct_voxblock *b = ctx_voxel(c, x, y, z, &v);
	if (!b || !observed(c, b->sdf[v], b->weight[v]))
		return 0;
	*s = b->sdf[v];
	return 1;
}

/* The sdf gradient at local voxel p (observed, value s0), in units per voxel. */
static void gradient(struct ctx *c, const int p[3], float s0, double g[3])
{
	for (int a = 0; a < 3; a++) {
		int q[3] = { p[0], p[1], p[2] };
		float sp, sm;
		q[a] = p[a] + 1;
		int hp = ctx_sample(c, q[0], q[1], q[2], &sp);
		q[a] = p[a] - 1;
		int hm = ctx_sample(c, q[0], q[1], q[2], &sm);
		if (hp && hm)
			g[a] = 0.5 * ((double)sp - (double)sm);
		else if (hp)
			g[a] = (double)sp - (double)s0;
		else if (hm)
			g[a] = (double)s0 - (double)sm;
		else
			g[a] = 0;
	}
}

static int grow_vertices(struct ctx *c, size_t need, struct fct_err *err)
{
	if (need > UINT32_MAX - 1)
		return fct_fail(err, "marching cubes: more than 2^32 - 1 vertices");
	if (need <= c->vcap)
		return 0;
	size_t cap = c->vcap, n3 = 3 * need;
	size_t xc = 3 * c->vcap, nc = 3 * c->vcap, cc = 3 * c->vcap;
	if (fct_grow((void **)&c->xyz, &xc, n3, sizeof *c->xyz, err) ||
	    fct_grow((void **)&c->nrm, &nc, n3, sizeof *c->nrm, err) ||
	    (c->colour && fct_grow((void **)&c->rgb, &cc, n3, 1, err)))
		return -1;
	cap = xc / 3;
	if (nc / 3 < cap)
		cap = nc / 3;
	if (c->colour && cc / 3 < cap)
		cap = cc / 3;
	c->vcap = cap;
	return 0;
}

static uint8_t to_u8(double v)
{
	v = floor(v + 0.5);
	return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* Vertex on the edge from local voxel p along axis a (both ends observed,
 * signs differ). */
static void make_vertex(struct ctx *c, const int p[3], int a, size_t id)
{
	int v0, v1, q[3] = { p[0], p[1], p[2] };
	q[a]++;
	const struct fct_voxblock *b0 = ctx_voxel(c, p[0], p[1], p[2], &v0);
	const struct fct_voxblock *b1 = ctx_voxel(c, q[0], q[1], q[2], &v1);
	float s0 = b0->sdf[v0], s1 = b1->sdf[v1];
	double t = (double)s0 / ((double)s0 - (double)s1);
	if (!(t >= 1.0 / 256))
		t = 1.0 / 256;
	if (t > 255.0 / 256)
		t = 255.0 / 256;
	int32_t gi[3] = { 8 * c->bx + p[0], 8 * c->by + p[1], 8 * c->bz + p[2] };
	double *x = c->xyz + 3 * id;
	for (int k = 0; k < 3; k++)
		x[k] = (double)gi[k] * c->voxel;
	x[a] = ((double)gi[a] + t) * c->voxel;
	double g0[3], g1[3], n[3], len = 0;
	gradient(c, p, s0, g0);
	gradient(c, q, s1, g1);
	for (int k = 0; k < 3; k++) {
		n[k] = (1 - t) * g0[k] + t * g1[k];
		len += n[k] * n[k];
	}
	float *nr = c->nrm + 3 * id;
	if (len > 0) {
		len = sqrt(len);
		for (int k = 0; k < 3; k++)
			nr[k] = (float)(n[k] / len);
	} else {
		nr[0] = nr[1] = nr[2] = 0;
		nr[a] = s1 >= 0 ? 1.0f : -1.0f;
	}
	if (c->colour) {
		const float *r0 = b0->rgb + 3 * v0, *r1 = b1->rgb + 3 * v1;
		for (int k = 0; k < 3; k++)
			c->rgb[3 * id + k] = to_u8((1 - t) * r0[k] + t * r1[k]);
	}
}

/* Sign and observed bits of one row of 9 voxels: local (0..8, y, z). */
static void row_bits(struct ctx *c, int y, int z, uint16_t *neg, uint16_t *obs)
{
	unsigned n = 0, o = 0;
	const struct fct_voxblock *b = ctx_nb(c, 0, y >> 3, z >> 3);
	int base = 8 * ((y & 7) + 8 * (z & 7));
	if (b) {
		const float *s = b->sdf + base, *w = b->weight + base;
		for (int x = 0; x < 8; x++) {
			n |= (unsigned)(s[x] < 0) << x;
			o |= (unsigned)(w[x] >= c->thr && fabsf(s[x]) <= FLT_MAX) << x;
		}
	}
	b = ctx_nb(c, 1, y >> 3, z >> 3);
	if (b) {
		float s = b->sdf[base], w = b->weight[base];
		n |= (unsigned)(s < 0) << 8;
		o |= (unsigned)observed(c, s, w) << 8;
	}
	*neg = (uint16_t)n;
	*obs = (uint16_t)o;
}

/* Bits of the 9 voxels of local row (y, z) inside the clip box. */
static unsigned clip_row(const struct ctx *c, int y, int z)
{
	if (!c->lo)
		return 0x1FF;
	int64_t gy = (int64_t)8 * c->by + y, gz = (int64_t)8 * c->bz + z;
	if (gy < c->lo[1] || gy > c->hi[1] || gz < c->lo[2] || gz > c->hi[2])
		return 0;
	unsigned m = 0;
	for (int x = 0; x < 9; x++) {
		int64_t gx = (int64_t)8 * c->bx + x;
		m |= (unsigned)(gx >= c->lo[0] && gx <= c->hi[0]) << x;
	}
	return m;
}

/* Pass 1 on the current block: fill A, create the block's vertices. */
static int pass1(struct ctx *c, struct aux *A, struct fct_err *err)
{
	uint16_t obs[9][9];
	memset(A, 0, sizeof *A);
	int anyobs = 0;
	for (int z = 0; z < 9; z++)
		for (int y = 0; y < 9; y++) {
			row_bits(c, y, z, &A->neg[z][y], &obs[z][y]);
			obs[z][y] &= (uint16_t)clip_row(c, y, z);
			anyobs |= obs[z][y];
		}
	if (!anyobs)
		return 0;
	size_t count = 0;
	for (int z = 0; z < 8; z++) {
		uint64_t bx = 0, by = 0, bz = 0;
		for (int y = 0; y < 8; y++) {
			unsigned n = A->neg[z][y], o = obs[z][y];
			unsigned ex = (n ^ n >> 1) & o & o >> 1 & 0xFF;
			unsigned ey = (n ^ A->neg[z][y + 1]) & o & obs[z][y + 1] & 0xFF;
			unsigned ez = (n ^ A->neg[z + 1][y]) & o & obs[z + 1][y] & 0xFF;
			bx |= (uint64_t)ex << 8 * y;
			by |= (uint64_t)ey << 8 * y;
			bz |= (uint64_t)ez << 8 * y;
			unsigned n01 = A->neg[z][y + 1], n10 = A->neg[z + 1][y], n11 = A->neg[z + 1][y + 1];
			unsigned all = o & obs[z][y + 1] & obs[z + 1][y] & obs[z + 1][y + 1];
			unsigned any = n | n01 | n10 | n11, every = n & n01 & n10 & n11;
			all &= all >> 1;
			any |= any >> 1;
			every &= every >> 1;
			A->active[z][y] = (uint8_t)(all & any & ~every & 0xFF);
			A->any_active |= A->active[z][y];
		}
		A->bits[z] = bx, A->bits[8 + z] = by, A->bits[16 + z] = bz;
	}
	for (int w = 0; w < 24; w++) {
		A->pre[w] = (uint32_t)count;
		count += (size_t)__builtin_popcountll(A->bits[w]);
	}
	if (!count)
		return 0;
	A->base = (uint32_t)c->nv;
	if (grow_vertices(c, c->nv + count, err))
		return -1;
	size_t id = c->nv;
	for (int w = 0; w < 24; w++)
		for (uint64_t m = A->bits[w]; m; m &= m - 1) {
			int bit = __builtin_ctzll(m);
			int p[3] = { bit & 7, bit >> 3, w & 7 };
			make_vertex(c, p, w >> 3, id++);
		}
	c->nv = id;
	return 0;
}

/* Vertex of crossing edge e of cube (x, y, z) of the current block; auxn
 * holds the aux of the block and its upper neighbours, [dz][dy][dx]. */
static inline uint32_t edge_vertex(const struct ctx *c, const struct aux *auxn[2][2][2],
                                   int x, int y, int z, int e)
{
	int lo = c->G.edge_lo[e], a = e >> 2;
	int px = x + (lo & 1), py = y + (lo >> 1 & 1), pz = z + (lo >> 2 & 1);
	const struct aux *A = auxn[pz >> 3][py >> 3][px >> 3];
	if (!A)
		abort();
	int w = 8 * a + (pz & 7), bit = (px & 7) + 8 * (py & 7);
	uint64_t word = A->bits[w];
	if (!(word >> bit & 1))
		abort();
	return A->base + A->pre[w] + (uint32_t)__builtin_popcountll(word & ((UINT64_C(1) << bit) - 1));
}

static int add_tri(struct ctx *c, uint32_t a, uint32_t b, uint32_t d, struct fct_err *err)
{
	if (c->nt + 1 > c->tcap / 3) {
		if (c->nt >= UINT32_MAX / 3)
			return fct_fail(err, "marching cubes: too many triangles");
		if (fct_grow((void **)&c->tri, &c->tcap, 3 * (c->nt + 1), sizeof *c->tri, err))
			return -1;
	}
	uint32_t *t = c->tri + 3 * c->nt++;
	t[0] = a, t[1] = b, t[2] = d;
	return 0;
}

/* The triangles of cube (x, y, z), sign pattern cfg. */
static int emit_cube(struct ctx *c, const struct aux *auxn[2][2][2], int x, int y, int z, int cfg,
                     struct fct_err *err)
{
	const struct mc_case *mc = &c->table[cfg];
	struct mc_case local;
	if (mc->amb) {
		/* asymptotic decider on each ambiguous face, from exact products */
		float val[8];
		for (int k = 0; k < 8; k++)
			if (!ctx_sample(c, x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1), &val[k]))
				abort();
		int joinneg = 0;
		for (int f = 0; f < 6; f++) {
			if (!(mc->amb >> f & 1))
				continue;
			const uint8_t *fc = c->G.face_corners[f];
			double d0 = (double)val[fc[0]] * (double)val[fc[2]];
			double d1 = (double)val[fc[1]] * (double)val[fc[3]];
			int c0neg = cfg >> fc[0] & 1;
			double pos = c0neg ? d1 : d0, negp = c0neg ? d0 : d1;
			if (!(pos >= negp))
				joinneg |= 1 << f;
		}
		c->st.ambiguous++;
		if (joinneg) {
			build_case(&c->G, cfg, joinneg, &local);
			mc = &local;
		}
	}
	uint32_t vid[12];
	for (int e = 0; e < 12; e++)
		if (mc->emask >> e & 1)
			vid[e] = edge_vertex(c, auxn, x, y, z, e);
	const uint8_t *ed = mc->edge;
	for (int l = 0; l < mc->nloops; l++) {
		int len = mc->len[l];
		if (mc->centre[l]) {
			if (grow_vertices(c, c->nv + 1, err))
				return -1;
			size_t id = c->nv++;
			double p[3] = { 0, 0, 0 }, n[3] = { 0, 0, 0 }, col[3] = { 0, 0, 0 };
			for (int i = 0; i < len; i++)
				for (int k = 0; k < 3; k++) {
					p[k] += c->xyz[3 * vid[ed[i]] + k];
					n[k] += c->nrm[3 * vid[ed[i]] + k];
					if (c->colour)
						col[k] += c->rgb[3 * vid[ed[i]] + k];
				}
			double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
			for (int k = 0; k < 3; k++) {
				c->xyz[3 * id + k] = p[k] / len;
				c->nrm[3 * id + k] = nl > 0 ? (float)(n[k] / nl) : 0.0f;
				if (c->colour)
					c->rgb[3 * id + k] = to_u8(col[k] / len);
			}
			c->st.centres++;
			for (int i = 0; i < len; i++)
				if (add_tri(c, (uint32_t)id, vid[ed[i]], vid[ed[(i + 1) % len]], err))
					return -1;
		} else {
			for (int i = 1; i + 1 < len; i++)
				if (add_tri(c, vid[ed[0]], vid[ed[i]], vid[ed[i + 1]], err))
					return -1;
		}
		ed += len;
	}
	c->st.cubes++;
	return 0;
}

/* Drop unused vertices, build the mesh. */
static int finish(struct ctx *c, struct fct_mesh *out, struct fct_err *err)
{
	uint32_t *remap = fct_alloc_array(c->nv, sizeof *remap, err);
	if (!remap)
		return -1;
	for (size_t v = 0; v < c->nv; v++)
		remap[v] = UINT32_MAX;
	for (size_t i = 0; i < 3 * c->nt; i++)
		remap[c->tri[i]] = 0;
	size_t n = 0;
	for (size_t v = 0; v < c->nv; v++)
		if (remap[v] == 0)
			remap[v] = (uint32_t)n++;
	int rc = -1;
	if (fct_mesh_set_vertex_count(out, n, err) || fct_mesh_set_triangle_count(out, c->nt, err))
		goto done;
	static const char *nn[3] = { "nx", "ny", "nz" }, *cn[3] = { "red", "green", "blue" };
	for (int k = 0; k < 3; k++)
		if (!fct_elem_add_scalar(&out->vertex, nn[k], FCT_FLOAT32, err))
			goto done;
	if (c->colour)
		for (int k = 0; k < 3; k++)
			if (!fct_elem_add_scalar(&out->vertex, cn[k], FCT_UINT8, err))
				goto done;
	float *nc[3];
	uint8_t *cc[3] = { NULL, NULL, NULL };
	for (int k = 0; k < 3; k++) {
		nc[k] = fct_elem_find(&out->vertex, nn[k])->data;
		if (c->colour)
			cc[k] = fct_elem_find(&out->vertex, cn[k])->data;
	}
	for (size_t v = 0; v < c->nv; v++) {
		uint32_t r = remap[v];
		if (r == UINT32_MAX)
			continue;
		for (int k = 0; k < 3; k++) {
			out->xyz[3 * (size_t)r + k] = c->xyz[3 * v + k];
			nc[k][r] = c->nrm[3 * v + k];
			if (c->colour)
				cc[k][r] = c->rgb[3 * v + k];
		}
	}
	for (size_t i = 0; i < 3 * c->nt; i++)
		out->fvert[i] = remap[c->tri[i]];
	rc = 0;
done:
	free(remap);
	return rc;
}

int fct_mcubes_stats(const struct fct_voxgrid *g, float min_weight, const int32_t *clip_lo,
                     const int32_t *clip_hi, struct fct_mesh *out, struct fct_mcubes_stats *stats,
                     struct fct_err *err)
{
	fct_mesh_init(out);
	if ((clip_lo == NULL) != (clip_hi == NULL))
		return fct_fail(err, "marching cubes: clip box needs both corners");
	struct ctx *c = calloc(1, sizeof *c);
	if (!c)
		return fct_fail(err, "out of memory");
	c->g = g;
	c->thr = min_weight > 0 ? min_weight : FLT_TRUE_MIN;
	if (isnan(min_weight))
		c->thr = INFINITY;
	c->colour = fct_voxgrid_has_colour(g);
	c->voxel = fct_voxgrid_voxel(g);
	c->lo = clip_lo, c->hi = clip_hi;
	geom_init(&c->G);
	for (int cfg = 0; cfg < 256; cfg++)
		build_case(&c->G, cfg, 0, &c->table[cfg]);

	int rc = -1;
	size_t nb = fct_voxgrid_count(g), naux = 0, auxcap = 0;
	struct aux *aux = NULL;
	uint32_t *auxidx = fct_alloc_array(nb, sizeof *auxidx, err);
	if (!auxidx)
		goto done;
	if (clip_lo && (clip_lo[0] >= clip_hi[0] || clip_lo[1] >= clip_hi[1] || clip_lo[2] >= clip_hi[2])) {
		/* an empty box: no cubes */
		nb = 0;
	}
	for (size_t b = 0; b < nb; b++) {
		const struct fct_voxblock *B = fct_voxgrid_at(g, b);
		auxidx[b] = UINT32_MAX;
		if (clip_lo) {
			/* blocks wholly outside the closed box [lo, hi] hold no corner */
			int64_t lo0 = (int64_t)8 * B->bx, lo1 = (int64_t)8 * B->by, lo2 = (int64_t)8 * B->bz;
			if (lo0 + 7 < clip_lo[0] || lo0 > clip_hi[0] || lo1 + 7 < clip_lo[1] ||
			    lo1 > clip_hi[1] || lo2 + 7 < clip_lo[2] || lo2 > clip_hi[2])
				continue;
		}
		if (fct_grow((void **)&aux, &auxcap, naux + 1, sizeof *aux, err))
			goto done;
		ctx_block(c, B);
		if (pass1(c, &aux[naux], err))
			goto done;
		int keep = aux[naux].any_active;
		for (int w = 0; w < 24; w++)
			keep |= aux[naux].bits[w] != 0;
		if (keep)
			auxidx[b] = (uint32_t)naux++;
	}
	for (size_t b = 0; b < nb; b++) {
		if (auxidx[b] == UINT32_MAX || !aux[auxidx[b]].any_active)
			continue;
		const struct fct_voxblock *B = fct_voxgrid_at(g, b);
		const struct aux *A = &aux[auxidx[b]];
		const struct aux *auxn[2][2][2];
		for (int k = 0; k < 8; k++) {
			long i = fct_voxgrid_index(g, B->bx + (k & 1), B->by + (k >> 1 & 1), B->bz + (k >> 2));
			auxn[k >> 2][k >> 1 & 1][k & 1] =
				i >= 0 && auxidx[i] != UINT32_MAX ? &aux[auxidx[i]] : NULL;
		}
		ctx_block(c, B);
		for (int z = 0; z < 8; z++)
			for (int y = 0; y < 8; y++)
				for (unsigned m = A->active[z][y]; m; m &= m - 1) {
					int x = __builtin_ctz(m);
					int cfg = (A->neg[z][y] >> x & 3) | (A->neg[z][y + 1] >> x & 3) << 2 |
					          (A->neg[z + 1][y] >> x & 3) << 4 |
					          (A->neg[z + 1][y + 1] >> x & 3) << 6;
					if (emit_cube(c, auxn, x, y, z, cfg, err))
						goto done;
				}
	}
	if (finish(c, out, err))
		goto done;
	c->st.blocks = nb;
	c->st.voxels = nb * FCT_VOXBLOCK_N;
	if (stats)
		*stats = c->st;
	rc = 0;
done:
	if (rc)
		fct_mesh_free(out);
	free(auxidx);
	free(aux);
	free(c->xyz);
	free(c->nrm);
	free(c->rgb);
	free(c->tri);
	free(c);
	return rc;
}

int fct_mcubes(const struct fct_voxgrid *g, float min_weight, const int32_t *clip_lo,
               const int32_t *clip_hi, struct fct_mesh *out, struct fct_err *err)
{
	return fct_mcubes_stats(g, min_weight, clip_lo, clip_hi, out, NULL, err);
}

/* Weld ---------------------------------------------------------------------- */

struct weld_key {
	double p[3];
	uint32_t v;
};

static int cmp_key(const void *pa, const void *pb)
{
	const struct weld_key *a = pa, *b = pb;
	int r = memcmp(a->p, b->p, sizeof a->p);
	return r ? r : (a->v > b->v) - (a->v < b->v);
}

long fct_mesh_weld_exact(struct fct_mesh *m, struct fct_err *err)
{
	if (m->nv > UINT32_MAX)
		return fct_fail(err, "weld: too many vertices");
	struct weld_key *key = fct_alloc_array(m->nv, sizeof *key, err);
	uint32_t *rep = fct_alloc_array(m->nv, sizeof *rep, err);
	size_t *keep = fct_alloc_array(m->nv, sizeof *keep, err);
	long rc = -1;
	if (!key || !rep || !keep)
		goto done;
	for (size_t v = 0; v < m->nv; v++) {
		memcpy(key[v].p, m->xyz + 3 * v, sizeof key[v].p);
		key[v].v = (uint32_t)v;
	}
	/* byte order of the positions: equal positions are adjacent, the
	 * smallest index first */
	qsort(key, m->nv, sizeof *key, cmp_key);
	for (size_t i = 0, first = 0; i < m->nv; i++) {
		if (i > 0 && memcmp(key[i].p, key[i - 1].p, sizeof key[i].p))
			first = i;
		rep[key[i].v] = key[first].v;
	}
	size_t n = 0;
	for (size_t v = 0; v < m->nv; v++)
		if (rep[v] == v)
			keep[n++] = v;
	for (size_t i = 0; m->nf && i < m->fstart[m->nf]; i++)
		m->fvert[i] = rep[m->fvert[i]];
	size_t removed = m->nv - n;
	/* renumbers the faces, whose vertices are all kept now */
	if (fct_mesh_gather_vertices(m, keep, n, err))
		goto done;
	rc = (long)removed;
done:
	free(key);
	free(rep);
	free(keep);
	return rc;
}

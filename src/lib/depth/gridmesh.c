/* gridmesh.c - organised range data to triangles (see gridmesh.h). */
#include "depth/gridmesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/lanes.h"
#include "geom/geom.h"

/* What one grid square becomes: which of its two triangles are made and
 * along which diagonal.  Corners: a = (i, j), b = (i+1, j), c = (i, j+1),
 * d = (i+1, j+1).  Diagonal bc: (a, c, b) and (b, c, d); diagonal ad:
 * (a, c, d) and (a, d, b) -- all clockwise in (u, v), which faces the sensor. */
enum { FIRST = 1, SECOND = 2, DIAG_AD = 4 };

/* Two floats made doubles (exactly). */
static inline v2d load2_float(const float *p)
{
	return (v2d){ p[0], p[1] };
}

struct grid {
	const struct fct_range_grid *g;
	double limit;            /* max_jump * footprint */
	double noise;            /* noise_jump * sqrt(2) */
	int w, h, wrap;
	double *ray_x, *ray_z;   /* g->col's x and z, each in an array of its own */
};

static inline int has_data(const struct grid *G, size_t c)
{
	double d = G->g->depth[c];
	return d > 0 && d < HUGE_VAL;
}

/* Whether cells c and c + 1 have data (has_data), as a mask. */
static inline v2i has_data2(const struct grid *G, size_t c)
{
	v2d d = load2(G->g->depth + c);
	const v2d zero = { 0, 0 }, huge = { HUGE_VAL, HUGE_VAL };
	return (d > zero) & (d < huge);
}

/* Cell (i, j) or -1 outside the grid; columns wrap on a full cylinder. */
static inline long cell_at(const struct grid *G, long i, long j)
{
	if (j < 0 || j >= G->h)
		return -1;
	if (i < 0 || i >= G->w) {
		if (!G->wrap)
			return -1;
		i = (i + G->w) % G->w;
	}
	return j * (long)G->w + i;
}

/* The position of cell c, which is (i, j). */
static inline void P(const struct grid *G, size_t c, size_t i, size_t j, double p[3])
{
	const struct fct_range_grid *g = G->g;
	if (g->xyz) {
		memcpy(p, g->xyz + 3 * c, 3 * sizeof *p);
		return;
	}
	double d = g->depth[c];
	p[0] = d * g->col[3 * i], p[1] = d * g->row[j], p[2] = d * g->col[3 * i + 2];
}

/* The position of cell (i, j), columns wrapped on a full cylinder; 0 when
 * it is outside the grid or has no data. */
static int position_at(const struct grid *G, long i, long j, double p[3])
{
	long c = cell_at(G, i, j);
	if (c < 0 || !has_data(G, (size_t)c))
		return 0;
	if (i < 0 || i >= G->w)
		i = (i + G->w) % G->w;
	P(G, (size_t)c, (size_t)i, (size_t)j, p);
	return 1;
}

/* Choose the diagonal of the full square (i, j) whose triangles fit the
 * surface better: 1 for ad, 0 for bc.  The bend along a diagonal from p to
 * q is the sum of squared distances of p and q from the lines through their
 * neighbours along it (pp before p, qq after q). */
static int choose_ad(double bad, double bbc, int around, const double a[3], const double b[3],
                     const double c[3], const double d[3])
{
	double lad = fct_v3_dist2(a, d), lbc = fct_v3_dist2(b, c);
	if (around) {
		/* Bends that are both rounding noise (a plane) decide nothing:
		 * then the shorter diagonal makes the better-shaped triangles. */
		double noise = 1e-18 * (lad > lbc ? lad : lbc);
		if (fabs(bad - bbc) > noise)
			return bad < bbc;
	}
	return lad < lbc;
}

/* prefer_ad from the positions alone: on the border of the grid, where
 * neighbours may be missing or wrap around a full cylinder, and for the
 * inner square that prefer_row leaves. */
static int prefer_ad_border(const struct grid *G, long i, long j)
{
	double a[3], b[3], c[3], d[3], aa[3], dd[3], bb[3], cc[3], bad = 0, bbc = 0;
	position_at(G, i, j, a), position_at(G, i + 1, j, b);
	position_at(G, i, j + 1, c), position_at(G, i + 1, j + 1, d);
	int around = position_at(G, i - 1, j - 1, aa) && position_at(G, i + 2, j + 2, dd) &&
	             position_at(G, i + 2, j - 1, bb) && position_at(G, i - 1, j + 2, cc);
	if (around) {
		bad = fct_v3_line_distance2(a, aa, d) + fct_v3_line_distance2(d, a, dd);
		bbc = fct_v3_line_distance2(b, bb, c) + fct_v3_line_distance2(c, b, cc);
	}
	return choose_ad(bad, bbc, around, a, b, c, d);
}

/* Inside the grid a square's bends are sums of per-cell terms: the bend
 * along ad is bend_ad(a) + bend_ad(d), bend_ad(x) being x's squared
 * distance from the line through its neighbours up-left and down-right
 * (fct_v3_line_distance2 with the same arguments in the same order, so
 * the same bits), and the bend along bc is bend_bc(b) + bend_bc(c) with the
 * neighbours up-right and down-left.  Each cell's terms are computed once
 * instead of once for each of the two squares that use them, from the
 * positions of the rows around it, which are computed once too.  Rows are
 * kept in rings: positions of rows j-1 .. j+2 and bends of rows j, j+1 while
 * the squares of row j are decided.  Positions are kept a coordinate per
 * array, so that the bends of two cells are computed at once
 * (line_distance2_pair). */
struct bend_rows {
	double *x[4], *y[4], *z[4];   /* per cell, row r in [r % 4]; 2 cells of padding */
	double *ad[2], *bc[2];        /* per cell, row r in [r % 2] */
	long npos, nbend;             /* rows computed so far */
	unsigned char *prefer;        /* prefer_ad of the row's squares 1 .. fast_end-1 */
	long fast_end;
};

static void position_row(const struct grid *G, const struct bend_rows *R, long j)
{
	double *x = R->x[j % 4], *y = R->y[j % 4], *z = R->z[j % 4], p[3];
	long i = 0;
	if (!G->g->xyz) {   /* P two cells at a time */
		const double *d = G->g->depth + (size_t)j * (size_t)G->w;
		const v2d ray_y = { G->g->row[j], G->g->row[j] };
		for (; i + 1 < G->w; i += 2) {
			v2d di = load2(d + i);
			store2(x + i, di * load2(G->ray_x + i));
			store2(y + i, di * ray_y);
			store2(z + i, di * load2(G->ray_z + i));
		}
	}
	for (; i < G->w; i++) {
		P(G, (size_t)(j * G->w + i), (size_t)i, (size_t)j, p);
		x[i] = p[0], y[i] = p[1], z[i] = p[2];
	}
}

/* fct_v3_line_distance2 of two cells at once: p, a and b are each given
 * by their coordinates' pairs, in the same operations and order. */
static inline v2d line_distance2_pair(v2d px, v2d py, v2d pz, v2d ax, v2d ay, v2d az,
                                      v2d bx, v2d by, v2d bz)
{
	v2d abx = bx - ax, aby = by - ay, abz = bz - az;
	v2d apx = px - ax, apy = py - ay, apz = pz - az;
	v2d xx = aby * apz - abz * apy, xy = abz * apx - abx * apz, xz = abx * apy - aby * apx;
	v2d l2 = abx * abx + aby * aby + abz * abz;
	v2d on_line = (xx * xx + xy * xy + xz * xz) / l2, to_a = apx * apx + apy * apy + apz * apz;
	/* l2 > 0 selects the first; where l2 is 0 its quotient (NaN or
	 * infinity) is discarded, and no trap is enabled. */
	return select2(l2 > 0, on_line, to_a);
}

/* The bends of the cells 1 .. w-2 of row j (0 < j < h-1); cells without data
 * or beside one get values that are never used.  Cells go two at a time;
 * an odd count's last pair reads the padding and writes bends of cell w-1,
 * which no square reads. */
static void bend_row(const struct bend_rows *R, long j, long w, double *ad, double *bc)
{
	int u = (int)((j - 1) % 4), m = (int)(j % 4), d = (int)((j + 1) % 4);
	const double *ux = R->x[u], *uy = R->y[u], *uz = R->z[u];
	const double *mx = R->x[m], *my = R->y[m], *mz = R->z[m];
	const double *dx = R->x[d], *dy = R->y[d], *dz = R->z[d];
	for (long i = 1; i + 1 < w; i += 2) {
		v2d px = load2(mx + i), py = load2(my + i), pz = load2(mz + i);
		store2(ad + i, line_distance2_pair(px, py, pz, load2(ux + i - 1), load2(uy + i - 1),
		                                   load2(uz + i - 1), load2(dx + i + 1), load2(dy + i + 1),
		                                   load2(dz + i + 1)));
		store2(bc + i, line_distance2_pair(px, py, pz, load2(ux + i + 1), load2(uy + i + 1),
		                                   load2(uz + i + 1), load2(dx + i - 1), load2(dy + i - 1),
		                                   load2(dz + i - 1)));
	}
}

/* Make the rings hold what the squares of row j need. */
static void bend_rows_advance(const struct grid *G, struct bend_rows *R, long j)
{
	for (; R->npos <= j + 2 && R->npos < G->h; R->npos++)
		position_row(G, R, R->npos);
	for (; R->nbend <= j + 1 && R->nbend + 1 < G->h; R->nbend++)
		if (R->nbend > 0)
			bend_row(R, R->nbend, G->w, R->ad[R->nbend % 2], R->bc[R->nbend % 2]);
}

/* prefer_ad of the inner squares of row j (1 <= i, i + 2 < w; 1 <= j,
 * j + 2 < h; bend_rows_advance(j) done) two at a time from the rings,
 * choose_ad's operations lane by lane and its branches made selects, into
 * R->prefer[1 .. R->fast_end); the last square of an odd count is left to
 * prefer_ad_border, whose bends are the rings' bits (fct_v3_line_distance2
 * with the same arguments).  Most squares of a depth frame ask, and their
 * choices alternate as good as randomly: branches mispredict. */
static void prefer_row(const struct grid *G, struct bend_rows *R, long j)
{
	size_t W = (size_t)G->w, row = (size_t)j * W;
	int r0 = (int)(j % 4), r1 = (int)((j + 1) % 4);
	const double *x0 = R->x[r0], *y0 = R->y[r0], *z0 = R->z[r0];
	const double *x1 = R->x[r1], *y1 = R->y[r1], *z1 = R->z[r1];
	const double *ad0 = R->ad[j % 2], *ad1 = R->ad[(j + 1) % 2];
	const double *bc0 = R->bc[j % 2], *bc1 = R->bc[(j + 1) % 2];
	const v2d tiny = { 1e-18, 1e-18 };
	const v2i magnitude = { INT64_MAX, INT64_MAX }, one = { 1, 1 };
	long i = 1;
	for (; i + 3 < G->w; i += 2) {
		size_t ca = row + (size_t)i;
		v2i around = has_data2(G, ca - W - 1) & has_data2(G, ca + 2 * W + 2) &
		             has_data2(G, ca - W + 2) & has_data2(G, ca + 2 * W - 1);
		v2d bad = load2(ad0 + i) + load2(ad1 + i + 1), bbc = load2(bc0 + i + 1) + load2(bc1 + i);
		v2d ex = load2(x0 + i) - load2(x1 + i + 1), ey = load2(y0 + i) - load2(y1 + i + 1),
		    ez = load2(z0 + i) - load2(z1 + i + 1);
		v2d lad = ex * ex + ey * ey + ez * ez;
		ex = load2(x0 + i + 1) - load2(x1 + i), ey = load2(y0 + i + 1) - load2(y1 + i),
		ez = load2(z0 + i + 1) - load2(z1 + i);
		v2d lbc = ex * ex + ey * ey + ez * ez;
		v2d noise = tiny * select2(lad > lbc, lad, lbc);
		v2i by_bend = around & ((v2d)((v2i)(bad - bbc) & magnitude) > noise);
		v2i ad = ((by_bend & (bad < bbc)) | (~by_bend & (lad < lbc))) & one;
		R->prefer[i] = (unsigned char)ad[0], R->prefer[i + 1] = (unsigned char)ad[1];
	}
	R->fast_end = i;
}

static int prefer_ad(const struct grid *G, const struct bend_rows *R, long i, long j)
{
	if (i >= 1 && i < R->fast_end)
		return R->prefer[i];
	return prefer_ad_border(G, i, j);
}

/* The corners of square (i, j): a b / c d. */
struct square {
	uint32_t a, b, c, d;
};

static inline struct square square_at(const struct grid *G, long i, long j)
{
	uint32_t row = (uint32_t)(j * G->w), next = row + (uint32_t)G->w;
	uint32_t i1 = (uint32_t)(i + 1 == G->w ? 0 : i + 1);
	return (struct square){ row + (uint32_t)i, row + i1, next + (uint32_t)i, next + i1 };
}

/* Which corners of a square have data and which of its six edges join
 * their ends (fct_depth_joined; 0 where an end has no data). */
enum { HA = 1, HB = 2, HC = 4, HD = 8, JAB = 16, JCD = 32, JAC = 64, JBD = 128, JAD = 256, JBC = 512 };

/* The triangles of a square whose corners and edges are e, ad saying which
 * diagonal to take when both join; *possible gets how many its corners
 * with data would allow. */
static unsigned square_code(unsigned e, int ad, unsigned *possible)
{
	int ha = !!(e & HA), hb = !!(e & HB), hc = !!(e & HC), hd = !!(e & HD);
	*possible = 0;
	if (ha + hb + hc + hd < 3)
		return 0;
	int ab = !!(e & JAB), cd = !!(e & JCD), ac = !!(e & JAC), bd = !!(e & JBD);
	int jad = !!(e & JAD), jbc = !!(e & JBC);
	if (!hd) {
		*possible = 1;
		return ac && jbc && ab ? FIRST : 0;
	}
	if (!ha) {
		*possible = 1;
		return jbc && cd && bd ? SECOND : 0;
	}
	if (!hb) {
		*possible = 1;
		return ac && cd && jad ? DIAG_AD | FIRST : 0;
	}
	if (!hc) {
		*possible = 1;
		return jad && bd && ab ? DIAG_AD | SECOND : 0;
	}
	*possible = 2;
	if (jad && (ad || !jbc))
		return DIAG_AD | (ac && cd ? FIRST : 0) | (bd && ab ? SECOND : 0);
	if (!jbc)
		return 0;
	return (ac && ab ? FIRST : 0) | (cd && bd ? SECOND : 0);
}

/* square_code of every e, looked up instead of branched through square by
 * square: the code along bc ([0]) and along ad ([1], the same unless ask),
 * whether the square's shape must choose between them (prefer_ad), and
 * possible. */
struct square_rule {
	unsigned char code[2], ask, possible;
};

static void square_rules(struct square_rule rules[1024])
{
	for (unsigned e = 0; e < 1024; e++) {
		unsigned possible;
		rules[e].code[0] = (unsigned char)square_code(e, 0, &possible);
		rules[e].code[1] = (unsigned char)square_code(e, 1, &possible);
		rules[e].possible = (unsigned char)possible;
		rules[e].ask = (e & (HA | HB | HC | HD | JAD | JBC)) == (HA | HB | HC | HD | JAD | JBC);
	}
}

/* The flags that make the e of a row of squares, a byte per cell or square,
 * made a run of cells at a time without branches.  Rows of cells j and
 * j+1 (the squares' top and bottom): has data, joined to the next cell in
 * the row; cells (i, j) and (i, j+1) joined; the diagonals ad and bc of
 * square i.  Per-cell arrays have w + 1 entries: on a full cylinder entry
 * w repeats column 0, so that square i's right corners are always i + 1.
 * The join test is symmetric in its ends, so row j+1's flags serve as row
 * j's for the next row of squares. */
struct edge_rows {
	unsigned char *has[2], *along[2];   /* rows j, j + 1: [j % 2] */
	unsigned char *down, *ad, *bc;
};

/* has_data of the w cells of row j into out (and the wrap's copy). */
static void has_row(const struct grid *G, long j, unsigned char *out)
{
	size_t c = (size_t)j * (size_t)G->w;
	long i = 0;
	for (; i + 1 < G->w; i += 2) {
		v2i has = has_data2(G, c + (size_t)i);
		out[i] = (unsigned char)(has[0] & 1), out[i + 1] = (unsigned char)(has[1] & 1);
	}
	for (; i < G->w; i++)
		out[i] = (unsigned char)has_data(G, c + (size_t)i);
	out[G->w] = out[0];
}

/* out[k] for k < n: cells a + k and b + k, steps grid steps apart, both
 * have data (ha[k], hb[k]) and are on one surface: the depth jump between
 * them is within the limit, widened by the noise where there is sigma. */
static void join_run(const struct grid *G, size_t a, size_t b, size_t n, double steps,
                     const unsigned char *ha, const unsigned char *hb, unsigned char *out)
{
	const double *d = G->g->depth;
	const float *s = G->g->sigma;
	/* Two at a time: fct_depth_joined's operations lane by lane (limit *
	 * steps * min is (limit * steps) * min; the larger float sigma made a
	 * double after choosing or before, the same value), the last odd one
	 * by fct_depth_joined itself. */
	const v2d limit = { G->limit * steps, G->limit * steps }, noise = { G->noise, G->noise };
	const v2i magnitude = { INT64_MAX, INT64_MAX };
	size_t k = 0;
	for (; k + 1 < n; k += 2) {
		v2d da = load2(d + a + k), db = load2(d + b + k), allow = { 0, 0 };
		if (s) {
			v2d sa = load2_float(s + a + k), sb = load2_float(s + b + k);
			allow = noise * select2(sa > sb, sa, sb);
		}
		v2d jump = (v2d)((v2i)(da - db) & magnitude);
		v2i joined = jump <= limit * select2(da < db, da, db) + allow;
		out[k] = ha[k] & hb[k] & (unsigned char)(joined[0] & 1);
		out[k + 1] = ha[k + 1] & hb[k + 1] & (unsigned char)(joined[1] & 1);
	}
	for (; k < n; k++) {
		double allow = s ? G->noise * (s[a + k] > s[b + k] ? s[a + k] : s[b + k]) : 0;
		out[k] = ha[k] & hb[k] & fct_depth_joined(d[a + k], d[b + k], G->limit, steps, allow);
	}
}

/* Row r's has and along flags. */
static void cell_row(const struct grid *G, struct edge_rows *E, long r)
{
	size_t w = (size_t)G->w, c = (size_t)r * w;
	unsigned char *has = E->has[r % 2], *along = E->along[r % 2];
	has_row(G, r, has);
	join_run(G, c, c + 1, w - 1, 1, has, has + 1, along);
	if (G->wrap)
		join_run(G, c + w - 1, c, 1, 1, has + w - 1, has, along + w - 1);
}

/* The flags between rows j and j + 1, whose has flags are made. */
static void between_rows(const struct grid *G, struct edge_rows *E, long j)
{
	size_t w = (size_t)G->w, c = (size_t)j * w, n = c + w;
	const unsigned char *h0 = E->has[j % 2], *h1 = E->has[(j + 1) % 2];
	const double diag = M_SQRT2;
	join_run(G, c, n, w, 1, h0, h1, E->down);
	E->down[w] = E->down[0];
	join_run(G, c, n + 1, w - 1, diag, h0, h1 + 1, E->ad);
	join_run(G, c + 1, n, w - 1, diag, h0 + 1, h1, E->bc);
	if (G->wrap) {
		join_run(G, c + w - 1, n, 1, diag, h0 + w - 1, h1, E->ad + w - 1);
		join_run(G, c, n + w - 1, 1, diag, h0, h1 + w - 1, E->bc + w - 1);
	}
}

/* The corners and edges of square i of the row the rings hold. */
static inline unsigned square_edges(const struct edge_rows *E, long j, long i)
{
	const unsigned char *h0 = E->has[j % 2], *h1 = E->has[(j + 1) % 2];
	return (unsigned)(h0[i] * HA | h0[i + 1] * HB | h1[i] * HC | h1[i + 1] * HD |
	                  E->along[j % 2][i] * JAB | E->along[(j + 1) % 2][i] * JCD |
	                  E->down[i] * JAC | E->down[i + 1] * JBD | E->ad[i] * JAD | E->bc[i] * JBC);
}

/* Eight flags (0 or 1) at p, widened to 16 bits. */
typedef uint8_t v8b __attribute__((vector_size(8)));
typedef uint16_t v8h __attribute__((vector_size(16)));

static inline v8h load8_flags(const unsigned char *p)
{
	v8b v;
	memcpy(&v, p, sizeof v);
	return __builtin_convertvector(v, v8h);
}

/* square_edges of the squares 0 .. n-1 of row j into out, eight at a time
 * (the row's flags have w + 1 entries, n <= w), the rest one by one. */
static void square_edges_row(const struct edge_rows *E, long j, long n, uint16_t *out)
{
	const unsigned char *h0 = E->has[j % 2], *h1 = E->has[(j + 1) % 2];
	const unsigned char *a0 = E->along[j % 2], *a1 = E->along[(j + 1) % 2];
	long i = 0;
	for (; i + 8 <= n; i += 8) {
		v8h e = load8_flags(h0 + i) | load8_flags(h0 + i + 1) << 1 | load8_flags(h1 + i) << 2 |
		        load8_flags(h1 + i + 1) << 3 | load8_flags(a0 + i) << 4 | load8_flags(a1 + i) << 5 |
		        load8_flags(E->down + i) << 6 | load8_flags(E->down + i + 1) << 7 |
		        load8_flags(E->ad + i) << 8 | load8_flags(E->bc + i) << 9;
		memcpy(out + i, &e, sizeof e);
	}
	for (; i < n; i++)
		out[i] = (uint16_t)square_edges(E, j, i);
}

/* x where mask is all ones, y where it is 0. */
static inline uint32_t pick(uint32_t mask, uint32_t x, uint32_t y)
{
	return (x & mask) | (y & ~mask);
}

/* The triangle `which` (FIRST or SECOND) of square q made with code. */
static inline void square_triangle(struct square q, unsigned code, unsigned which, uint32_t t[3])
{
	/* Selects, not branches: the diagonal is as good as random from one
	 * square to the next, and this runs in four passes over the squares.
	 * Masks, as GCC compiled `ad ? x : y` here to branches in the faces'
	 * pass (1.3 of dm2mesh's 15 ms on a 640x480 frame). */
	uint32_t ad = 0u - (uint32_t)((code & DIAG_AD) != 0);   /* all ones for ad */
	if (which == FIRST) {
		t[0] = q.a, t[1] = q.c, t[2] = pick(ad, q.d, q.b);
	} else {
		t[0] = pick(ad, q.a, q.b), t[1] = pick(ad, q.d, q.c), t[2] = pick(ad, q.b, q.d);
	}
}

/* The corners that the triangles of code k use, as bits: a 1, b 2, c 4,
 * d 8. */
static unsigned square_corners(unsigned k)
{
	unsigned first = k & FIRST, second = (k & SECOND) >> 1, ad = (k & DIAG_AD) >> 2;
	return (first | (second & ad)) | ((first & !ad) | second) << 1 |
	       (first | (second & !ad)) << 2 | ((first & ad) | second) << 3;
}

/* Number the cells of a row that a kept triangle uses in vindex[0..w),
 * from *nv on (UINT32_MAX for the others).  A cell is corner a of square
 * i of the row of squares below it, b of square i-1 there, c of square i
 * of the row above and d of square i-1 there (below, above: those rows'
 * codes, zeros beyond the grid; sw squares a row, w on a full cylinder,
 * whose column 0 is the last square's b and d).  corners: square_corners
 * of each code.  Worked out cell by cell from the final codes: marking
 * each square's four corners in a byte per cell chained a square's
 * stores to its neighbour's through memory. */
static void number_row(const unsigned char corners[8], const unsigned char *below,
                       const unsigned char *above, long w, long sw, uint32_t *vindex, size_t *nv)
{
	size_t n = *nv;
	/* per square, bit 0: its left corners (a, c) used, bit 1: its right
	 * ones (b, d); left: the previous square's bit 1 */
	unsigned left = 0;
	if (sw == w && sw > 0)
		left = ((corners[below[sw - 1]] & 3u) | (corners[above[sw - 1]] >> 2)) >> 1;
	long i = 0;
	for (; i < sw; i++) {
		unsigned sides = (corners[below[i]] & 3u) | (corners[above[i]] >> 2);
		unsigned u = left | (sides & 1u);
		left = sides >> 1;
		vindex[i] = u ? (uint32_t)n : UINT32_MAX;
		n += u;
	}
	for (; i < w; i++) {   /* the last column, without squares of its own */
		vindex[i] = left ? (uint32_t)n : UINT32_MAX;
		n += left;
		left = 0;
	}
	*nv = n;
}

/* Union-find over cells; the smaller index is the root, so the result does
 * not depend on the order of the unions and a parent always precedes its
 * child. */
static uint32_t find_root(uint32_t *parent, uint32_t x)
{
	while (parent[x] != x) {
		parent[x] = parent[parent[x]];
		x = parent[x];
	}
	return x;
}

/* Join cell x to the piece whose root is r; returns the root after. */
static inline uint32_t join_root(uint32_t *parent, uint32_t r, uint32_t x)
{
	uint32_t y = find_root(parent, x);
	if (y < r) {
		parent[r] = y;
		return y;
	}
	if (r < y)
		parent[y] = r;
	return r;
}

/* Join the corners of the triangles that code k makes of square q: the
 * corners of one triangle, and the fourth corner when both are made (they
 * share the diagonal) -- three or four finds where uniting each triangle's
 * corners pairwise took four or eight. */
static inline uint32_t join_square(uint32_t *parent, struct square q, unsigned k)
{
	uint32_t t[3];
	square_triangle(q, k, k & FIRST ? FIRST : SECOND, t);
	uint32_t r = find_root(parent, t[0]);
	r = join_root(parent, r, t[1]);
	r = join_root(parent, r, t[2]);
	if ((k & FIRST) && (k & SECOND))
		r = join_root(parent, r, k & DIAG_AD ? q.b : q.d);
	return r;
}

/* join_square of a square whose left neighbour in the row made its SECOND
 * triangle, which holds that square's b and d (this one's a and c): they
 * are in the piece whose root is left, and every triangle of this square
 * has a or c, so only its b and d are left to join -- the same pieces
 * with one to three finds fewer.  Returns the root after. */
static inline uint32_t join_square_after(uint32_t *parent, uint32_t left, struct square q, unsigned k)
{
	unsigned ad = k & DIAG_AD, first = k & FIRST, second = k & SECOND;
	uint32_t r = left;
	if (second || (first && !ad))   /* a triangle with corner b */
		r = join_root(parent, r, q.b);
	if (second || (first && ad))    /* a triangle with corner d */
		r = join_root(parent, r, q.d);
	return r;
}

int fct_grid_mesh(struct fct_mesh *m, const struct fct_range_grid *g,
                  const struct fct_grid_params *p, uint32_t **cell_of,
                  struct fct_grid_stats *stats, struct fct_err *err)
{
	struct grid G = { g, p->max_jump * g->footprint, M_SQRT2 * g->noise_jump, g->width, g->height,
	                  g->wrap && g->width > 2, NULL, NULL };
	size_t ncells;
	if (cell_of)
		*cell_of = NULL;
	if (g->width < 1 || g->height < 1 || fct_mul_size((size_t)g->width, (size_t)g->height, &ncells))
		return fct_fail(err, "grid: bad size %d x %d", g->width, g->height);
	if (ncells > UINT32_MAX / 2)
		return fct_fail(err, "grid: %zu cells are too many", ncells);
	long sw = G.wrap ? G.w : G.w - 1, sh = G.h - 1;   /* squares per row, rows of squares */
	int pieces = p->min_faces > 1;

	/* Per cell a uint32 (with pieces parent, which becomes the piece
	 * labels and then vindex; else vindex), then per square its code, then
	 * a row of zero codes for the squares beyond the grid's top and bottom:
	 * one block, the 2 MB page of a 640x480 grid's uint32s holding the rest
	 * too instead of 150 pages of 4 KB faulted in (squares are no more than
	 * cells, a row no longer than the grid). */
	uint32_t *cells = fct_alloc_big(ncells, sizeof *cells + 2, err);
	uint32_t *parent = pieces ? cells : NULL, *vindex = pieces ? NULL : cells, *count = NULL;
	unsigned char *code = cells ? (unsigned char *)(cells + ncells) : NULL;
	unsigned char *no_squares = code ? code + ncells : NULL;
	size_t pw = (size_t)G.w + 2;   /* a position row and its padding */
	double *rings = fct_alloc_array(pw, 16 * sizeof *rings, err);
	unsigned char *flags = fct_alloc_array((size_t)G.w + 1, 8, err);
	uint16_t *edges = fct_alloc_array((size_t)G.w, sizeof *edges, err);   /* a row's square_edges */
	double *rays = g->xyz ? NULL : fct_alloc_array((size_t)G.w, 2 * sizeof *rays, err);
	struct bend_rows R = { {NULL}, {NULL}, {NULL}, {NULL}, {NULL}, 0, 0, NULL, 0 };
	struct square_rule rules[1024];
	int rc = -1;
	if (!cells || !rings || !flags || !edges || (!g->xyz && !rays))
		goto out;
	memset(no_squares, 0, (size_t)G.w);

	/* The triangles of every square, and the pieces they join. */
	size_t possible = 0, made = 0;
	if (pieces)
		for (size_t c = 0; c < ncells; c++)
			parent[c] = (uint32_t)c;
	memset(rings, 0, 16 * pw * sizeof *rings);   /* the padding is read */
	for (size_t r = 0; r < 4; r++)
		R.x[r] = rings + r * pw, R.y[r] = rings + (4 + r) * pw, R.z[r] = rings + (8 + r) * pw;
	for (size_t r = 0; r < 2; r++)
		R.ad[r] = rings + (12 + r) * pw, R.bc[r] = rings + (14 + r) * pw;
	size_t fw = (size_t)G.w + 1;
	struct edge_rows E = { { flags, flags + fw }, { flags + 2 * fw, flags + 3 * fw },
	                       flags + 4 * fw, flags + 5 * fw, flags + 6 * fw };
	R.prefer = flags + 7 * fw;
	if (rays) {
		G.ray_x = rays, G.ray_z = rays + G.w;
		for (long i = 0; i < G.w; i++)
			G.ray_x[i] = g->col[3 * i], G.ray_z[i] = g->col[3 * i + 2];
	}
	square_rules(rules);
	if (sh > 0)
		cell_row(&G, &E, 0);
	for (long j = 0; j < sh; j++) {
		bend_rows_advance(&G, &R, j);
		R.fast_end = 0;
		if (j >= 1 && j + 2 < G.h)
			prefer_row(&G, &R, j);
		cell_row(&G, &E, j + 1);
		between_rows(&G, &E, j);
		square_edges_row(&E, j, sw, edges);
		/* the root of the left square's piece when it made its SECOND
		 * triangle, else none */
		uint32_t left = UINT32_MAX;
		for (long i = 0; i < sw; i++) {
			struct square q = square_at(&G, i, j);
			const struct square_rule *rule = &rules[edges[i]];
			/* indexed, not `prefer ? ad : bc`, which GCC made a branch
			 * that the as-good-as-random choice mispredicts */
			unsigned k = rule->code[rule->ask ? prefer_ad(&G, &R, i, j) : 0];
			code[j * sw + i] = (unsigned char)k;
			possible += rule->possible;
			if (!(k & (FIRST | SECOND))) {
				left = UINT32_MAX;
				continue;
			}
			made += (k & FIRST ? 1 : 0) + (k & SECOND ? 1 : 0);
			if (pieces) {
				uint32_t r = left != UINT32_MAX ? join_square_after(parent, left, q, k)
				                                : join_square(parent, q, k);
				left = k & SECOND ? r : UINT32_MAX;
			}
		}
	}

	/* Drop the triangles of small pieces.  Every root is the smallest cell
	 * of its piece and a parent precedes its child, so one ascending pass
	 * labels the pieces 0, 1, ... in the order of their roots: a root takes
	 * the next label, any other cell its parent's, already a label.  Count
	 * each piece's triangles; FIRST triangles all have corner a, SECOND
	 * ones corner b. */
	size_t nf = made;
	if (pieces) {
		uint32_t npieces = 0;
		for (size_t c = 0; c < ncells; c++)
			parent[c] = parent[c] == c ? npieces++ : parent[parent[c]];
		if (!(count = calloc(npieces ? npieces : 1, sizeof *count))) {
			fct_fail(err, "out of memory");
			goto out;
		}
		for (long j = 0; j < sh; j++)
			for (long i = 0; i < sw; i++) {
				unsigned k = code[j * sw + i];
				struct square q = square_at(&G, i, j);
				count[parent[q.a]] += k & FIRST;
				count[parent[q.b]] += (k & SECOND) >> 1;
			}
		for (long j = 0; j < sh; j++)
			for (long i = 0; i < sw; i++) {
				unsigned char *k = &code[j * sw + i];
				if (!*k)
					continue;
				struct square q = square_at(&G, i, j);
				if ((*k & FIRST) && count[parent[q.a]] < p->min_faces)
					*k &= (unsigned char)~FIRST, nf--;
				if ((*k & SECOND) && count[parent[q.b]] < p->min_faces)
					*k &= (unsigned char)~SECOND, nf--;
			}
		vindex = parent, parent = NULL;
	}

	/* Vertices: the cells used by a kept triangle, in cell order. */
	size_t nv = 0;
	unsigned char corners[8];
	for (unsigned k = 0; k < 8; k++)
		corners[k] = (unsigned char)square_corners(k);
	for (long j = 0; j < G.h; j++)
		number_row(corners, j < sh ? code + j * sw : no_squares, j > 0 ? code + (j - 1) * sw : no_squares,
		           G.w, sw, vindex + (size_t)j * (size_t)G.w, &nv);
	if (fct_mesh_set_counts_big(m, nv, nf, err))
		goto out;
	/* The faces: a square's corners' vertex numbers read once for its
	 * triangles (fvert's stores could alias vindex for the compiler). */
	uint32_t *fv = m->fvert;
	for (long j = 0; j < sh; j++)
		for (long i = 0; i < sw; i++) {
			unsigned k = code[j * sw + i];
			if (!(k & (FIRST | SECOND)))
				continue;
			struct square q = square_at(&G, i, j);
			struct square v = { vindex[q.a], vindex[q.b], vindex[q.c], vindex[q.d] };
			for (unsigned which = FIRST; which <= SECOND; which <<= 1)
				if (k & which) {
					square_triangle(v, k, which, fv);
					fv += 3;
				}
		}
	/* The positions; vindex becomes cell_of in place (vertex v is a cell
	 * c >= v, and entry v has been read by the time c is reached).  From
	 * depths, P's products with the arrays in locals: the compiler read
	 * them anew through g after each store. */
	for (size_t c = 0, j = 0; j < (size_t)G.h; j++) {
		const double *depth = g->depth, *ray_x = G.ray_x, *ray_z = G.ray_z;
		double ray_y = g->xyz ? 0 : g->row[j], *xyz = m->xyz;
		for (size_t i = 0; i < (size_t)G.w; i++, c++) {
			uint32_t v = vindex[c];
			if (v == UINT32_MAX)
				continue;
			double *p = xyz + 3 * (size_t)v, d = depth[c];
			if (g->xyz)
				P(&G, c, i, j, p);
			else
				p[0] = d * ray_x[i], p[1] = d * ray_y, p[2] = d * ray_z[i];
			vindex[v] = (uint32_t)c;
		}
	}
	if (cell_of) {
		uint32_t *shrunk = realloc(cells, (nv ? nv : 1) * sizeof *cells);   /* vindex's part */
		*cell_of = shrunk ? shrunk : cells;
		cells = NULL;
	}
	if (stats) {
		stats->jump_faces = possible - made;
		stats->speck_faces = made - nf;
	}
	rc = 0;
out:
	free(cells);
	free(count);
	free(rings);
	free(flags);
	free(edges);
	free(rays);
	return rc;
}

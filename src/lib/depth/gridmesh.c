/* gridmesh.c - organised range data to triangles (see gridmesh.h). */
#include "depth/gridmesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/geom.h"

/* What one grid square becomes: which of its two triangles are made and
 * along which diagonal.  Corners: a = (i, j), b = (i+1, j), c = (i, j+1),
 * d = (i+1, j+1).  Diagonal bc: (a, c, b) and (b, c, d); diagonal ad:
 * (a, c, d) and (a, d, b) -- all clockwise in (u, v), which faces the sensor. */
enum { FIRST = 1, SECOND = 2, DIAG_AD = 4 };

struct grid {
	const struct fct_range_grid *g;
	double limit;            /* max_jump * footprint */
	double noise;            /* noise_jump * sqrt(2) */
	int w, h, wrap;
};

static inline int has_data(const struct grid *G, size_t c)
{
	double d = G->g->depth[c];
	return d > 0 && d < HUGE_VAL;
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

/* Both cells on one surface: the depth jump between them, steps grid steps
 * apart, is within the limit. */
static inline int joined(const struct grid *G, size_t a, size_t b, double steps)
{
	const float *s = G->g->sigma;
	double allow = s ? G->noise * (s[a] > s[b] ? s[a] : s[b]) : 0;
	return fct_depth_joined(G->g->depth[a], G->g->depth[b], G->limit, steps, allow);
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


/* Squared distance of point p from the line through a and b. */
static inline double line_distance2(const double p[3], const double a[3], const double b[3])
{
	double ab[3], ap[3], x[3];
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ap, p, a);
	fct_v3_cross(x, ab, ap);
	double l2 = fct_v3_dot(ab, ab);
	return l2 > 0 ? fct_v3_dot(x, x) / l2 : fct_v3_dot(ap, ap);
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

/* prefer_ad on the border of the grid, where neighbours may be missing or
 * wrap around a full cylinder. */
static int prefer_ad_border(const struct grid *G, long i, long j)
{
	double a[3], b[3], c[3], d[3], aa[3], dd[3], bb[3], cc[3], bad = 0, bbc = 0;
	position_at(G, i, j, a), position_at(G, i + 1, j, b);
	position_at(G, i, j + 1, c), position_at(G, i + 1, j + 1, d);
	int around = position_at(G, i - 1, j - 1, aa) && position_at(G, i + 2, j + 2, dd) &&
	             position_at(G, i + 2, j - 1, bb) && position_at(G, i - 1, j + 2, cc);
	if (around) {
		bad = line_distance2(a, aa, d) + line_distance2(d, a, dd);
		bbc = line_distance2(b, bb, c) + line_distance2(c, b, cc);
	}
	return choose_ad(bad, bbc, around, a, b, c, d);
}

/* Inside the grid a square's bends are sums of per-cell terms: the bend
 * along ad is bend_ad(a) + bend_ad(d), bend_ad(x) being x's squared
 * distance from the line through its neighbours up-left and down-right
 * (line_distance2 with the same arguments in the same order, so the same
 * bits), and the bend along bc is bend_bc(b) + bend_bc(c) with the
 * neighbours up-right and down-left.  Each cell's terms are computed once
 * instead of once for each of the two squares that use them, from the
 * positions of the rows around it, which are computed once too.  Rows are
 * kept in rings: positions of rows j-1 .. j+2 and bends of rows j, j+1 while
 * the squares of row j are decided. */
struct bend_rows {
	double *pos[4];          /* 3 per cell, row r in pos[r % 4] */
	double *ad[2], *bc[2];   /* per cell, row r in [r % 2] */
	long npos, nbend;        /* rows computed so far */
};

static void position_row(const struct grid *G, long j, double *out)
{
	for (long i = 0; i < G->w; i++)
		P(G, (size_t)(j * G->w + i), (size_t)i, (size_t)j, out + 3 * i);
}

/* The bends of the cells 1 .. w-2 of row j (0 < j < h-1); cells without data
 * or beside one get values that are never used. */
static void bend_row(const struct bend_rows *R, long j, long w, double *ad, double *bc)
{
	const double *up = R->pos[(j - 1) % 4], *mid = R->pos[j % 4], *down = R->pos[(j + 1) % 4];
	for (long i = 1; i + 1 < w; i++) {
		ad[i] = line_distance2(mid + 3 * i, up + 3 * (i - 1), down + 3 * (i + 1));
		bc[i] = line_distance2(mid + 3 * i, up + 3 * (i + 1), down + 3 * (i - 1));
	}
}

/* Make the rings hold what the squares of row j need. */
static void bend_rows_advance(const struct grid *G, struct bend_rows *R, long j)
{
	for (; R->npos <= j + 2 && R->npos < G->h; R->npos++)
		position_row(G, R->npos, R->pos[R->npos % 4]);
	for (; R->nbend <= j + 1 && R->nbend + 1 < G->h; R->nbend++)
		if (R->nbend > 0)
			bend_row(R, R->nbend, G->w, R->ad[R->nbend % 2], R->bc[R->nbend % 2]);
}

/* prefer_ad of square (i, j) with 1 <= i, i + 2 < w, 1 <= j, j + 2 < h from
 * the rings (bend_rows_advance(j) done). */
static int prefer_ad_inside(const struct grid *G, const struct bend_rows *R, long i, long j)
{
	size_t W = (size_t)G->w, ca = (size_t)j * W + (size_t)i;
	const double *r0 = R->pos[j % 4], *r1 = R->pos[(j + 1) % 4];
	int around = has_data(G, ca - W - 1) && has_data(G, ca + 2 * W + 2) &&
	             has_data(G, ca - W + 2) && has_data(G, ca + 2 * W - 1);
	double bad = 0, bbc = 0;
	if (around) {
		const double *ad0 = R->ad[j % 2], *ad1 = R->ad[(j + 1) % 2];
		const double *bc0 = R->bc[j % 2], *bc1 = R->bc[(j + 1) % 2];
		bad = ad0[i] + ad1[i + 1];
		bbc = bc0[i + 1] + bc1[i];
	}
	return choose_ad(bad, bbc, around, r0 + 3 * i, r0 + 3 * (i + 1), r1 + 3 * i, r1 + 3 * (i + 1));
}

static int prefer_ad(const struct grid *G, const struct bend_rows *R, long i, long j)
{
	if (i >= 1 && j >= 1 && i + 2 < G->w && j + 2 < G->h)
		return prefer_ad_inside(G, R, i, j);
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
 * their ends (fct_depth_joined; 0 where an end has no data).  The test is
 * symmetric in its ends, so a square's top edge is the bottom edge of the
 * square above and its left edge the right edge of the square before: four
 * tests a square instead of six. */
enum { HA = 1, HB = 2, HC = 4, HD = 8, JAB = 16, JCD = 32, JAC = 64, JBD = 128, JAD = 256, JBC = 512 };

/* The triangles of square (i, j) whose corners and edges are e;
 * *possible gets how many its corners with data would allow. */
static unsigned square_code(const struct grid *G, const struct bend_rows *R, long i, long j,
                            unsigned e, unsigned *possible)
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
	int ad = jad && jbc ? prefer_ad(G, R, i, j) : jad;
	if (ad)
		return DIAG_AD | (ac && cd ? FIRST : 0) | (bd && ab ? SECOND : 0);
	if (!jbc)
		return 0;
	return (ac && ab ? FIRST : 0) | (cd && bd ? SECOND : 0);
}

/* Do cells x and y, both with data or not, join across an edge `steps`
 * grid steps long?  0 when either has no data. */
static inline int joined_data(const struct grid *G, int hx, int hy, size_t x, size_t y, double steps)
{
	return hx && hy && joined(G, x, y, steps);
}

/* The corners and edges of square q, the square before it in its row
 * having given *bd_before its right edge (or -1 for none) and the square
 * above having left its bottom edge in *cd_above (or -1 for none); both are
 * updated for the next ones. */
static inline unsigned square_edges(const struct grid *G, struct square q, int *bd_before,
                                    signed char *cd_above)
{
	const double S = 1.0, D = M_SQRT2;
	int ha = has_data(G, q.a), hb = has_data(G, q.b), hc = has_data(G, q.c), hd = has_data(G, q.d);
	int ab = *cd_above >= 0 ? *cd_above : joined_data(G, ha, hb, q.a, q.b, S);
	int ac = *bd_before >= 0 ? *bd_before : joined_data(G, ha, hc, q.a, q.c, S);
	int cd = joined_data(G, hc, hd, q.c, q.d, S), bd = joined_data(G, hb, hd, q.b, q.d, S);
	int ad = joined_data(G, ha, hd, q.a, q.d, D), bc = joined_data(G, hb, hc, q.b, q.c, D);
	*cd_above = (signed char)cd, *bd_before = bd;
	return (unsigned)(ha * HA | hb * HB | hc * HC | hd * HD | ab * JAB | cd * JCD | ac * JAC |
	                  bd * JBD | ad * JAD | bc * JBC);
}

/* The triangle `which` (FIRST or SECOND) of square q made with code. */
static inline void square_triangle(struct square q, unsigned code, unsigned which, uint32_t t[3])
{
	if (code & DIAG_AD) {
		if (which == FIRST)
			t[0] = q.a, t[1] = q.c, t[2] = q.d;
		else
			t[0] = q.a, t[1] = q.d, t[2] = q.b;
	} else {
		if (which == FIRST)
			t[0] = q.a, t[1] = q.c, t[2] = q.b;
		else
			t[0] = q.b, t[1] = q.c, t[2] = q.d;
	}
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
static inline void join_square(uint32_t *parent, struct square q, unsigned k)
{
	uint32_t t[3];
	square_triangle(q, k, k & FIRST ? FIRST : SECOND, t);
	uint32_t r = find_root(parent, t[0]);
	r = join_root(parent, r, t[1]);
	r = join_root(parent, r, t[2]);
	if ((k & FIRST) && (k & SECOND))
		join_root(parent, r, k & DIAG_AD ? q.b : q.d);
}

int fct_grid_mesh(struct fct_mesh *m, const struct fct_range_grid *g,
                  const struct fct_grid_params *p, uint32_t **cell_of,
                  struct fct_grid_stats *stats, struct fct_err *err)
{
	struct grid G = { g, p->max_jump * g->footprint, M_SQRT2 * g->noise_jump, g->width, g->height,
	                  g->wrap && g->width > 2 };
	size_t ncells, nsq;
	if (cell_of)
		*cell_of = NULL;
	if (g->width < 1 || g->height < 1 || fct_mul_size((size_t)g->width, (size_t)g->height, &ncells))
		return fct_fail(err, "grid: bad size %d x %d", g->width, g->height);
	if (ncells > UINT32_MAX / 2)
		return fct_fail(err, "grid: %zu cells are too many", ncells);
	long sw = G.wrap ? G.w : G.w - 1, sh = G.h - 1;   /* squares per row, rows of squares */
	nsq = sw > 0 && sh > 0 ? (size_t)sw * (size_t)sh : 0;
	int pieces = p->min_faces > 1;

	/* With pieces, parent becomes the piece labels and then vindex. */
	unsigned char *code = fct_alloc_array(nsq, 1, err);
	uint32_t *parent = pieces ? fct_alloc_big(ncells, sizeof *parent, err) : NULL;
	uint32_t *vindex = pieces ? NULL : fct_alloc_big(ncells, sizeof *vindex, err);
	uint32_t *count = NULL;
	unsigned char *used = calloc(ncells ? ncells : 1, 1);   /* a kept triangle uses the cell */
	double *rings = fct_alloc_array((size_t)G.w, 16 * sizeof *rings, err);
	signed char *cd_above = fct_alloc_array((size_t)G.w, 1, err);
	struct bend_rows R = { {NULL}, {NULL}, {NULL}, 0, 0 };
	int rc = -1;
	if (!code || (pieces ? !parent : !vindex) || !used || !rings || !cd_above) {
		if (!used)
			fct_fail(err, "out of memory");
		goto out;
	}

	/* The triangles of every square, and the pieces they join. */
	size_t possible = 0, made = 0;
	if (pieces)
		for (size_t c = 0; c < ncells; c++)
			parent[c] = (uint32_t)c;
	for (int r = 0; r < 4; r++)
		R.pos[r] = rings + (size_t)r * 3 * (size_t)G.w;
	for (int r = 0; r < 2; r++)
		R.ad[r] = rings + (12 + (size_t)r) * (size_t)G.w, R.bc[r] = rings + (14 + (size_t)r) * (size_t)G.w;
	memset(cd_above, -1, (size_t)sw);
	for (long j = 0; j < sh; j++) {
		bend_rows_advance(&G, &R, j);
		int bd_before = -1;
		for (long i = 0; i < sw; i++) {
			struct square q = square_at(&G, i, j);
			unsigned e = square_edges(&G, q, &bd_before, &cd_above[i]);
			unsigned pos, k = square_code(&G, &R, i, j, e, &pos);
			code[j * sw + i] = (unsigned char)k;
			possible += pos;
			if (!(k & (FIRST | SECOND)))
				continue;
			made += (k & FIRST ? 1 : 0) + (k & SECOND ? 1 : 0);
			if (pieces) {
				join_square(parent, q, k);
				continue;
			}
			for (unsigned which = FIRST; which <= SECOND; which <<= 1)
				if (k & which) {
					uint32_t t[3];
					square_triangle(q, k, which, t);
					used[t[0]] = used[t[1]] = used[t[2]] = 1;
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
				if (k & FIRST)
					count[parent[q.a]]++;
				if (k & SECOND)
					count[parent[q.b]]++;
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
				for (unsigned which = FIRST; which <= SECOND; which <<= 1)
					if (*k & which) {
						uint32_t t[3];
						square_triangle(q, *k, which, t);
						used[t[0]] = used[t[1]] = used[t[2]] = 1;
					}
			}
		vindex = parent, parent = NULL;
	}

	/* Vertices: the cells used by a kept triangle, in cell order. */
	size_t nv = 0;
	for (size_t c = 0; c < ncells; c++)
		vindex[c] = used[c] ? (uint32_t)nv++ : UINT32_MAX;
	if (fct_mesh_set_counts_big(m, nv, nf, err))
		goto out;
	uint32_t *fv = m->fvert;
	for (long j = 0; j < sh; j++)
		for (long i = 0; i < sw; i++) {
			unsigned k = code[j * sw + i];
			struct square q = square_at(&G, i, j);
			for (unsigned which = FIRST; which <= SECOND; which <<= 1)
				if (k & which) {
					uint32_t t[3];
					square_triangle(q, k, which, t);
					*fv++ = vindex[t[0]], *fv++ = vindex[t[1]], *fv++ = vindex[t[2]];
				}
		}
	/* The positions; vindex becomes cell_of in place (vertex v is a cell
	 * c >= v, and entry v has been read by the time c is reached). */
	for (size_t c = 0, j = 0; j < (size_t)G.h; j++)
		for (size_t i = 0; i < (size_t)G.w; i++, c++) {
			uint32_t v = vindex[c];
			if (v == UINT32_MAX)
				continue;
			P(&G, c, i, j, m->xyz + 3 * (size_t)v);
			vindex[v] = (uint32_t)c;
		}
	if (cell_of) {
		uint32_t *shrunk = realloc(vindex, (nv ? nv : 1) * sizeof *vindex);
		*cell_of = shrunk ? shrunk : vindex;
		vindex = NULL;
	}
	if (stats) {
		stats->jump_faces = possible - made;
		stats->speck_faces = made - nf;
	}
	rc = 0;
out:
	free(code);
	free(parent);
	free(vindex);
	free(count);
	free(used);
	free(rings);
	free(cd_above);
	return rc;
}

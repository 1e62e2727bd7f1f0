/* mcubesfast.c - the marching cubes the programs run (fct_mcubes,
 * fct_mcubes_stats): the output of mcubes.c's plain extraction, bit for bit
 * (tests/unit/test_mcubes.c compares them), computed in passes over the
 * blocks on threads, with SSE2 where rows and vertices are worked side by
 * side and with the loads of the next block started while one is worked on.
 * What the output is, and the contour tables, are mcubes.c's; the
 * arithmetic that fixes the output's bits is mcubespriv.h's, shared.
 *
 * Passes over the blocks.  Pass 0 turns each block into rows of sign and
 * "observed" bits.  Pass 1 reads each block and its upper neighbours' bits
 * into 9x9 rows, marks the crossing lattice edges each voxel owns (the edges
 * from it towards +x, +y, +z) in three 512-bit masks and counts exactly the
 * block's triangles and centroid vertices (running the decider on its
 * ambiguous cubes and keeping the outcomes for the triangle pass); it hands
 * each upper neighbour its extracted cubes along that neighbour's lower
 * faces.  Pass 2 keeps the crossing edges that an extracted cube uses (the
 * others, at the rim of the observed region, would be vertices no triangle
 * uses) and counts the block's vertices per z layer.  Prefix sums in block
 * order then fix every block's place in the output, so that the last two
 * passes -- the vertices (values gathered once per block, gradients once
 * per corner; the rows a block reads are found, and their loads started,
 * while the block before it is worked on, so that its cache misses overlap
 * that work) and the triangles -- write disjoint ranges and run on threads
 * with the same bytes for any count.  A vertex's number is its block's
 * base plus a popcount in its masks; the triangle pass writes the numbers
 * of the edges a block's cubes use (its own and its upper neighbours') into
 * a 3x9x9x9 table once per block, a row at a time from tabulated bit
 * prefixes, and reads a cube's fans from it through tabulated offsets; the
 * cubes with a centroid vertex (which reads back the vertices of its loop)
 * are queued and worked through back to back.  Blocks lie apart in memory,
 * where the hardware's prefetchers do not follow, so passes 0 and 1 and
 * the triangle pass start loading the next block's lines (its values, its
 * upper neighbours' bits or records) while they work on one.  The bit rows
 * of a z layer are walked as one 64-bit word, so that empty rows cost no
 * branch; where rows are combined (pass 1's rows and masks, a layer's sign
 * patterns, the vertex pass's window), the eight rows of a layer are 16-bit
 * lanes of one SSE2 register, the scalar code kept for builds without SSE2.
 * The vertices' normals are worked in float, four vertices side by side
 * (mcubespriv.h's float operations, so the same bits), and in double where
 * float would not be exact enough (gradients that nearly cancel); their
 * positions in double.  The measurements behind these choices are in
 * bench/NOTES.md. */
#include "fusion/mcubespriv.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <pthread.h>

#include "core/clock.h"
#include "core/par.h"

/* The functions the time goes into start on a cache line, so that their
 * loops fall alike on the lines (and the branch predictor's entries) in
 * every build, whatever the code linked before them. */
#if defined(__GNUC__)
#define HOT __attribute__((aligned(64)))
#else
#define HOT
#endif

/* The fast path's tables ------------------------------------------------- */

/* A block's vertex table: the vertex of the lattice edge along axis a from
 * local corner (x, y, z), 0..8 each (the block's own edges and those of its
 * upper neighbours that its cubes use). */
#define VT_IDX(a, x, y, z) ((a) * 729 + (x) + 9 * (y) + 81 * (z))

/* Built once per process beside the contours (struct mc_cases). */
struct fast_tables {
	uint16_t toff[MC_VARIANTS][36];         /* the fans' edges (when no loop has a
	                                         * centre) as places in a block's vertex
	                                         * table, from the cube's */
	uint16_t eoff[12];                      /* edge e's place in it, from the cube's */
	uint8_t amb_corners[64];                /* the corners of a set of faces */
	uint8_t bpre[256][8];                   /* bits of a byte below bit x */
};

static struct fast_tables tables;
static pthread_once_t tables_once = PTHREAD_ONCE_INIT;

static void tables_init(void)
{
	const struct mc_cases *C = mcubes_cases();
	struct fast_tables *T = &tables;
	for (int e = 0; e < 12; e++) {
		int lo = C->G.edge_lo[e];
		T->eoff[e] = (uint16_t)(VT_IDX(e >> 2, lo & 1, lo >> 1 & 1, lo >> 2));
	}
	for (int n = 0; n < MC_VARIANTS; n++) {
		const struct mc_case *mc = &C->var[n];
		const uint8_t *ed = mc->edge;
		for (int l = 0, j = 0; l < mc->nloops && !C->ncentre[n]; ed += mc->len[l], l++)
			for (int i = 1; i + 1 < mc->len[l]; i++, j += 3) {
				T->toff[n][j] = T->eoff[ed[0]];
				T->toff[n][j + 1] = T->eoff[ed[i]];
				T->toff[n][j + 2] = T->eoff[ed[i + 1]];
			}
	}
	for (int faces = 0; faces < 64; faces++)
		for (int f = 0; f < 6; f++)
			for (int k = 0; faces >> f & 1 && k < 4; k++)
				T->amb_corners[faces] |= (uint8_t)(1u << C->G.face_corners[f][k]);
	for (int b = 0; b < 256; b++)
		for (int x = 0; x < 8; x++)
			T->bpre[b][x] = (uint8_t)__builtin_popcount((unsigned)b & ((1u << x) - 1));
}

/* Per-block data ------------------------------------------------------------ */

#define NONE UINT32_MAX

/* A block's own voxels as bits, row z * 8 + y, bit x: negative, and
 * observed (inside the clip box); seen: observed, the clip box aside (the
 * vertex pass's gradients read beyond the box), so that the vertex pass
 * reads no weights. */
struct own {
	uint8_t neg[64], obs[64], seen[64];
	int32_t b[3];           /* the block's coordinates */
	int anyobs;
};

/* Ambiguous cubes per block whose decision pass 1 keeps; the triangle pass
 * decides the others again. */
#define AMB_KEEP 32

/* The extracted cubes of a block's lower neighbours along its lower faces,
 * which pass 2 needs: pass 1 of each neighbour writes its own field (its
 * only writer), so that pass 2 reads one record instead of seven.  x: the
 * -x neighbour's cubes (7, y, z), bit 8 * z + y; y: the -y neighbour's
 * rows (y = 7), byte z; z: the -z neighbour's layer z = 7, byte y (bit x
 * in each); xy: (7, 7, z), bit z; xz: (7, y, 7), bit y; yz: (x, 7, 7), bit
 * x; xyz: (7, 7, 7). */
struct rim {
	uint64_t x, y, z;
	uint8_t xy, xz, yz, xyz;
};

/* Pass-1 record of a block that owns crossings or has extracted cubes. */
struct aux {
	uint8_t bits[3][64];    /* crossing edges it owns, per axis: row z * 8 + y, bit x;
	                         * after pass 2 only those an extracted cube uses */
	uint16_t pre[3][8];     /* the block's vertices before each z layer of rows */
	uint32_t base, nverts;  /* its first edge vertex, their count */
	uint32_t tbase, ntri;   /* its first triangle, their count */
	uint32_t cbase, ncent;  /* its first centroid vertex (numbered after every
	                         * edge vertex), their count */
	uint32_t block;
	int32_t up[8];          /* block + (k & 1, k >> 1 & 1, k >> 2): its index, -1 absent */
	uint16_t neg[9][9];     /* [z][y]: bit x (0..8) set when negative */
	uint8_t active[64];     /* row z * 8 + y: bit x set when cube (x, y, z) is extracted */
	uint8_t any_active;
	uint8_t nvar;           /* decisions kept in var */
	uint8_t var[AMB_KEEP];  /* the decider's outcome (variant) of its first ambiguous
	                         * cubes, in cube order, for the triangle pass */
	uint32_t ncubes, namb;  /* its extracted cubes, those with an ambiguous face */
};

/* The sdf around the current block, local -1..9 on each axis (only the
 * voxels a central difference at 0..8 reads); NaN where unobserved. */
#define CW 11
#define CIDX(x, y, z) ((x) + 1 + CW * ((y) + 1 + CW * ((z) + 1)))

struct worker;

/* The run, shared by the threads: tables, per-block records, output. */
struct mc {
	const struct fct_voxgrid *g;
	float thr;
	int colour;
	double voxel;
	const int32_t *lo, *hi;         /* clip box or NULL */
	const struct mc_cases *C;       /* the contours */
	const struct fast_tables *T;

	struct own *own;                /* per block */
	uint32_t *auxof;                /* per block: its pass-1 record, or NONE (apart
	                                 * from own: the triangle pass reads it for
	                                 * every upper neighbour, 4 bytes in cache) */
	/* the blocks' indices over their bounding box, x fastest from map_lo
	 * (-1: absent), when that box is small enough (blockmap) */
	int32_t *map, map_lo[3];
	size_t map_dim[3];
	struct rim *rim;                /* per block */
	struct aux *aux;                /* per block with an observed voxel */
	uint32_t *live;                 /* aux records with something, in block order */
	size_t nlive;
	size_t nverts;                  /* edge vertices */

	struct mc_out o;                /* output columns */
	uint32_t *tri;

	struct worker *w;               /* one per thread */
};

/* A block and its neighbours (dx, dy, dz in -1..1 at (dx + 1) + 3 * (dy +
 * 1) + 9 * (dz + 1)); for the vertex pass also the voxels its vertices read:
 * need[z][y], bit x: the corners (0..8) at the ends of its crossing edges,
 * whose gradients are needed; win[z + 1][y + 1], bit x + 1: those and their
 * six neighbours, wrows[z + 1] bit y + 1 set where that row has any.  The
 * rows are padded to WROW so that plan() works on them eight at a time. */
#define WROW 16
struct blockctx {
	const struct fct_voxblock *nb[27];      /* looked up on demand */
	const uint8_t *seen[27];                /* their struct own seen bits (when nb) */
	unsigned nb_done;
	int32_t bx, by, bz;
	double coord[3][9];                     /* (8 * block + i) * voxel on each axis */
	uint16_t need[9][WROW];
	uint16_t win[CW][WROW];
	uint16_t wrows[CW];
};

/* A cube with a centroid vertex, queued by the triangle pass: its
 * centroid averages the loop's vertices, which the vertex pass wrote long
 * before (cache misses); worked through back to back, the cubes' reads
 * overlap. */
struct centred {
	uint32_t vid[12];       /* its crossed edges' vertices, by edge */
	uint32_t *t;            /* its triangles' place in the output */
	uint32_t cid;           /* its first centroid vertex */
	int id;                 /* its contour */
};

#define CQ 256          /* queue length */

/* One thread's scratch: the current block, its neighbours, its values. */
struct worker {
	const struct mc *M;
	struct blockctx c[2];           /* the vertex pass: the current block and the next */
	struct blockctx *cur;
	float val[CW * CW * CW];        /* valid where the block's vertices need it */
	_Alignas(16) float grad4[729][4]; /* gradients at corners 0..8 (x, y, z, 0), where needed */
	/* the vertices of one axis of a block (axis_normals): the value index
	 * (CIDX) and gradient index of each edge's lower end, its local (x, y,
	 * z) as x | y << 4 | z << 8; then its t, and the normals of the
	 * last four when fewer (the others go to the output directly) */
	uint16_t lc[512], lg[512], lp[512];
	double lt[512];
	float ln[3][512];
	uint32_t vt[3 * 729];           /* the triangle pass: the block's vertex table */
	struct centred cq[CQ];          /* its cubes with a centroid, queued */
	unsigned ncq;
	struct fct_mcubes_stats st;
	char pad[64];                   /* no cache line shared with the next thread's */
};

/* Index of block (bx, by, bz), -1 when absent: one read from M->map where
 * there is one, instead of a probe of the grid's hash. */
static inline long block_index(const struct mc *M, int32_t bx, int32_t by, int32_t bz)
{
	if (!M->map)
		return fct_voxgrid_index(M->g, bx, by, bz);
	size_t x = (size_t)((int64_t)bx - M->map_lo[0]), y = (size_t)((int64_t)by - M->map_lo[1]);
	size_t z = (size_t)((int64_t)bz - M->map_lo[2]);
	if (x >= M->map_dim[0] || y >= M->map_dim[1] || z >= M->map_dim[2])
		return -1;
	return M->map[x + M->map_dim[0] * (y + M->map_dim[1] * z)];
}

/* Neighbour n of c (struct blockctx nb) is block i (-1: absent). */
static inline void ctx_set(const struct mc *M, struct blockctx *c, int n, long i)
{
	c->nb_done |= 1u << n;
	c->nb[n] = i >= 0 ? fct_voxgrid_at(M->g, (size_t)i) : NULL;
	c->seen[n] = i >= 0 ? M->own[i].seen : NULL;
	if (i >= 0)
		__builtin_prefetch(c->seen[n]);
}

/* Make b, with record A, the block of c. */
static void ctx_block(const struct mc *M, struct blockctx *c, const struct fct_voxblock *b,
                      const struct aux *A)
{
	c->bx = b->bx, c->by = b->by, c->bz = b->bz;
	for (int i = 0; i < 9; i++) {
		c->coord[0][i] = (double)(8 * c->bx + i) * M->voxel;
		c->coord[1][i] = (double)(8 * c->by + i) * M->voxel;
		c->coord[2][i] = (double)(8 * c->bz + i) * M->voxel;
	}
	c->nb_done = 0;
	for (int k = 0; k < 8; k++) {
		int n = (k & 1) + 1 + 3 * ((k >> 1 & 1) + 1 + 3 * ((k >> 2) + 1));
		ctx_set(M, c, n, A->up[k]);
	}
}

/* Neighbour block (dx, dy, dz) in -1..1 of c's block. */
static inline const struct fct_voxblock *ctx_nb(const struct mc *M, struct blockctx *c, int dx,
                                                int dy, int dz)
{
	int k = (dx + 1) + 3 * ((dy + 1) + 3 * (dz + 1));
	if (!(c->nb_done >> k & 1))
		ctx_set(M, c, k, block_index(M, c->bx + dx, c->by + dy, c->bz + dz));
	return c->nb[k];
}

/* Voxel at local coordinates (x, y, z) in -8..15 of c's block: its block
 * (NULL when absent) and index. */
static inline const struct fct_voxblock *ctx_voxel(const struct mc *M, struct blockctx *c, int x,
                                                   int y, int z, int *v)
{
	int dx = (x + 8) / 8 - 1, dy = (y + 8) / 8 - 1, dz = (z + 8) / 8 - 1;
	*v = ((x + 8) & 7) + 8 * (((y + 8) & 7) + 8 * ((z + 8) & 7));
	return ctx_nb(M, c, dx, dy, dz);
}

/* Bits of 8 consecutive voxels: negative, observed. */
static inline void bits8(const float *s, const float *w, float thr, unsigned *neg, unsigned *obs)
{
#if defined(__SSE2__)
	__m128 zero = _mm_setzero_ps(), t = _mm_set1_ps(thr), big = _mm_set1_ps(FLT_MAX);
	__m128 absm = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
	__m128 s0 = _mm_loadu_ps(s), s1 = _mm_loadu_ps(s + 4);
	__m128 w0 = _mm_loadu_ps(w), w1 = _mm_loadu_ps(w + 4);
	*neg = (unsigned)(_mm_movemask_ps(_mm_cmplt_ps(s0, zero)) |
	                  _mm_movemask_ps(_mm_cmplt_ps(s1, zero)) << 4);
	__m128 o0 = _mm_and_ps(_mm_cmpge_ps(w0, t), _mm_cmple_ps(_mm_and_ps(s0, absm), big));
	__m128 o1 = _mm_and_ps(_mm_cmpge_ps(w1, t), _mm_cmple_ps(_mm_and_ps(s1, absm), big));
	*obs = (unsigned)(_mm_movemask_ps(o0) | _mm_movemask_ps(o1) << 4);
#else
	unsigned n = 0, o = 0;
	for (int x = 0; x < 8; x++) {
		n |= (unsigned)(s[x] < 0) << x;
		o |= (unsigned)mc_observed(s[x], w[x], thr) << x;
	}
	*neg = n, *obs = o;
#endif
}

#if defined(__SSE2__)
/* Bits of 16 consecutive voxels (two rows), as bits8 does for each eight:
 * the compares' lanes packed to bytes, one movemask each. */
static inline void bits16(const float *s, const float *w, float thr, unsigned *neg, unsigned *obs)
{
	__m128 zero = _mm_setzero_ps(), t = _mm_set1_ps(thr), big = _mm_set1_ps(FLT_MAX);
	__m128 absm = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
#define NEG(k) _mm_castps_si128(_mm_cmplt_ps(_mm_loadu_ps(s + 4 * (k)), zero))
#define OBS(k)                                                                     \
	_mm_castps_si128(_mm_and_ps(_mm_cmpge_ps(_mm_loadu_ps(w + 4 * (k)), t),    \
	                            _mm_cmple_ps(_mm_and_ps(_mm_loadu_ps(s + 4 * (k)), absm), big)))
	__m128i nb = _mm_packs_epi16(_mm_packs_epi32(NEG(0), NEG(1)), _mm_packs_epi32(NEG(2), NEG(3)));
	__m128i ob = _mm_packs_epi16(_mm_packs_epi32(OBS(0), OBS(1)), _mm_packs_epi32(OBS(2), OBS(3)));
#undef NEG
#undef OBS
	*neg = (unsigned)_mm_movemask_epi8(nb);
	*obs = (unsigned)_mm_movemask_epi8(ob);
}
#endif

/* 8 consecutive voxels into dst: the sdf where bit x of seen is set
 * (observed, struct own), NaN elsewhere. */
static inline void vals8_seen(const float *s, unsigned seen, float *dst)
{
#if defined(__SSE2__)
	const __m128i lo = _mm_setr_epi32(1, 2, 4, 8), hi = _mm_setr_epi32(16, 32, 64, 128);
	__m128i b = _mm_set1_epi32((int)seen);
	__m128 m0 = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(b, lo), lo));
	__m128 m1 = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(b, hi), hi));
	__m128 nan = _mm_set1_ps(NAN);
	_mm_storeu_ps(dst, _mm_or_ps(_mm_and_ps(m0, _mm_loadu_ps(s)), _mm_andnot_ps(m0, nan)));
	_mm_storeu_ps(dst + 4, _mm_or_ps(_mm_and_ps(m1, _mm_loadu_ps(s + 4)), _mm_andnot_ps(m1, nan)));
#else
	for (int x = 0; x < 8; x++)
		dst[x] = seen >> x & 1 ? s[x] : NAN;
#endif
}

/* Voxel v of block b (NULL: absent) with its seen bits: its sdf, or NaN. */
static inline float val1(const struct fct_voxblock *b, const uint8_t *seen, int v)
{
	return b && seen[v >> 3] >> (v & 7) & 1 ? b->sdf[v] : NAN;
}

/* The 8 rows b[0..7] (8 bits each) as one word, row j in bits 8j..8j+7. */
static inline uint64_t rows8(const uint8_t *b)
{
	uint64_t v = 0;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
	memcpy(&v, b, 8);
#else
	for (int j = 0; j < 8; j++)
		v |= (uint64_t)b[j] << 8 * j;
#endif
	return v;
}

/* Set bits of v (no popcnt instruction in the baseline x86-64). */
static inline int pop64(uint64_t v)
{
	v -= (v >> 1) & UINT64_C(0x5555555555555555);
	v = (v & UINT64_C(0x3333333333333333)) + ((v >> 2) & UINT64_C(0x3333333333333333));
	v = (v + (v >> 4)) & UINT64_C(0x0F0F0F0F0F0F0F0F);
	return (int)((v * UINT64_C(0x0101010101010101)) >> 56);
}

/* need, win and wrows of c (struct blockctx) for record A. */
static void plan_rows(const struct aux *A, struct blockctx *c)
{
	uint16_t(*need)[WROW] = c->need, (*win)[WROW] = c->win;
	memset(win, 0, sizeof c->win);
#if defined(__SSE2__)
	/* rows y = 0..15 of a layer as two registers of eight 16-bit lanes;
	 * UP(k) moves row y to y + k */
	const __m128i zero = _mm_setzero_si128();
#define BITS8(p) _mm_unpacklo_epi8(_mm_loadl_epi64((const __m128i *)(p)), zero)
#define LD(r, h) _mm_loadu_si128((const __m128i *)&(r)[8 * (h)])
#define OR(r, h, v) _mm_storeu_si128((__m128i *)&(r)[8 * (h)], _mm_or_si128(LD(r, h), v))
	__m128i carry = zero;   /* b2 of the layer below: need at z + 1 */
	for (int z = 0; z < 8; z++) {
		__m128i b0 = BITS8(A->bits[0] + 8 * z), b1 = BITS8(A->bits[1] + 8 * z);
		__m128i b2 = BITS8(A->bits[2] + 8 * z);
		__m128i own = _mm_or_si128(_mm_or_si128(b0, _mm_slli_epi16(b0, 1)), _mm_or_si128(b1, b2));
		_mm_storeu_si128((__m128i *)need[z], _mm_or_si128(_mm_or_si128(own, carry),
		                                                 _mm_slli_si128(b1, 2)));
		_mm_storeu_si128((__m128i *)&need[z][8], _mm_srli_si128(b1, 14));
		carry = b2;
	}
	_mm_storeu_si128((__m128i *)need[8], carry);
	_mm_storeu_si128((__m128i *)&need[8][8], zero);
	for (int z = 0; z < 9; z++) {
		__m128i lo = LD(need[z], 0), hi = LD(need[z], 1);
		__m128i clo = _mm_or_si128(_mm_or_si128(lo, _mm_slli_epi16(lo, 1)), _mm_slli_epi16(lo, 2));
		__m128i chi = _mm_or_si128(_mm_or_si128(hi, _mm_slli_epi16(hi, 1)), _mm_slli_epi16(hi, 2));
		__m128i slo = _mm_slli_epi16(lo, 1), shi = _mm_slli_epi16(hi, 1);
		/* S moved up one row: the window's rows beside, above and below */
		__m128i s1lo = _mm_slli_si128(slo, 2), s1hi = _mm_or_si128(_mm_slli_si128(shi, 2), _mm_srli_si128(slo, 14));
		OR(win[z + 1], 0, _mm_or_si128(_mm_or_si128(_mm_slli_si128(clo, 2), slo), _mm_slli_si128(slo, 4)));
		OR(win[z + 1], 1, _mm_or_si128(_mm_or_si128(_mm_or_si128(_mm_slli_si128(chi, 2), _mm_srli_si128(clo, 14)), shi),
		                               _mm_or_si128(_mm_slli_si128(shi, 4), _mm_srli_si128(slo, 12))));
		OR(win[z], 0, s1lo);
		OR(win[z], 1, s1hi);
		OR(win[z + 2], 0, s1lo);
		OR(win[z + 2], 1, s1hi);
	}
	for (int wz = 0; wz < CW; wz++) {
		__m128i empty = _mm_packs_epi16(_mm_cmpeq_epi16(LD(win[wz], 0), zero),
		                                _mm_cmpeq_epi16(LD(win[wz], 1), zero));
		c->wrows[wz] = (uint16_t)(~_mm_movemask_epi8(empty) & ((1u << CW) - 1));
	}
#undef BITS8
#undef LD
#undef OR
#else
	memset(need, 0, sizeof c->need);
	for (int r = 0; r < 64; r++) {
		int y = r & 7, z = r >> 3;
		unsigned b0 = A->bits[0][r], b1 = A->bits[1][r], b2 = A->bits[2][r];
		need[z][y] |= (uint16_t)(b0 | b0 << 1 | b1 | b2);
		need[z][y + 1] |= (uint16_t)b1;
		need[z + 1][y] |= (uint16_t)b2;
	}
	for (int z = 0; z < 9; z++)
		for (int y = 0; y < 9; y++) {
			unsigned n = need[z][y];
			win[z + 1][y + 1] |= (uint16_t)(n | n << 1 | n << 2);
			win[z + 1][y] |= (uint16_t)(n << 1);
			win[z + 1][y + 2] |= (uint16_t)(n << 1);
			win[z][y + 1] |= (uint16_t)(n << 1);
			win[z + 2][y + 1] |= (uint16_t)(n << 1);
		}
	for (int wz = 0; wz < CW; wz++) {
		c->wrows[wz] = 0;
		for (int wy = 0; wy < CW; wy++)
			c->wrows[wz] |= (uint16_t)((win[wz][wy] != 0) << wy);
	}
#endif
}

/* Plan block record A's vertex reads in c: its neighbours, need and win
 * (struct blockctx), and start loading every row of the window, so that
 * the misses on the block and its neighbours are on their way while the
 * block before is worked on. */
HOT static void plan(const struct mc *M, struct blockctx *c, const struct aux *A)
{
	ctx_block(M, c, fct_voxgrid_at(M->g, A->block), A);
	plan_rows(A, c);
	for (int wz = 0; wz < CW; wz++)
		for (unsigned rows = c->wrows[wz]; rows; rows &= rows - 1) {
			int wy = __builtin_ctz(rows);
			unsigned m = c->win[wz][wy];
			int z = wz - 1, y = wy - 1;
			int dz = (z + 8) / 8 - 1, dy = (y + 8) / 8 - 1;
			int row = 8 * ((y + 8) & 7) + 64 * ((z + 8) & 7);
			const struct fct_voxblock *b;
			if ((m & 0x1FE) && (b = ctx_nb(M, c, 0, dy, dz))) {
				__builtin_prefetch(b->sdf + row);
				__builtin_prefetch(b->sdf + row + 7);
			}
			if ((m & 0x001) && (b = ctx_nb(M, c, -1, dy, dz)))
				__builtin_prefetch(b->sdf + row + 7);
			if ((m & 0x600) && (b = ctx_nb(M, c, 1, dy, dz)))
				__builtin_prefetch(b->sdf + row);
		}
}

/* Read what the vertices of the planned block c need into w->val: the ends
 * of its crossing edges and their six neighbours; nothing else of w->val is
 * touched. */
static void gather(struct worker *w, const struct blockctx *c)
{
	for (int wz = 0; wz < CW; wz++)
		for (unsigned rows = c->wrows[wz]; rows; rows &= rows - 1) {
			int wy = __builtin_ctz(rows);
			unsigned m = c->win[wz][wy];
			int z = wz - 1, y = wy - 1;
			int dz = (z + 8) / 8 - 1, dy = (y + 8) / 8 - 1;
			int r = ((y + 8) & 7) + 8 * ((z + 8) & 7), row = 8 * r;
			float *dst = w->val + CIDX(0, y, z);
			/* plan() looked up every neighbour read here */
			int n = 3 * (dy + 1) + 9 * (dz + 1);
			const struct fct_voxblock *const *nb = c->nb + n;
			const uint8_t *const *seen = c->seen + n;
			if (m & 0x1FE) {
				if (nb[1])
					vals8_seen(nb[1]->sdf + row, seen[1][r], dst);
				else
					for (int x = 0; x < 8; x++)
						dst[x] = NAN;
			}
			if (m & 0x001)
				dst[-1] = val1(nb[0], seen[0], row + 7);
			if (m & 0x200)
				dst[8] = val1(nb[2], seen[2], row);
			if (m & 0x400)
				dst[9] = val1(nb[2], seen[2], row + 1);
		}
}

/* The sdf gradient at local voxel (x, y, z) (observed, value s0), in
 * double (mc_diff_d): the fallback's (exact_normal). */
static void gradient(const float *val, int x, int y, int z, double s0, double g[3])
{
	static const int step[3] = { 1, CW, CW * CW };
	const float *p = val + CIDX(x, y, z);
	for (int a = 0; a < 3; a++)
		g[a] = mc_diff_d(s0, p[step[a]], p[-step[a]]);
}

/* The same in float (mc_diff_f) at the voxel at val + c, into g[0..2] (g[3]
 * = 0): with SSE2 the three components side by side, the same float
 * operations. */
static inline void gradient4(const float *val, int c, float g[4])
{
	const float *p = val + c;
#if defined(__SSE2__)
	__m128 s = _mm_set1_ps(p[0]), half = _mm_set1_ps(0.5f), one = _mm_set1_ps(1.0f);
	__m128 sp = _mm_setr_ps(p[1], p[CW], p[CW * CW], p[0]);
	__m128 sm = _mm_setr_ps(p[-1], p[-CW], p[-CW * CW], p[0]);
	__m128 hp = _mm_cmpord_ps(sp, sp), hm = _mm_cmpord_ps(sm, sm);
	__m128 P = _mm_or_ps(_mm_and_ps(hp, sp), _mm_andnot_ps(hp, s));
	__m128 M = _mm_or_ps(_mm_and_ps(hm, sm), _mm_andnot_ps(hm, s));
	__m128 both = _mm_and_ps(hp, hm);
	__m128 f = _mm_or_ps(_mm_and_ps(both, half), _mm_andnot_ps(both, one));
	_mm_store_ps(g, _mm_mul_ps(f, _mm_sub_ps(P, M)));
#else
	static const int step[3] = { 1, CW, CW * CW };
	for (int a = 0; a < 3; a++)
		g[a] = mc_diff_f(p[0], p[step[a]], p[-step[a]]);
	g[3] = 0;
#endif
}

/* The normal of the vertex at t on the edge from local voxel (x, y, z)
 * along axis a in double (mc_normal_d): the fallback where float is not
 * exact enough (near-cancelling gradients, tiny or huge values). */
static void exact_normal(const float *val, int x, int y, int z, int a, double t, float n_out[3])
{
	int q[3] = { x, y, z };
	q[a]++;
	float s0 = val[CIDX(x, y, z)], s1 = val[CIDX(q[0], q[1], q[2])];
	double g0[3], g1[3];
	gradient(val, x, y, z, s0, g0);
	gradient(val, q[0], q[1], q[2], s1, g1);
	mc_normal_d(g0, g1, t, a, s1, n_out);
}

/* The t and normals of the n vertices listed in w (lc, lg, lp) along axis
 * a: t into w->lt, normals four at a time in float, into the output at id
 * onwards (the last four, when fewer, through w->ln). */
static void axis_normals(struct worker *w, int a, int n, size_t id)
{
	static const int vstep[3] = { 1, CW, CW * CW }, gstep[3] = { 1, 9, 81 };
	const int vs = vstep[a], gs = gstep[a];
	const float *val = w->val;
	const float(*g4)[4] = w->grad4;
	for (int i = n; i & 3; i++)     /* pad the last four with a listed vertex */
		w->lc[i] = w->lc[0], w->lg[i] = w->lg[0], w->lp[i] = w->lp[0];
	for (int i = 0; i < n; i += 4) {
		const uint16_t *lc = w->lc + i, *lg = w->lg + i;
		unsigned bad;
		float *dst[3];
		for (int k = 0; k < 3; k++)
			dst[k] = i + 4 <= n ? w->M->o.nrm[k] + id + (size_t)i : w->ln[k] + i;
#if defined(__SSE2__)
		__m128 s0 = _mm_setr_ps(val[lc[0]], val[lc[1]], val[lc[2]], val[lc[3]]);
		__m128 s1 = _mm_setr_ps(val[lc[0] + vs], val[lc[1] + vs], val[lc[2] + vs], val[lc[3] + vs]);
		/* mc_edge_t, two lanes of double at a time */
		const __m128d tlo = _mm_set1_pd(1.0 / 256), thi = _mm_set1_pd(255.0 / 256);
		__m128d a0 = _mm_cvtps_pd(s0), a1 = _mm_cvtps_pd(_mm_movehl_ps(s0, s0));
		__m128d b0 = _mm_cvtps_pd(s1), b1 = _mm_cvtps_pd(_mm_movehl_ps(s1, s1));
		__m128d t0 = _mm_min_pd(_mm_max_pd(_mm_div_pd(a0, _mm_sub_pd(a0, b0)), tlo), thi);
		__m128d t1 = _mm_min_pd(_mm_max_pd(_mm_div_pd(a1, _mm_sub_pd(a1, b1)), tlo), thi);
		_mm_storeu_pd(w->lt + i, t0);
		_mm_storeu_pd(w->lt + i + 2, t1);
		const __m128 one = _mm_set1_ps(1.0f), absm = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
		__m128 T = _mm_movelh_ps(_mm_cvtpd_ps(t0), _mm_cvtpd_ps(t1)), U = _mm_sub_ps(one, T);
		__m128 nv[4], ev[4];
#define LANE(j, sh)                                                                          \
	do {                                                                                 \
		__m128 p = _mm_mul_ps(_mm_shuffle_ps(U, U, sh), _mm_load_ps(g4[lg[j]]));      \
		__m128 q = _mm_mul_ps(_mm_shuffle_ps(T, T, sh), _mm_load_ps(g4[lg[j] + gs])); \
		nv[j] = _mm_add_ps(p, q);                                                    \
		ev[j] = _mm_add_ps(_mm_and_ps(p, absm), _mm_and_ps(q, absm));                \
	} while (0)
		LANE(0, 0x00);
		LANE(1, 0x55);
		LANE(2, 0xAA);
		LANE(3, 0xFF);
#undef LANE
		/* mc_normal_f, four vertices side by side: to x, y, z across them */
		_MM_TRANSPOSE4_PS(nv[0], nv[1], nv[2], nv[3]);
		_MM_TRANSPOSE4_PS(ev[0], ev[1], ev[2], ev[3]);
		__m128 n2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(nv[0], nv[0]), _mm_mul_ps(nv[1], nv[1])),
		                       _mm_mul_ps(nv[2], nv[2]));
		__m128 e2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(ev[0], ev[0]), _mm_mul_ps(ev[1], ev[1])),
		                       _mm_mul_ps(ev[2], ev[2]));
		__m128 ok = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(n2, _mm_set1_ps(FLT_MIN)),
		                                  _mm_cmple_ps(n2, _mm_set1_ps(FLT_MAX))),
		                       _mm_cmpge_ps(_mm_mul_ps(n2, _mm_set1_ps(MC_NRM_CANCEL)), e2));
		__m128 inv = _mm_div_ps(one, _mm_sqrt_ps(n2));
		for (int k = 0; k < 3; k++)
			_mm_storeu_ps(dst[k], _mm_mul_ps(nv[k], inv));
		bad = (unsigned)~_mm_movemask_ps(ok) & 15;
#else
		bad = 0;
		for (int j = 0; j < 4; j++) {
			float nn[3];
			w->lt[i + j] = mc_edge_t(val[lc[j]], val[lc[j] + vs]);
			if (mc_normal_f(g4[lg[j]], g4[lg[j] + gs], w->lt[i + j], nn))
				for (int k = 0; k < 3; k++)
					dst[k][j] = nn[k];
			else
				bad |= 1u << j;
		}
#endif
		for (; bad; bad &= bad - 1) {
			int j = __builtin_ctz(bad), p = w->lp[i + j];
			float nn[3];
			if (i + j >= n)
				break;
			exact_normal(val, p & 15, p >> 4 & 15, p >> 8, a, w->lt[i + j], nn);
			for (int k = 0; k < 3; k++)
				dst[k][j] = nn[k];
		}
	}
	for (int i = n & ~3; i < n; i++)
		for (int k = 0; k < 3; k++)
			w->M->o.nrm[k][id + (size_t)i] = w->ln[k][i];
}

/* The positions (and colours) of the n vertices listed in w along axis a
 * of the block in w->cur, with their t (axis_normals), to the output at id
 * onwards. */
static void axis_output(struct worker *w, int a, int n, size_t id)
{
	const struct mc *M = w->M;
	struct blockctx *c = w->cur;
	double o = (double)(8 * (a == 0 ? c->bx : a == 1 ? c->by : c->bz));
	for (int i = 0; i < n; i++) {
		int p = w->lp[i], x = p & 15, y = p >> 4 & 15, z = p >> 8;
		int q[3] = { x, y, z };
		double *xyz = M->o.xyz + 3 * (id + (size_t)i);
		xyz[0] = c->coord[0][x], xyz[1] = c->coord[1][y], xyz[2] = c->coord[2][z];
		xyz[a] = ((o + q[a]) + w->lt[i]) * M->voxel;
	}
	for (int i = 0; M->colour && i < n; i++) {
		int p = w->lp[i], x = p & 15, y = p >> 4 & 15, z = p >> 8, v0, v1;
		int q[3] = { x, y, z };
		q[a]++;
		double t = w->lt[i];
		const struct fct_voxblock *b0 = ctx_voxel(M, c, x, y, z, &v0);
		const struct fct_voxblock *b1 = ctx_voxel(M, c, q[0], q[1], q[2], &v1);
		for (int k = 0; k < 3; k++)
			M->o.rgb[k][id + (size_t)i] = mc_to_u8((1 - t) * b0->rgb[3 * v0 + k] + t * b1->rgb[3 * v1 + k]);
	}
}

/* The vertices of block record A, planned in w->cur, at A->base onwards:
 * float gradients at the ends of its crossing edges, then per axis the
 * edges listed and their vertices computed four at a time. */
static void block_vertices(struct worker *w, const struct aux *A)
{
	const uint16_t(*need)[WROW] = w->cur->need;
	gather(w, w->cur);
	/* four rows of need (16 bits each) at a time */
	for (int z = 0; z < 9; z++)
		for (int y0 = 0; y0 < 9; y0 += 4) {
			const uint16_t *r = &need[z][y0];
			uint64_t m = r[0] | (uint64_t)r[1] << 16 | (uint64_t)r[2] << 32 | (uint64_t)r[3] << 48;
			for (; m; m &= m - 1) {
				int p = __builtin_ctzll(m), x = p & 15, y = y0 + (p >> 4);
				gradient4(w->val, CIDX(x, y, z), w->grad4[x + 9 * (y + 9 * z)]);
			}
		}
	size_t id = A->base;
	for (int a = 0; a < 3; a++) {
		int n = 0;
		for (int z = 0; z < 8; z++)
			for (uint64_t m = rows8(A->bits[a] + 8 * z); m; m &= m - 1) {
				int p = __builtin_ctzll(m), x = p & 7, y = p >> 3;
				w->lc[n] = (uint16_t)CIDX(x, y, z);
				w->lg[n] = (uint16_t)(x + 9 * (y + 9 * z));
				w->lp[n] = (uint16_t)(x | y << 4 | z << 8);
				n++;
			}
		if (!n)
			continue;
		axis_normals(w, a, n, id);
		axis_output(w, a, n, id);
		id += (size_t)n;
	}
}

/* Pass 0 on block B: its own bits, clipped. */
static void pass0(const struct mc *M, const struct fct_voxblock *B, struct own *o,
                  struct rim *rim)
{
	memset(rim, 0, sizeof *rim);
	o->b[0] = B->bx, o->b[1] = B->by, o->b[2] = B->bz;
	const int32_t *lo = M->lo, *hi = M->hi;
	unsigned any = 0, xm = 0xFF;
#if defined(__SSE2__)
	if (!lo) {
		/* two rows at a time, no clip box */
		for (int r = 0; r < 64; r += 2) {
			unsigned n, ob;
			bits16(B->sdf + 8 * r, B->weight + 8 * r, M->thr, &n, &ob);
			o->seen[r] = o->obs[r] = (uint8_t)ob;
			o->seen[r + 1] = o->obs[r + 1] = (uint8_t)(ob >> 8);
			o->neg[r] = (uint8_t)n;
			o->neg[r + 1] = (uint8_t)(n >> 8);
			any |= ob;
		}
		o->anyobs = any != 0;
		return;
	}
#endif
	if (lo)
		for (int x = 0; x < 8; x++) {
			int64_t gx = (int64_t)8 * B->bx + x;
			if (gx < lo[0] || gx > hi[0])
				xm &= ~(1u << x);
		}
	for (int r = 0; r < 64; r++) {
		unsigned n, ob;
		bits8(B->sdf + 8 * r, B->weight + 8 * r, M->thr, &n, &ob);
		o->seen[r] = (uint8_t)ob;
		if (lo) {
			int64_t gy = (int64_t)8 * B->by + (r & 7), gz = (int64_t)8 * B->bz + (r >> 3);
			if (gy < lo[1] || gy > hi[1] || gz < lo[2] || gz > hi[2])
				ob = 0;
			ob &= xm;
		}
		o->neg[r] = (uint8_t)n;
		o->obs[r] = (uint8_t)ob;
		any |= ob;
	}
	o->anyobs = any != 0;
}

#if !defined(__SSE2__)
/* Sign pattern of cube (x, y, z) of record A: bit c set when corner c is
 * negative. */
static inline int cube_cfg(const struct aux *A, int x, int y, int z)
{
	return (A->neg[z][y] >> x & 3) | (A->neg[z][y + 1] >> x & 3) << 2 |
	       (A->neg[z + 1][y] >> x & 3) << 4 | (A->neg[z + 1][y + 1] >> x & 3) << 6;
}
#endif

/* The sign patterns (cube_cfg) of the cubes of layer z of record A, at
 * cfg[8 * x + y]. */
static inline void layer_cfgs(const struct aux *A, int z, uint8_t cfg[64])
{
#if defined(__SSE2__)
	/* the eight rows y side by side, one x at a time */
	const __m128i three = _mm_set1_epi16(3);
	__m128i n00 = _mm_loadu_si128((const __m128i *)&A->neg[z][0]);
	__m128i n01 = _mm_loadu_si128((const __m128i *)&A->neg[z][1]);
	__m128i n10 = _mm_loadu_si128((const __m128i *)&A->neg[z + 1][0]);
	__m128i n11 = _mm_loadu_si128((const __m128i *)&A->neg[z + 1][1]);
	for (int x = 0; x < 8; x++) {
		__m128i c = _mm_cvtsi32_si128(x);
		__m128i t = _mm_or_si128(
			_mm_or_si128(_mm_and_si128(_mm_srl_epi16(n00, c), three),
		                     _mm_slli_epi16(_mm_and_si128(_mm_srl_epi16(n01, c), three), 2)),
			_mm_or_si128(_mm_slli_epi16(_mm_and_si128(_mm_srl_epi16(n10, c), three), 4),
		                     _mm_slli_epi16(_mm_and_si128(_mm_srl_epi16(n11, c), three), 6)));
		_mm_storel_epi64((__m128i *)(cfg + 8 * x), _mm_packus_epi16(t, t));
	}
#else
	for (int x = 0; x < 8; x++)
		for (int y = 0; y < 8; y++)
			cfg[8 * x + y] = (uint8_t)cube_cfg(A, x, y, z);
#endif
}

/* The contour of cube (x, y, z) of the block whose upper neighbours (k &
 * 1, k >> 1 & 1, k >> 2: the block itself at 0) are up[k], sign pattern
 * cfg, ambiguous faces amb: its variant, by the asymptotic decider
 * (mc_decide).  Only the sdf of the ambiguous faces' corners is read (pass 1 found the cube observed): these
 * reads miss the cache, the rest of the extraction works on bits. */
HOT static int cube_variant(const struct mc *M, const struct fct_voxblock *const up[8], int x, int y,
                        int z, int cfg, int amb)
{
	float val[8];
	for (unsigned m = M->T->amb_corners[amb]; m; m &= m - 1) {
		int k = __builtin_ctz(m);
		int px = x + (k & 1), py = y + (k >> 1 & 1), pz = z + (k >> 2);
		const struct fct_voxblock *b = up[(px >> 3) | (py >> 3) << 1 | (pz >> 3) << 2];
		if (!b)
			abort();
		val[k] = b->sdf[(px & 7) + 8 * ((py & 7) + 8 * (pz & 7))];
	}
	return mc_decide(M->C, val, cfg, amb);
}

/* The bits of m at 0, 8, ..., 56 as bits 0..7. */
static inline unsigned gather8(uint64_t m)
{
	return (unsigned)((m * UINT64_C(0x0102040810204080)) >> 56);
}

/* Give record A's upper neighbours (A->up) its cubes along their lower
 * faces (struct rim). */
static void push_rim(struct mc *M, const struct aux *A)
{
	const uint64_t col0 = 0x0101010101010101u;
	const uint8_t *ac = A->active;
	uint64_t x = 0, y = 0, z = rows8(ac + 56);
	for (int l = 0; l < 8; l++) {
		x |= (uint64_t)gather8(rows8(ac + 8 * l) >> 7 & col0) << 8 * l;
		y |= (uint64_t)ac[8 * l + 7] << 8 * l;
	}
	if (A->up[1] >= 0)
		M->rim[A->up[1]].x = x;
	if (A->up[2] >= 0)
		M->rim[A->up[2]].y = y;
	if (A->up[4] >= 0)
		M->rim[A->up[4]].z = z;
	if (A->up[3] >= 0)
		M->rim[A->up[3]].xy = (uint8_t)gather8(y >> 7 & col0);
	if (A->up[5] >= 0)
		M->rim[A->up[5]].xz = (uint8_t)gather8(z >> 7 & col0);
	if (A->up[6] >= 0)
		M->rim[A->up[6]].yz = ac[63];
	if (A->up[7] >= 0)
		M->rim[A->up[7]].xyz = (uint8_t)(ac[63] >> 7);
}

/* The 9x9 rows of sign and observed bits (bit x of row [z][y], x, y, z in
 * 0..8) of the block whose upper neighbours' bits (k & 1, k >> 1 & 1, k >>
 * 2; the block itself at 0) are o[k]. */
static void rows9(const struct own *const o[8], uint16_t neg[9][9], uint16_t obs[9][9])
{
#if defined(__SSE2__)
	/* rows y = 0..7 of a layer as eight 16-bit lanes: the block's byte,
	 * and bit 0 of its +x neighbour's as bit 8 */
	const __m128i zero = _mm_setzero_si128(), one = _mm_set1_epi8(1);
#define ROWS8(lo, hi)                                                              \
	_mm_or_si128(_mm_unpacklo_epi8(_mm_loadl_epi64((const __m128i *)(lo)), zero), \
	             _mm_unpacklo_epi8(zero, _mm_and_si128(_mm_loadl_epi64((const __m128i *)(hi)), one)))
	for (int z = 0; z < 8; z++) {
		_mm_storeu_si128((__m128i *)neg[z], ROWS8(o[0]->neg + 8 * z, o[1]->neg + 8 * z));
		_mm_storeu_si128((__m128i *)obs[z], ROWS8(o[0]->obs + 8 * z, o[1]->obs + 8 * z));
		neg[z][8] = (uint16_t)(o[2]->neg[8 * z] | (o[3]->neg[8 * z] & 1) << 8);
		obs[z][8] = (uint16_t)(o[2]->obs[8 * z] | (o[3]->obs[8 * z] & 1) << 8);
	}
	_mm_storeu_si128((__m128i *)neg[8], ROWS8(o[4]->neg, o[5]->neg));
	_mm_storeu_si128((__m128i *)obs[8], ROWS8(o[4]->obs, o[5]->obs));
	neg[8][8] = (uint16_t)(o[6]->neg[0] | (o[7]->neg[0] & 1) << 8);
	obs[8][8] = (uint16_t)(o[6]->obs[0] | (o[7]->obs[0] & 1) << 8);
#undef ROWS8
#else
	for (int z = 0; z < 9; z++)
		for (int y = 0; y < 9; y++) {
			int k = (y >> 3) << 1 | (z >> 3) << 2, r = (z & 7) * 8 + (y & 7);
			neg[z][y] = (uint16_t)(o[k]->neg[r] | (o[k | 1]->neg[r] & 1) << 8);
			obs[z][y] = (uint16_t)(o[k]->obs[r] | (o[k | 1]->obs[r] & 1) << 8);
		}
#endif
}

/* Record A's crossing edges and extracted cubes (struct aux bits, active,
 * any_active) from its rows A->neg and obs (rows9).  Returns nonzero when
 * there is any. */
static unsigned cube_bits(struct aux *A, const uint16_t obs[9][9])
{
#if defined(__SSE2__)
	/* a layer's eight rows side by side, the scalar code's operations */
	const __m128i ff = _mm_set1_epi16(0xFF);
	__m128i anything = _mm_setzero_si128(), active = _mm_setzero_si128();
	for (int z = 0; z < 8; z++) {
		__m128i n = _mm_loadu_si128((const __m128i *)&A->neg[z][0]);
		__m128i n01 = _mm_loadu_si128((const __m128i *)&A->neg[z][1]);
		__m128i n10 = _mm_loadu_si128((const __m128i *)&A->neg[z + 1][0]);
		__m128i n11 = _mm_loadu_si128((const __m128i *)&A->neg[z + 1][1]);
		__m128i o = _mm_loadu_si128((const __m128i *)&obs[z][0]);
		__m128i o01 = _mm_loadu_si128((const __m128i *)&obs[z][1]);
		__m128i o10 = _mm_loadu_si128((const __m128i *)&obs[z + 1][0]);
		__m128i o11 = _mm_loadu_si128((const __m128i *)&obs[z + 1][1]);
		__m128i b0 = _mm_and_si128(_mm_and_si128(_mm_xor_si128(n, _mm_srli_epi16(n, 1)), o),
		                           _mm_and_si128(_mm_srli_epi16(o, 1), ff));
		__m128i b1 = _mm_and_si128(_mm_and_si128(_mm_xor_si128(n, n01), o), _mm_and_si128(o01, ff));
		__m128i b2 = _mm_and_si128(_mm_and_si128(_mm_xor_si128(n, n10), o), _mm_and_si128(o10, ff));
		__m128i all = _mm_and_si128(_mm_and_si128(o, o01), _mm_and_si128(o10, o11));
		__m128i any = _mm_or_si128(_mm_or_si128(n, n01), _mm_or_si128(n10, n11));
		__m128i every = _mm_and_si128(_mm_and_si128(n, n01), _mm_and_si128(n10, n11));
		all = _mm_and_si128(all, _mm_srli_epi16(all, 1));
		any = _mm_or_si128(any, _mm_srli_epi16(any, 1));
		every = _mm_and_si128(every, _mm_srli_epi16(every, 1));
		__m128i act = _mm_and_si128(_mm_andnot_si128(every, _mm_and_si128(all, any)), ff);
		_mm_storel_epi64((__m128i *)&A->bits[0][8 * z], _mm_packus_epi16(b0, b0));
		_mm_storel_epi64((__m128i *)&A->bits[1][8 * z], _mm_packus_epi16(b1, b1));
		_mm_storel_epi64((__m128i *)&A->bits[2][8 * z], _mm_packus_epi16(b2, b2));
		_mm_storel_epi64((__m128i *)&A->active[8 * z], _mm_packus_epi16(act, act));
		active = _mm_or_si128(active, act);
		anything = _mm_or_si128(anything, _mm_or_si128(_mm_or_si128(b0, b1), _mm_or_si128(b2, act)));
	}
	uint64_t a;
	_mm_storel_epi64((__m128i *)&a, _mm_packus_epi16(active, active));
	a |= a >> 32, a |= a >> 16, a |= a >> 8;
	A->any_active = (uint8_t)a;
	return _mm_movemask_epi8(_mm_cmpeq_epi8(anything, _mm_setzero_si128())) != 0xFFFF;
#else
	unsigned anything = 0;
	A->any_active = 0;
	for (int z = 0; z < 8; z++)
		for (int y = 0; y < 8; y++) {
			int r = 8 * z + y;
			unsigned n = A->neg[z][y], o = obs[z][y];
			unsigned n01 = A->neg[z][y + 1], n10 = A->neg[z + 1][y], n11 = A->neg[z + 1][y + 1];
			A->bits[0][r] = (uint8_t)((n ^ n >> 1) & o & o >> 1);
			A->bits[1][r] = (uint8_t)((n ^ n01) & o & obs[z][y + 1]);
			A->bits[2][r] = (uint8_t)((n ^ n10) & o & obs[z + 1][y]);
			unsigned all = o & obs[z][y + 1] & obs[z + 1][y] & obs[z + 1][y + 1];
			unsigned any = n | n01 | n10 | n11, every = n & n01 & n10 & n11;
			all &= all >> 1;
			any |= any >> 1;
			every &= every >> 1;
			A->active[r] = (uint8_t)(all & any & ~every);
			A->any_active |= A->active[r];
			anything |= A->bits[0][r] | A->bits[1][r] | A->bits[2][r] | A->active[r];
		}
	return anything;
#endif
}

/* Pass 1 on block b: its edge and cube bits, exact counts of triangles
 * and centroids.  Returns 1 when the block has anything (A
 * filled), else 0. */
static int pass1(struct mc *M, size_t b, const int32_t up[8], struct aux *A)
{
	const struct own *own = M->own;
	A->block = (uint32_t)b;
	memcpy(A->up, up, sizeof A->up);
	static const struct own none;   /* an absent neighbour: nothing observed */
	const struct own *o[8];
	for (int k = 0; k < 8; k++)
		o[k] = A->up[k] >= 0 ? &own[A->up[k]] : &none;
	uint16_t obs[9][9];
	rows9(o, A->neg, obs);
	unsigned anything = cube_bits(A, obs);
	if (!anything)
		return 0;
	const struct fct_voxblock *upb[8];
	for (int k = 0; k < 8; k++)
		upb[k] = A->up[k] >= 0 ? fct_voxgrid_at(M->g, (size_t)A->up[k]) : NULL;
	const struct mc_cases *C = M->C;
	uint32_t nt = 0, nc = 0, ncubes = 0, namb = 0;
	uint8_t cfgs[64];
	for (int z = 0; z < 8 && A->any_active; z++) {
		uint64_t layer = rows8(A->active + 8 * z);
		if (layer)
			layer_cfgs(A, z, cfgs);
		for (uint64_t m = layer; m; m &= m - 1) {
			int p = __builtin_ctzll(m), x = p & 7, y = p >> 3;
			int cfg = cfgs[8 * x + y], id = C->first[cfg], amb = C->amb[cfg];
			if (amb) {
				int v = cube_variant(M, upb, x, y, z, cfg, amb);
				if (namb < AMB_KEEP)
					A->var[namb] = (uint8_t)v;
				namb++;
				id += v;
			}
			ncubes++;
			nt += C->ntri[id];
			nc += C->ncentre[id];
		}
	}
	A->ntri = nt;
	A->ncent = nc;
	A->ncubes = ncubes;
	A->namb = namb;
	A->nvar = (uint8_t)(namb < AMB_KEEP ? namb : AMB_KEEP);
	if (A->any_active)
		push_rim(M, A);
	return 1;
}

/* Pass 2 on record A: keep the crossing edges that an extracted cube uses
 * (one of the four around the edge, some in the lower neighbours' records),
 * so that no vertex is made that no triangle uses, and count them. */
static void pass2(const struct mc *M, struct aux *A)
{
	/* act[z + 1][y + 1], bit x + 1: cube (x, y, z) extracted, -1..7 */
	uint16_t act[9][9];
	memset(act, 0, sizeof act);
	for (int r = 0; r < 64; r++)
		act[(r >> 3) + 1][(r & 7) + 1] = (uint16_t)(A->active[r] << 1);
	/* the lower neighbours' cubes at -1 */
	const struct rim *R = &M->rim[A->block];
	for (uint64_t m = R->x; m; m &= m - 1) {
		int p = __builtin_ctzll(m);
		act[(p >> 3) + 1][(p & 7) + 1] |= 1;
	}
	for (int l = 0; l < 8; l++) {
		act[l + 1][0] |= (uint16_t)((R->y >> 8 * l & 0xFF) << 1 | (R->xy >> l & 1));
		act[0][l + 1] |= (uint16_t)((R->z >> 8 * l & 0xFF) << 1 | (R->xz >> l & 1));
	}
	act[0][0] |= (uint16_t)(R->yz << 1 | R->xyz);
	uint32_t count = 0;
	for (int z = 0; z < 8; z++)
		for (int y = 0; y < 8; y++) {
			int r = 8 * z + y;
			unsigned c11 = act[z + 1][y + 1], c01 = act[z][y + 1], c10 = act[z + 1][y];
			unsigned ux = c11 | c01 | c10 | act[z][y];      /* cubes (x, y-1..y, z-1..z) */
			unsigned uy = c11 | c01, uz = c11 | c10;        /* (x-1..x, y, z-1..z), (x-1..x, y-1..y, z) */
			A->bits[0][r] &= (uint8_t)(ux >> 1);
			A->bits[1][r] &= (uint8_t)(uy | uy >> 1);
			A->bits[2][r] &= (uint8_t)(uz | uz >> 1);
		}
	for (int a = 0; a < 3; a++)
		for (int z = 0; z < 8; z++) {
			A->pre[a][z] = (uint16_t)count;
			count += pop64(rows8(A->bits[a] + 8 * z));
		}
	A->nverts = count;
}

/* The vertices before each row of a layer of bits l (row y in byte y):
 * byte y of the result. */
static inline uint64_t row_starts(uint64_t l)
{
	uint64_t c = l - ((l >> 1) & UINT64_C(0x5555555555555555));
	c = (c & UINT64_C(0x3333333333333333)) + ((c >> 2) & UINT64_C(0x3333333333333333));
	c = (c + (c >> 4)) & UINT64_C(0x0F0F0F0F0F0F0F0F);
	return (c * UINT64_C(0x0101010101010101)) << 8;
}

/* Entries x = 0..7 of a row of vt whose edges with a vertex are the bits
 * of b, numbered from id: id plus the vertices before x in the row
 * (tables.bpre), without a branch per vertex; the entries of edges without
 * a vertex get numbers no cube reads. */
static inline void vt_row(uint32_t *row, uint32_t id, unsigned b)
{
	const uint8_t *pre = tables.bpre[b];
#if defined(__SSE2__)
	const __m128i zero = _mm_setzero_si128();
	__m128i r = _mm_unpacklo_epi8(_mm_loadl_epi64((const __m128i *)pre), zero);
	__m128i base = _mm_set1_epi32((int)id);
	_mm_storeu_si128((__m128i *)row, _mm_add_epi32(base, _mm_unpacklo_epi16(r, zero)));
	_mm_storeu_si128((__m128i *)(row + 4), _mm_add_epi32(base, _mm_unpackhi_epi16(r, zero)));
#else
	for (int x = 0; x < 8; x++)
		row[x] = id + pre[x];
#endif
}

/* Rows y = 0..7 of a layer of vt (row y at lay + 9 y) from a layer of
 * bits l, numbered from id. */
static inline void vt_layer(uint32_t *lay, uint32_t id, uint64_t l)
{
	uint64_t c = row_starts(l);
	for (int y = 0; y < 8; y++, l >>= 8, c >>= 8)
		vt_row(lay + 9 * y, id + (uint32_t)(c & 0xFF), (unsigned)(l & 0xFF));
}

/* Entries x = 8 of rows y = 0..7 (at col + 9 y) from a neighbour's layer
 * of bits l numbered from id: its edges at x = 0, each its row's first. */
static inline void vt_column(uint32_t *col, uint32_t id, uint64_t l)
{
	uint64_t c = row_starts(l);
	for (int y = 0; y < 8; y++, c >>= 8)
		col[9 * y] = id + (uint32_t)(c & 0xFF);
}

/* Fill vt (VT_IDX) for record A: its own edges, and those of its upper
 * neighbours' records up[k] (NULL: none) that its cubes use, the edges
 * with a lower corner at local 8 on an axis other than their own.  The
 * entries of edges with a vertex are written (and some others, whose
 * numbers no cube reads). */
static void fill_vt(uint32_t *vt, const struct aux *A, const struct aux *const up[8])
{
	const uint64_t col0 = 0x0101010101010101u;      /* bit x = 0 of each row */
	for (int a = 0; a < 3; a++)
		for (int z = 0; z < 8; z++) {
			uint64_t l = rows8(A->bits[a] + 8 * z);
			if (l)
				vt_layer(vt + VT_IDX(a, 0, 0, z), A->base + A->pre[a][z], l);
		}
	const struct aux *N;
	/* +x: along y and z at x = 8 (the neighbour's x = 0) */
	if ((N = up[1]))
		for (int a = 1; a < 3; a++)
			for (int z = 0; z < 8; z++) {
				uint64_t l = rows8(N->bits[a] + 8 * z);
				if (l & col0)
					vt_column(vt + VT_IDX(a, 8, 0, z), N->base + N->pre[a][z], l);
			}
	/* +y: along x and z at y = 8, the neighbour's rows (z, 0) */
	if ((N = up[2]))
		for (int a = 0; a < 3; a += 2)
			for (int z = 0; z < 8; z++)
				if (N->bits[a][8 * z])
					vt_row(vt + VT_IDX(a, 0, 8, z), N->base + N->pre[a][z], N->bits[a][8 * z]);
	/* +z: along x and y at z = 8, rows (0, y) */
	if ((N = up[4]))
		for (int a = 0; a < 2; a++) {
			uint64_t l = rows8(N->bits[a]);
			if (l)
				vt_layer(vt + VT_IDX(a, 0, 0, 8), N->base + N->pre[a][0], l);
		}
	/* +x+y: along z at (8, 8, z); +x+z: along y at (8, y, 8); +y+z: along x
	 * at (x, 8, 8) */
	if ((N = up[3]))
		for (int z = 0; z < 8; z++)
			if (N->bits[2][8 * z] & 1)
				vt[VT_IDX(2, 8, 8, z)] = N->base + N->pre[2][z];
	if ((N = up[5])) {
		uint64_t l = rows8(N->bits[1]);
		if (l & col0)
			vt_column(vt + VT_IDX(1, 8, 0, 8), N->base + N->pre[1][0], l);
	}
	if ((N = up[6])) {
		uint32_t id = N->base + N->pre[0][0];
		for (unsigned m = N->bits[0][0]; m; m &= m - 1)
			vt[VT_IDX(0, __builtin_ctz(m), 8, 8)] = id++;
	}
}

/* The triangles and centroid vertices of queued cube c. */
HOT static void emit_centred(struct worker *w, const struct centred *c)
{
	const struct mc *M = w->M;
	uint32_t cid = c->cid;
	uint32_t *t = mc_cube_triangles(&M->o, &M->C->var[c->id], c->vid, c->t, &cid);
	w->st.centres += cid - c->cid;
	/* pass 1 counted the same triangles and centroids */
	if (t != c->t + 3 * M->C->ntri[c->id] || cid != c->cid + M->C->ncentre[c->id])
		abort();
}

/* Work through w's queue of cubes with a centroid. */
static void flush_centred(struct worker *w)
{
	for (unsigned i = 0; i < w->ncq; i++)
		emit_centred(w, &w->cq[i]);
	w->ncq = 0;
}

/* The triangles of block record A, at A->tbase onwards. */
static void block_triangles(struct worker *w, const struct aux *A)
{
	const struct mc *M = w->M;
	const struct mc_cases *C = M->C;
	const struct fast_tables *T = M->T;
	const struct aux *up[8];
	for (int k = 0; k < 8; k++)
		up[k] = A->up[k] >= 0 && M->auxof[A->up[k]] != NONE ? &M->aux[M->auxof[A->up[k]]] : NULL;
	const struct fct_voxblock *upb[8];
	for (int k = 0; A->namb > A->nvar && k < 8; k++)
		upb[k] = A->up[k] >= 0 ? fct_voxgrid_at(M->g, (size_t)A->up[k]) : NULL;
	uint32_t *vt = w->vt;
	fill_vt(vt, A, up);
	uint32_t *t = M->tri + 3 * (size_t)A->tbase, cid = (uint32_t)M->nverts + A->cbase;
	uint32_t *tend = M->tri + 3 * ((size_t)A->tbase + A->ntri);
	unsigned k = 0;
	uint8_t cfgs[64];
	for (int z = 0; z < 8; z++) {
		uint64_t layer = rows8(A->active + 8 * z);
		if (layer)
			layer_cfgs(A, z, cfgs);
		for (uint64_t m = layer; m; m &= m - 1) {
			int p = __builtin_ctzll(m), x = p & 7, y = p >> 3;
			int cfg = cfgs[8 * x + y], id = C->first[cfg];
			if (C->amb[cfg]) {
				/* pass 1's decision, or the same one again */
				id += k < A->nvar ? A->var[k]
				                  : cube_variant(M, upb, x, y, z, cfg, C->amb[cfg]);
				k++;
			}
			const uint32_t *cv = vt + VT_IDX(0, x, y, z);
			if (C->ncentre[id]) {
				/* queued, its place in the output kept */
				if (w->ncq == CQ)
					flush_centred(w);
				struct centred *c = &w->cq[w->ncq++];
				for (unsigned e = C->var[id].emask; e; e &= e - 1)
					c->vid[__builtin_ctz(e)] = cv[T->eoff[__builtin_ctz(e)]];
				c->t = t, c->cid = cid, c->id = id;
				t += 3 * C->ntri[id];
				cid += C->ncentre[id];
				continue;
			}
			/* the common case: the tabulated fans; up to 4 triangles
			 * copied as 12 entries whatever their number, where the
			 * block's range has room (the excess is overwritten by the
			 * next cube), so that the copy's length mispredicts no branch */
			const uint16_t *to = T->toff[id];
			int n = 3 * C->ntri[id], j = 0;
			if (t + 12 <= tend) {
				for (; j < 12; j += 4) {
					t[j] = cv[to[j]], t[j + 1] = cv[to[j + 1]];
					t[j + 2] = cv[to[j + 2]], t[j + 3] = cv[to[j + 3]];
				}
			}
			for (; j < n; j++)
				t[j] = cv[to[j]];
			t += n;
		}
	}
	w->st.cubes += A->ncubes;
	w->st.ambiguous += A->namb;
	/* pass 1 counted the same cubes with the same decisions */
	if (t != M->tri + 3 * ((size_t)A->tbase + A->ntri) || cid != M->nverts + A->cbase + A->ncent)
		abort();
}

/* The passes as parallel loops over blocks (0, 1) and records (2, 3). */
/* Start loading a block's 512 values (sdf or weight), a cache line of 16
 * floats at a time. */
static inline void prefetch_values(const float *v)
{
	for (int k = 0; k < FCT_VOXBLOCK_N; k += 16)
		__builtin_prefetch(v + k);
}

HOT static void run_pass0(void *ctx, size_t lo, size_t hi, int worker)
{
	struct mc *M = ctx;
	(void)worker;
	for (size_t b = lo; b < hi; b++) {
		if (b + 1 < hi) {
			const struct fct_voxblock *n = fct_voxgrid_at(M->g, b + 1);
			prefetch_values(n->sdf);
			prefetch_values(n->weight);
		}
		pass0(M, fct_voxgrid_at(M->g, b), &M->own[b], &M->rim[b]);
	}
}

/* Block b (its coordinates from pass 0) and its upper neighbours (struct
 * aux up) into up. */
static void block_up(const struct mc *M, size_t b, int32_t up[8])
{
	const int32_t *c = M->own[b].b;
	up[0] = (int32_t)b;
	for (int k = 1; k < 8; k++)
		up[k] = (int32_t)block_index(M, c[0] + (k & 1), c[1] + (k >> 1 & 1), c[2] + (k >> 2));
}

HOT static void run_pass1(void *ctx, size_t lo, size_t hi, int worker)
{
	struct mc *M = ctx;
	struct aux A;
	int32_t up[2][8];
	(void)worker;
	if (lo < hi && M->auxof[lo] != NONE)
		block_up(M, lo, up[0]);
	for (size_t b = lo, k = 0; b < hi; b++, k ^= 1) {
		/* the next block's neighbours found, and the loads of their bits
		 * and of its sdf (the decider's) started, while this one is worked
		 * on */
		if (b + 1 < hi && M->auxof[b + 1] != NONE) {
			int32_t *u = up[k ^ 1];
			block_up(M, b + 1, u);
			for (int j = 1; j < 8; j++)
				if (u[j] >= 0) {
					__builtin_prefetch(M->own[u[j]].neg);
					__builtin_prefetch(M->own[u[j]].obs);
				}
			prefetch_values(fct_voxgrid_at(M->g, b + 1)->sdf);
		}
		/* computed aside, so that the records of empty blocks stay
		 * untouched (never paged in) */
		if (M->auxof[b] == NONE)
			continue;
		if (pass1(M, b, up[k], &A))
			M->aux[M->auxof[b]] = A;
		else
			M->auxof[b] = NONE;
	}
}

HOT static void run_pass2(void *ctx, size_t lo, size_t hi, int worker)
{
	struct mc *M = ctx;
	(void)worker;
	for (size_t i = lo; i < hi; i++)
		pass2(M, &M->aux[M->live[i]]);
}

HOT static void run_vertices(void *ctx, size_t lo, size_t hi, int worker)
{
	struct mc *M = ctx;
	struct worker *w = &M->w[worker];
	/* each block is planned while the one before is worked on */
	size_t i = lo, next;
	while (i < hi && !M->aux[M->live[i]].nverts)
		i++;
	if (i < hi)
		plan(M, &w->c[0], &M->aux[M->live[i]]);
	for (int k = 0; i < hi; i = next, k ^= 1) {
		next = i + 1;
		while (next < hi && !M->aux[M->live[next]].nverts)
			next++;
		if (next < hi)
			plan(M, &w->c[k ^ 1], &M->aux[M->live[next]]);
		w->cur = &w->c[k];
		block_vertices(w, &M->aux[M->live[i]]);
	}
}

HOT static void run_triangles(void *ctx, size_t lo, size_t hi, int worker)
{
	struct mc *M = ctx;
	for (size_t i = lo; i < hi; i++) {
		/* the next record's neighbours' records (their vertex bits, counts
		 * and base: the first four lines) start loading */
		if (i + 1 < hi) {
			const struct aux *N = &M->aux[M->live[i + 1]];
			for (int k = 1; k < 8; k++)
				if (N->up[k] >= 0 && M->auxof[N->up[k]] != NONE) {
					const char *r = (const char *)&M->aux[M->auxof[N->up[k]]];
					for (int l = 0; l < 256; l += 64)
						__builtin_prefetch(r + l);
				}
		}
		if (M->aux[M->live[i]].any_active)
			block_triangles(&M->w[worker], &M->aux[M->live[i]]);
	}
	flush_centred(&M->w[worker]);
}

/* M->map for the nb blocks (their coordinates in M->own) when their
 * bounding box has at most 16 cells per block (and 2^28 in all), so that
 * the neighbour lookups of pass 1 and of the vertex pass (about 20 per
 * block) read a small array, the neighbours along x side by side, instead
 * of probing the grid's hash.  Left NULL for sparse sites or when out of
 * memory (the lookups then probe the hash). */
static void blockmap(struct mc *M, size_t nb)
{
	if (!nb)
		return;
	int64_t lo[3], hi[3];
	for (int k = 0; k < 3; k++)
		lo[k] = hi[k] = M->own[0].b[k];
	for (size_t b = 1; b < nb; b++)
		for (int k = 0; k < 3; k++) {
			int64_t v = M->own[b].b[k];
			lo[k] = v < lo[k] ? v : lo[k];
			hi[k] = v > hi[k] ? v : hi[k];
		}
	double cells = 1;
	for (int k = 0; k < 3; k++)
		cells *= (double)(hi[k] - lo[k] + 1);
	if (cells > 16.0 * (double)nb + 4096 || cells > (double)(1 << 28) ||
	    !(M->map = malloc((size_t)cells * sizeof *M->map)))
		return;
	for (int k = 0; k < 3; k++) {
		M->map_lo[k] = (int32_t)lo[k];
		M->map_dim[k] = (size_t)(hi[k] - lo[k] + 1);
	}
	memset(M->map, 0xFF, (size_t)cells * sizeof *M->map);        /* all -1 */
	for (size_t b = 0; b < nb; b++) {
		const int32_t *c = M->own[b].b;
		size_t x = (size_t)(c[0] - lo[0]), y = (size_t)(c[1] - lo[1]), z = (size_t)(c[2] - lo[2]);
		M->map[x + M->map_dim[0] * (y + M->map_dim[1] * z)] = (int32_t)b;
	}
}


/* Chunks of the parallel loops: fixed, so the work is cut alike for any
 * thread count (the results do not depend on it anyway). */
#define MC_CHUNKS 64

int mcubes_fast(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                const int32_t *clip_lo, const int32_t *clip_hi, int threads,
                struct fct_mcubes_stats *stats, struct fct_err *err)
{
	struct mc *M = calloc(1, sizeof *M);
	if (!M)
		return fct_fail(err, "out of memory");
	M->g = g;
	M->lo = clip_lo, M->hi = clip_hi;
	M->thr = mc_threshold(min_weight);
	M->colour = fct_voxgrid_has_colour(g);
	M->voxel = fct_voxgrid_voxel(g);
	M->C = mcubes_cases();
	if (pthread_once(&tables_once, tables_init))
		abort();
	M->T = &tables;

	int rc = -1, nthreads = fct_par_threads(threads);
	double tp[FCT_MC_PHASES + 1];
	size_t nb = fct_voxgrid_count(g), naux = 0, ntri = 0, ncent = 0, nverts = 0;
	M->w = calloc((size_t)nthreads, sizeof *M->w);
	M->own = fct_alloc_array(nb, sizeof *M->own, err);
	M->auxof = fct_alloc_array(nb, sizeof *M->auxof, err);
	M->rim = fct_alloc_array(nb, sizeof *M->rim, err);
	if (!M->w || !M->own || !M->auxof || !M->rim) {
		if (!M->w)
			fct_fail(err, "out of memory");
		goto done;
	}
	for (int t = 0; t < nthreads; t++)
		M->w[t].M = M;
	if (clip_lo && (clip_lo[0] >= clip_hi[0] || clip_lo[1] >= clip_hi[1] || clip_lo[2] >= clip_hi[2]))
		nb = 0;         /* an empty box: no cubes */
	tp[0] = fct_now();
	fct_par_run(nthreads, nb, MC_CHUNKS, run_pass0, M);
	tp[1] = fct_now();
	for (size_t b = 0; b < nb; b++)
		M->auxof[b] = M->own[b].anyobs ? (uint32_t)naux++ : NONE;
	blockmap(M, nb);
	if (!(M->aux = fct_alloc_array(naux, sizeof *M->aux, err)) ||
	    !(M->live = fct_alloc_array(naux, sizeof *M->live, err)))
		goto done;
	fct_par_run(nthreads, nb, MC_CHUNKS, run_pass1, M);
	tp[2] = fct_now();
	for (size_t b = 0; b < nb; b++)
		if (M->auxof[b] != NONE)
			M->live[M->nlive++] = M->auxof[b];
	fct_par_run(nthreads, M->nlive, MC_CHUNKS, run_pass2, M);
	tp[3] = fct_now();
	/* every record's place in the output, in block order */
	for (size_t i = 0; i < M->nlive; i++) {
		struct aux *A = &M->aux[M->live[i]];
		A->base = (uint32_t)nverts;
		A->tbase = (uint32_t)ntri;
		A->cbase = (uint32_t)ncent;
		nverts += A->nverts;
		ntri += A->ntri;
		ncent += A->ncent;
		if (nverts + ncent > UINT32_MAX - 1) {
			fct_fail(err, "marching cubes: more than 2^32 - 1 vertices");
			goto done;
		}
		if (ntri > UINT32_MAX / 3) {
			fct_fail(err, "marching cubes: more than 2^32 / 3 triangles");
			goto done;
		}
	}
	M->nverts = nverts;
	if (mcubes_output(&M->o, out, nverts + ncent, ntri, M->colour, err))
		goto done;
	M->tri = out->fvert;
	tp[4] = fct_now();
	fct_par_run(nthreads, M->nlive, MC_CHUNKS, run_vertices, M);
	tp[5] = fct_now();
	fct_par_run(nthreads, M->nlive, MC_CHUNKS, run_triangles, M);
	tp[6] = fct_now();
	if (stats) {
		memset(stats, 0, sizeof *stats);
		for (int t = 0; t < nthreads; t++) {
			stats->cubes += M->w[t].st.cubes;
			stats->ambiguous += M->w[t].st.ambiguous;
			stats->centres += M->w[t].st.centres;
		}
		stats->blocks = nb;
		stats->voxels = nb * FCT_VOXBLOCK_N;
		stats->threads = (size_t)nthreads;
		for (int k = 0; k < FCT_MC_PHASES; k++)
			stats->phase_s[k] = tp[k + 1] - tp[k];
	}
	rc = 0;
done:
	if (rc)
		fct_mesh_free(out);
	free(M->own);
	free(M->auxof);
	free(M->map);
	free(M->rim);
	free(M->aux);
	free(M->live);
	free(M->w);
	free(M);
	return rc;
}

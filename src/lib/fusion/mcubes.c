/* mcubes.c - marching cubes over the sparse block grid: the contour
 * tables, and a plain extraction, cube by cube, that is the reference for
 * the extraction the programs run (mcubesfast.c: the same output, bit for
 * bit, in passes on threads) and the tests' oracle.  mcubes.h says what the
 * output is.
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
 * facing the positive side.  The 256 sign patterns under every outcome of
 * the decider on their ambiguous faces (656 contours) are tabulated once per
 * process.
 *
 * The output's order, which both extractions follow: blocks in the grid's
 * order; a block's edge vertices axis by axis (the edges towards +x, then
 * +y, then +z), each axis's by the voxel at their lower end (z, then y,
 * then x); the centroid vertices after every edge vertex; the triangles
 * cube by cube (blocks in order, a block's cubes by z, y, x; a cube's loops
 * in table order).  A vertex's normal is worked in float and, where float
 * is not exact enough, in double (mcubespriv.h). */
#include "fusion/mcubes.h"

#include <pthread.h>
#include <string.h>

#include "fusion/mcubespriv.h"

/* Cube geometry ----------------------------------------------------------- */

static int corner_coord(int c, int a)
{
	return (c >> a) & 1;
}

static void geom_init(struct mc_geom *G)
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

/* Build the contour of sign pattern cfg (bit c set: corner c negative),
 * joining the negative diagonal on the ambiguous faces in joinneg (a face
 * mask) and the positive one on the others.  Aborts on an inconsistency
 * (the rule guarantees one segment in and one out at each crossing). */
static void build_case(const struct mc_geom *G, int cfg, int joinneg, struct mc_case *mc)
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

/* Triangles and centroid vertices of a contour. */
static void case_counts(const struct mc_case *mc, uint32_t *nt, uint32_t *nc)
{
	for (int l = 0; l < mc->nloops; l++) {
		*nt += mc->centre[l] ? mc->len[l] : mc->len[l] - 2u;
		*nc += mc->centre[l];
	}
}

/* The face mask of the faces of amb picked by the bits of v (bit i: the
 * i-th face of amb). */
static int expand_faces(int amb, int v)
{
	int mask = 0;
	for (int f = 0, i = 0; f < 6; f++)
		if (amb >> f & 1)
			mask |= (v >> i++ & 1) << f;
	return mask;
}

static struct mc_cases cases;
static pthread_once_t cases_once = PTHREAD_ONCE_INIT;

static void cases_init(void)
{
	struct mc_cases *C = &cases;
	geom_init(&C->G);
	int n = 0;
	for (int cfg = 0; cfg < 256; cfg++) {
		C->first[cfg] = (uint16_t)n;
		struct mc_case base;
		build_case(&C->G, cfg, 0, &base);
		int nv = 1 << __builtin_popcount(base.amb);
		if (n + nv > MC_VARIANTS)
			abort();
		for (int v = 0; v < nv; v++, n++) {
			struct mc_case *mc = &C->var[n];
			build_case(&C->G, cfg, expand_faces(base.amb, v), mc);
			uint32_t nt = 0, nc = 0;
			case_counts(mc, &nt, &nc);
			C->ntri[n] = (uint8_t)nt;
			C->ncentre[n] = (uint8_t)nc;
		}
		C->amb[cfg] = base.amb;
	}
	if (n != MC_VARIANTS)
		abort();
}

const struct mc_cases *mcubes_cases(void)
{
	if (pthread_once(&cases_once, cases_init))
		abort();
	return &cases;
}

int mcubes_output(struct mc_out *o, struct fct_mesh *out, size_t nv, size_t ntri, int colour,
                  struct fct_err *err)
{
	if (fct_mesh_set_vertex_count(out, nv, err) || fct_mesh_set_triangle_count(out, ntri, err))
		return -1;
	static const char *nn[3] = { "nx", "ny", "nz" }, *cn[3] = { "red", "green", "blue" };
	for (int k = 0; k < 3; k++)
		if (!fct_elem_add_scalar(&out->vertex, nn[k], FCT_FLOAT32, err))
			return -1;
	if (colour)
		for (int k = 0; k < 3; k++)
			if (!fct_elem_add_scalar(&out->vertex, cn[k], FCT_UINT8, err))
				return -1;
	memset(o, 0, sizeof *o);
	for (int k = 0; k < 3; k++) {
		o->nrm[k] = fct_elem_find(&out->vertex, nn[k])->data;
		if (colour)
			o->rgb[k] = fct_elem_find(&out->vertex, cn[k])->data;
	}
	o->xyz = out->xyz;
	return 0;
}

/* The plain extraction ------------------------------------------------------ */

#define NONE UINT32_MAX         /* no vertex on the edge */
#define USED (UINT32_MAX - 1)   /* a vertex, not numbered yet */

/* One run: the grid and what counts as observed, the vertex of every
 * lattice edge, the output. */
struct ref {
	const struct fct_voxgrid *g;
	const struct mc_cases *C;
	float thr;
	const int32_t *lo, *hi;         /* clip box or NULL */
	double voxel;
	/* the vertex of the lattice edge from voxel v of block b along axis a:
	 * vid[3 * 512 * b + 512 * a + v], NONE or USED or its number */
	uint32_t *vid;
	struct mc_out o;
};

/* A voxel by its global index (i, j, k): its block's index (-1: absent),
 * the block and its index v in it. */
struct vox {
	long block;
	const struct fct_voxblock *b;
	int v;
};

static int64_t floor8(int64_t i)
{
	return i >= 0 ? i / 8 : -((7 - i) / 8);
}

static struct vox vox_at(const struct ref *R, const int64_t p[3])
{
	struct vox x = { -1, NULL, 0 };
	int64_t b[3];
	for (int k = 0; k < 3; k++) {
		b[k] = floor8(p[k]);
		if (b[k] < INT32_MIN || b[k] > INT32_MAX)
			return x;
	}
	x.block = fct_voxgrid_index(R->g, (int32_t)b[0], (int32_t)b[1], (int32_t)b[2]);
	if (x.block < 0)
		return x;
	x.b = fct_voxgrid_at(R->g, (size_t)x.block);
	x.v = (int)(p[0] - 8 * b[0]) + 8 * ((int)(p[1] - 8 * b[1]) + 8 * (int)(p[2] - 8 * b[2]));
	return x;
}

/* The sdf of voxel p when it is observed (mc_observed; the clip box aside,
 * for the gradients read beyond it), NaN otherwise. */
static float seen_value(const struct ref *R, const int64_t p[3])
{
	struct vox x = vox_at(R, p);
	if (!x.b || !mc_observed(x.b->sdf[x.v], x.b->weight[x.v], R->thr))
		return NAN;
	return x.b->sdf[x.v];
}

/* Voxel p is observed and inside the clip box, corners included (the
 * box's cubes, minimum corners in [lo, hi), have corners up to hi). */
static int in_box(const struct ref *R, const int64_t p[3], float *sdf)
{
	for (int k = 0; R->lo && k < 3; k++)
		if (p[k] < R->lo[k] || p[k] > R->hi[k])
			return 0;
	*sdf = seen_value(R, p);
	return *sdf == *sdf;
}

/* Voxel v of block b by its global index. */
static void global_index(const struct ref *R, size_t b, int v, int64_t p[3])
{
	const struct fct_voxblock *B = fct_voxgrid_at(R->g, b);
	p[0] = (int64_t)8 * B->bx + (v & 7);
	p[1] = (int64_t)8 * B->by + (v >> 3 & 7);
	p[2] = (int64_t)8 * B->bz + (v >> 6);
}

/* The cube whose minimum corner is voxel v of block b: its contour (an
 * index in R->C->var), or -1 when the cube is not extracted (a corner
 * outside the box or unobserved, or every corner of one sign, negative
 * being sdf < 0); slot[e]: the vid entry of its edge e when crossed, else
 * NULL. */
static int cube_at(const struct ref *R, size_t b, int v, uint32_t *slot[12])
{
	const struct mc_cases *C = R->C;
	int64_t p[3], q[8][3];
	float val[8];
	int cfg = 0;
	global_index(R, b, v, p);
	for (int c = 0; c < 8; c++) {
		q[c][0] = p[0] + (c & 1), q[c][1] = p[1] + (c >> 1 & 1), q[c][2] = p[2] + (c >> 2);
		if (!in_box(R, q[c], &val[c]))
			return -1;
		cfg |= (val[c] < 0) << c;
	}
	if (cfg == 0 || cfg == 255)
		return -1;
	int id = C->first[cfg] + (C->amb[cfg] ? mc_decide(C, val, cfg, C->amb[cfg]) : 0);
	for (int e = 0; e < 12; e++) {
		struct vox x = vox_at(R, q[C->G.edge_lo[e]]);
		slot[e] = C->var[id].emask >> e & 1
		        ? &R->vid[3 * 512 * (size_t)x.block + 512 * (size_t)(e / 4) + (size_t)x.v]
		        : NULL;
	}
	return id;
}

/* The sdf gradient at observed voxel p, each component from its two
 * neighbours along the axis (mc_diff_f, mc_diff_d). */
static void gradient(const struct ref *R, const int64_t p[3], float gf[3], double gd[3])
{
	float s0 = seen_value(R, p);
	for (int a = 0; a < 3; a++) {
		int64_t up[3] = { p[0], p[1], p[2] }, down[3] = { p[0], p[1], p[2] };
		up[a]++, down[a]--;
		float sp = seen_value(R, up), sm = seen_value(R, down);
		gf[a] = mc_diff_f(s0, sp, sm);
		gd[a] = mc_diff_d(s0, sp, sm);
	}
}

/* Vertex id, on the edge from voxel p along axis a: its place (the zero
 * crossing), its normal (the gradients at the two ends interpolated,
 * normalised: in float, in double where float is not exact enough), its
 * colour (interpolated). */
static void make_vertex(const struct ref *R, const int64_t p[3], int a, uint32_t id)
{
	int64_t q[3] = { p[0], p[1], p[2] };
	q[a]++;
	float s0 = seen_value(R, p), s1 = seen_value(R, q);
	double t = mc_edge_t(s0, s1), *xyz = R->o.xyz + 3 * (size_t)id;
	for (int k = 0; k < 3; k++)
		xyz[k] = (double)p[k] * R->voxel;
	xyz[a] = ((double)p[a] + t) * R->voxel;
	float g0f[3], g1f[3], n[3];
	double g0d[3], g1d[3];
	gradient(R, p, g0f, g0d);
	gradient(R, q, g1f, g1d);
	if (!mc_normal_f(g0f, g1f, t, n))
		mc_normal_d(g0d, g1d, t, a, s1, n);
	for (int k = 0; k < 3; k++)
		R->o.nrm[k][id] = n[k];
	if (R->o.rgb[0]) {
		struct vox x0 = vox_at(R, p), x1 = vox_at(R, q);
		for (int k = 0; k < 3; k++)
			R->o.rgb[k][id] = mc_to_u8((1 - t) * x0.b->rgb[3 * x0.v + k] +
			                           t * x1.b->rgb[3 * x1.v + k]);
	}
}

/* The extraction in four sweeps: the cubes mark the edges they use and are
 * counted; the marked edges are numbered in output order; the vertices;
 * the triangles and centroid vertices. */
static int reference(struct fct_mesh *out, struct ref *R, struct fct_err *err)
{
	const struct mc_cases *C = R->C;
	size_t nb = fct_voxgrid_count(R->g), nv = 0, ncent = 0, ntri = 0;
	if (!(R->vid = fct_alloc_array(nb, 3 * 512 * sizeof *R->vid, err)))
		return -1;
	memset(R->vid, 0xFF, nb * 3 * 512 * sizeof *R->vid);     /* all NONE */
	for (size_t b = 0; b < nb; b++)
		for (int v = 0; v < 512; v++) {
			uint32_t *slot[12];
			int id = cube_at(R, b, v, slot);
			for (int e = 0; id >= 0 && e < 12; e++)
				if (slot[e])
					*slot[e] = USED;
			ntri += id >= 0 ? C->ntri[id] : 0;
			ncent += id >= 0 ? C->ncentre[id] : 0;
		}
	for (size_t i = 0; i < nb * 3 * 512; i++)
		if (R->vid[i] == USED)
			R->vid[i] = (uint32_t)nv++;
	if (nv + ncent > UINT32_MAX - 1)
		return fct_fail(err, "marching cubes: more than 2^32 - 1 vertices");
	if (ntri > UINT32_MAX / 3)
		return fct_fail(err, "marching cubes: more than 2^32 / 3 triangles");
	if (mcubes_output(&R->o, out, nv + ncent, ntri, fct_voxgrid_has_colour(R->g), err))
		return -1;
	for (size_t b = 0; b < nb; b++)
		for (int a = 0; a < 3; a++)
			for (int v = 0; v < 512; v++) {
				uint32_t id = R->vid[3 * 512 * b + 512 * (size_t)a + (size_t)v];
				int64_t p[3];
				global_index(R, b, v, p);
				if (id != NONE)
					make_vertex(R, p, a, id);
			}
	uint32_t *t = out->fvert, cid = (uint32_t)nv;
	for (size_t b = 0; b < nb; b++)
		for (int v = 0; v < 512; v++) {
			uint32_t *slot[12], vid[12];
			int id = cube_at(R, b, v, slot);
			if (id < 0)
				continue;
			for (int e = 0; e < 12; e++)
				vid[e] = slot[e] ? *slot[e] : NONE;
			t = mc_cube_triangles(&R->o, &C->var[id], vid, t, &cid);
		}
	return 0;
}

int fct_mcubes_reference(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                         const int32_t *clip_lo, const int32_t *clip_hi, struct fct_err *err)
{
	fct_mesh_init(out);
	if ((clip_lo == NULL) != (clip_hi == NULL))
		return fct_fail(err, "marching cubes: clip box needs both corners");
	struct ref R = { .g = g, .C = mcubes_cases(), .thr = mc_threshold(min_weight),
		         .lo = clip_lo, .hi = clip_hi, .voxel = fct_voxgrid_voxel(g) };
	int rc = reference(out, &R, err);
	if (rc)
		fct_mesh_free(out);
	free(R.vid);
	return rc;
}

/* The extraction the programs run ------------------------------------------- */

int fct_mcubes_stats(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                     const int32_t *clip_lo, const int32_t *clip_hi, int threads,
                     struct fct_mcubes_stats *stats, struct fct_err *err)
{
	fct_mesh_init(out);
	if ((clip_lo == NULL) != (clip_hi == NULL))
		return fct_fail(err, "marching cubes: clip box needs both corners");
	return mcubes_fast(out, g, min_weight, clip_lo, clip_hi, threads, stats, err);
}

int fct_mcubes(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
               const int32_t *clip_lo, const int32_t *clip_hi, struct fct_err *err)
{
	return fct_mcubes_stats(out, g, min_weight, clip_lo, clip_hi, 0, NULL, err);
}

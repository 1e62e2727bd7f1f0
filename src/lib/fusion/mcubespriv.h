/* mcubespriv.h - what the two marching cubes share: mcubes.c (the contour
 * tables, and the plain extraction that is the reference and the tests'
 * oracle) and mcubesfast.c (the extraction the programs run).  The tables,
 * and inline here the arithmetic that fixes the output's bits (a vertex's
 * place on its edge, its normal, a colour's rounding, the asymptotic
 * decider, a centroid vertex, a cube's triangles), so that the two compute
 * them with the same operations.  Not for other callers: the interface is
 * mcubes.h. */
#ifndef FCT_MCUBESPRIV_H
#define FCT_MCUBESPRIV_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "fusion/mcubes.h"

/* Cube geometry.  Corner c is at (c & 1, c >> 1 & 1, c >> 2 & 1).  Edge e
 * has axis e / 4 and its lower end at the corner edge_lo[e]; face f = 2 *
 * axis + side, side 1 being the face at coordinate 1. */
struct mc_geom {
	uint8_t edge_lo[12], edge_hi[12];
	uint8_t face_edges[6][4];
	uint8_t face_corners[6][4];     /* in cyclic order */
};

/* A cube's contour: loops of crossed edges, in order. */
struct mc_case {
	uint8_t nloops;
	uint8_t len[4];
	uint8_t centre[4];      /* 1: triangulate around the loop's centroid */
	uint8_t edge[12];       /* the loops' edges back to back */
	uint8_t amb;            /* faces with four crossings */
	uint16_t emask;         /* crossed edges */
};

/* The contours of every sign pattern under every decision on its ambiguous
 * faces (656 in all), so that no cube builds one on the spot.  Variant v of
 * pattern cfg (bit c set: corner c negative) is var[first[cfg] + v]: bit i
 * of v set when the i-th of its ambiguous faces (in face order) joins the
 * negative diagonal; variant 0 joins every positive one. */
#define MC_VARIANTS 656

struct mc_cases {
	struct mc_geom G;
	uint16_t first[256];
	struct mc_case var[MC_VARIANTS];
	uint8_t ntri[MC_VARIANTS], ncentre[MC_VARIANTS];   /* a contour's triangles, centroids */
	uint8_t amb[256];                                   /* a pattern's ambiguous faces */
};

/* The tables, built on the first call (thread-safe). */
const struct mc_cases *mcubes_cases(void);

/* The fast extraction (mcubesfast.c): fct_mcubes_stats's work, after its
 * arguments were checked and out initialised. */
int mcubes_fast(struct fct_mesh *out, const struct fct_voxgrid *g, float min_weight,
                const int32_t *clip_lo, const int32_t *clip_hi, int threads,
                struct fct_mcubes_stats *stats, struct fct_err *err);

/* The weight threshold of "observed" (weight >= it): min_weight, at least
 * the smallest positive float (weight 0 is never observed), none for NaN. */
static inline float mc_threshold(float min_weight)
{
	if (isnan(min_weight))
		return INFINITY;
	return min_weight > 0 ? min_weight : FLT_TRUE_MIN;
}

/* Observed: weight at least thr and a finite sdf. */
static inline int mc_observed(float sdf, float weight, float thr)
{
	return weight >= thr && fabsf(sdf) <= FLT_MAX;
}

/* A vertex's t on its edge from the values at its ends: the zero crossing
 * in double, at least 1/256 from either end. */
static inline double mc_edge_t(float s0, float s1)
{
	double t = (double)s0 / ((double)s0 - (double)s1);
	if (!(t >= 1.0 / 256))
		t = 1.0 / 256;
	if (t > 255.0 / 256)
		t = 255.0 / 256;
	return t;
}

/* One component of the sdf gradient at a voxel of value s0 (observed),
 * from the values above (sp) and below (sm) it, NaN where unobserved:
 * central differences, one-sided beside unobserved voxels.  Written as f *
 * (P - M), P the value above or s0 where that is unobserved, M the one
 * below or s0, f 0.5 when both are observed and 1 otherwise, so that it
 * takes no branch; each case is the same operations as spelled out (0.5 *
 * (sp - sm), sp - s0, s0 - sm, s0 - s0 = +0).  In float (mc_diff_f, the
 * normals' first try) and in double (mc_diff_d, their fallback). */
static inline float mc_diff_f(float s0, float sp, float sm)
{
	int hp = sp == sp, hm = sm == sm;
	return (hp && hm ? 0.5f : 1.0f) * ((hp ? sp : s0) - (hm ? sm : s0));
}

static inline double mc_diff_d(double s0, float sp, float sm)
{
	int hp = sp == sp, hm = sm == sm;
	return (hp && hm ? 0.5 : 1.0) * ((hp ? (double)sp : s0) - (hm ? (double)sm : s0));
}

/* The float normal's test: accepted when its squared length n2 is a normal
 * float and at least 1/64 of e2, the squared length of the sum of the
 * interpolated gradients' magnitudes (per axis |(1 - t) g0| + |t g1|), so
 * that the float rounding (a few units of 2^-24 of e) moves no component by
 * more than about 2e-6; cancelling gradients go to mc_normal_d. */
#define MC_NRM_CANCEL 64.0f

/* The normal at t between float gradients g0 and g1 (mc_diff_f), in float
 * into n: 1, or 0 (n undefined) where float is not exact enough. */
static inline int mc_normal_f(const float g0[3], const float g1[3], double t, float n[3])
{
	float T = (float)t, U = 1.0f - T, nv[3], ev[3];
	for (int k = 0; k < 3; k++) {
		float p = U * g0[k], q = T * g1[k];
		nv[k] = p + q;
		ev[k] = fabsf(p) + fabsf(q);
	}
	float n2 = nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2];
	float e2 = ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2];
	if (!(n2 >= FLT_MIN && n2 <= FLT_MAX && n2 * MC_NRM_CANCEL >= e2))
		return 0;
	float inv = 1.0f / sqrtf(n2);
	for (int k = 0; k < 3; k++)
		n[k] = nv[k] * inv;
	return 1;
}

/* The same in double from double gradients (mc_diff_d), the fallback: a
 * zero gradient gives the edge's axis a, towards the positive end (s1 is
 * the value at the edge's upper end). */
static inline void mc_normal_d(const double g0[3], const double g1[3], double t, int a, float s1,
                               float n_out[3])
{
	double n[3];
	for (int k = 0; k < 3; k++)
		n[k] = (1 - t) * g0[k] + t * g1[k];
	double len = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
	if (len > 0) {
		len = 1 / sqrt(len);
		for (int k = 0; k < 3; k++)
			n_out[k] = (float)(n[k] * len);
	} else {
		for (int k = 0; k < 3; k++)
			n_out[k] = 0;
		n_out[a] = s1 >= 0 ? 1.0f : -1.0f;
	}
}

static inline uint8_t mc_to_u8(double v)
{
	v = floor(v + 0.5);
	return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* The asymptotic decider on the ambiguous faces amb of a cube of sign
 * pattern cfg whose corner values are val[0..7] (only the corners of those
 * faces are read): the variant (struct mc_cases).  On each face the
 * diagonal with the larger product of values is joined (exact products in
 * double; a tie joins the positive one), so both cubes sharing the face
 * decide it alike. */
static inline int mc_decide(const struct mc_cases *C, const float val[8], int cfg, int amb)
{
	int variant = 0, i = 0;
	for (int f = 0; f < 6; f++) {
		if (!(amb >> f & 1))
			continue;
		const uint8_t *fc = C->G.face_corners[f];
		double d0 = (double)val[fc[0]] * (double)val[fc[2]];
		double d1 = (double)val[fc[1]] * (double)val[fc[3]];
		int c0neg = cfg >> fc[0] & 1;
		double pos = c0neg ? d1 : d0, neg = c0neg ? d0 : d1;
		if (!(pos >= neg))
			variant |= 1 << i;
		i++;
	}
	return variant;
}

/* The output's vertex columns (rgb[k] NULL without colour). */
struct mc_out {
	double *xyz;
	float *nrm[3];
	uint8_t *rgb[3];
};

/* Size out (initialised, empty) for nv vertices and ntri triangles, with
 * float nx ny nz and, when colour, uchar red green blue; o gets their
 * columns.  Returns 0 or -1 (out of memory). */
int mcubes_output(struct mc_out *o, struct fct_mesh *out, size_t nv, size_t ntri, int colour,
                  struct fct_err *err);

/* Centroid vertex id of the loop of vertices vid[ed[0..len-1]]: the mean
 * of their positions (and colours), their normals' sum normalised.  The
 * sums are kept in registers (in memory, each addition waited for the one
 * before through a store and a load). */
static inline void mc_centroid(const struct mc_out *o, const uint32_t *vid, const uint8_t *ed,
                               int len, uint32_t id)
{
	double px = 0, py = 0, pz = 0, nx = 0, ny = 0, nz = 0;
	for (int i = 0; i < len; i++) {
		size_t v = vid[ed[i]];
		const double *q = o->xyz + 3 * v;
		px += q[0], py += q[1], pz += q[2];
		nx += o->nrm[0][v], ny += o->nrm[1][v], nz += o->nrm[2][v];
	}
	double nl = sqrt(nx * nx + ny * ny + nz * nz), *p = o->xyz + 3 * (size_t)id;
	p[0] = px / len, p[1] = py / len, p[2] = pz / len;
	o->nrm[0][id] = nl > 0 ? (float)(nx / nl) : 0.0f;
	o->nrm[1][id] = nl > 0 ? (float)(ny / nl) : 0.0f;
	o->nrm[2][id] = nl > 0 ? (float)(nz / nl) : 0.0f;
	for (int k = 0; k < 3 && o->rgb[k]; k++) {
		double col = 0;
		for (int i = 0; i < len; i++)
			col += o->rgb[k][vid[ed[i]]];
		o->rgb[k][id] = mc_to_u8(col / len);
	}
}

/* The triangles of a cube of contour mc whose crossed edges have the
 * vertices vid[edge], into t: each loop as a fan from its first vertex, or
 * around its centroid (vertices cid, cid + 1, ... in loop order, made here
 * from the loop's vertices, which must be written).  Returns the end of
 * the triangles written; *cid is moved past the centroids. */
static inline uint32_t *mc_cube_triangles(const struct mc_out *o, const struct mc_case *mc,
                                          const uint32_t *vid, uint32_t *t, uint32_t *cid)
{
	const uint8_t *ed = mc->edge;
	for (int l = 0; l < mc->nloops; l++) {
		int len = mc->len[l];
		if (mc->centre[l]) {
			uint32_t id = (*cid)++;
			mc_centroid(o, vid, ed, len, id);
			for (int i = 0; i < len; i++, t += 3)
				t[0] = id, t[1] = vid[ed[i]], t[2] = vid[ed[(i + 1) % len]];
		} else {
			for (int i = 1; i + 1 < len; i++, t += 3)
				t[0] = vid[ed[0]], t[1] = vid[ed[i]], t[2] = vid[ed[i + 1]];
		}
		ed += len;
	}
	return t;
}

#endif

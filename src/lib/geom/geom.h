/* geom.h - small 3-vector helpers and exact closest points on segments and
 * triangles, in double precision.
 *
 * Vectors are plain double[3] arrays so they sit directly on fct_mesh.xyz
 * (vertex i is xyz + 3*i).  The closest-point routines follow Ericson,
 * "Real-Time Collision Detection" (2005), section 5.1.5: the query point is
 * classified into one of the seven Voronoi regions of the triangle (three
 * vertices, three edges, the face) from signs of dot products, so the answer
 * is exact up to rounding in every region.  A triangle with (nearly) no area
 * is treated as the union of its three edges, each of which may itself be a
 * single point, so degenerate input gives the true closest point rather than
 * a division by zero. */
#ifndef FCT_GEOM_H
#define FCT_GEOM_H

#include <stddef.h>

static inline void fct_v3_sub(double r[3], const double a[3], const double b[3])
{
	r[0] = a[0] - b[0];
	r[1] = a[1] - b[1];
	r[2] = a[2] - b[2];
}

static inline void fct_v3_add(double r[3], const double a[3], const double b[3])
{
	r[0] = a[0] + b[0];
	r[1] = a[1] + b[1];
	r[2] = a[2] + b[2];
}

/* r = a + s*b */
static inline void fct_v3_axpy(double r[3], const double a[3], double s, const double b[3])
{
	r[0] = a[0] + s * b[0];
	r[1] = a[1] + s * b[1];
	r[2] = a[2] + s * b[2];
}

static inline double fct_v3_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void fct_v3_cross(double r[3], const double a[3], const double b[3])
{
	double x = a[1] * b[2] - a[2] * b[1];
	double y = a[2] * b[0] - a[0] * b[2];
	double z = a[0] * b[1] - a[1] * b[0];
	r[0] = x;
	r[1] = y;
	r[2] = z;
}

/* fmax(x, y) without the call to libm: a NaN gives way to the other
 * operand (of +0 and -0 either may come, as with fmax). */
static inline double fct_fmax(double x, double y)
{
	return x > y || y != y ? x : y;
}

/* Squared distance between points a and b. */
static inline double fct_v3_dist2(const double a[3], const double b[3])
{
	double d[3];
	fct_v3_sub(d, a, b);
	return fct_v3_dot(d, d);
}

/* Squared distance of p from the line through a and b (from a itself when
 * a and b coincide). */
static inline double fct_v3_line_distance2(const double p[3], const double a[3], const double b[3])
{
	double ab[3], ap[3], x[3];
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ap, p, a);
	fct_v3_cross(x, ab, ap);
	double l2 = fct_v3_dot(ab, ab);
	return l2 > 0 ? fct_v3_dot(x, x) / l2 : fct_v3_dot(ap, ap);
}

/* Where on a triangle the closest point lies (the Voronoi region of p). */
enum fct_tri_region {
	FCT_TRI_A, FCT_TRI_B, FCT_TRI_C,        /* at a vertex */
	FCT_TRI_AB, FCT_TRI_BC, FCT_TRI_CA,     /* inside an edge */
	FCT_TRI_FACE,                           /* inside the face */
	FCT_TRI_DEGENERATE                      /* the triangle has no area */
};

/* Closest point q on segment ab to p; returns |p - q|^2.  a == b is a point. */
double fct_closest_on_segment(const double p[3], const double a[3], const double b[3],
                              double q[3]);

/* The square of fct_triangle_degenerate's limit on |(b-a) x (c-a)| for a
 * longest edge squared of l2; it grows with l2 (rounding is monotone), so
 * the limit of a bound on l2 bounds the limit. */
static inline double fct_degenerate_limit(double l2)
{
	double lim = 1e-12 * l2;
	return lim * lim;
}

/* Does triangle abc have too little area for its face region to be computed
 * reliably?  True when |(b-a) x (c-a)| <= 1e-12 * (longest edge)^2, i.e. the
 * face is nowhere wider than 1e-12 of its length, so treating it as its three
 * edges moves no closest point by more than that.  Inline, so that a caller
 * that has the cross product (b-a) x (c-a) already shares it. */
static inline int fct_triangle_degenerate(const double a[3], const double b[3], const double c[3])
{
	double ab[3], ac[3], bc[3], n[3];
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ac, c, a);
	fct_v3_sub(bc, c, b);
	fct_v3_cross(n, ab, ac);
	double l2 = fct_fmax(fct_v3_dot(ab, ab), fct_fmax(fct_v3_dot(ac, ac), fct_v3_dot(bc, bc)));
	/* l2 == 0 (all corners equal) is degenerate too: 0 <= 0. */
	return fct_v3_dot(n, n) <= fct_degenerate_limit(l2);
}

/* Closest point q on triangle abc to p; returns |p - q|^2 and, when region is
 * not NULL, the region it found.  Degenerate triangles (see above: collinear
 * or coincident corners) give the closest point on their edges and
 * FCT_TRI_DEGENERATE. */
double fct_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double q[3], enum fct_tri_region *region);

/* The same for a triangle known not to be degenerate: Ericson's
 * ClosestPtPointTriangle, inline because the BVH calls it in its inner loop.
 * On a degenerate triangle the face case may divide by zero. */
static inline double fct_closest_on_triangle_nd(const double p[3], const double a[3],
                                                const double b[3], const double c[3],
                                                double q[3], enum fct_tri_region *region)
{
	double ab[3], ac[3], ap[3], bp[3], cp[3];
	enum fct_tri_region r;
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ac, c, a);
	fct_v3_sub(ap, p, a);
	double d1 = fct_v3_dot(ab, ap), d2 = fct_v3_dot(ac, ap);
	if (d1 <= 0 && d2 <= 0) {
		q[0] = a[0], q[1] = a[1], q[2] = a[2];
		r = FCT_TRI_A;
		goto done;
	}
	fct_v3_sub(bp, p, b);
	double d3 = fct_v3_dot(ab, bp), d4 = fct_v3_dot(ac, bp);
	if (d3 >= 0 && d4 <= d3) {
		q[0] = b[0], q[1] = b[1], q[2] = b[2];
		r = FCT_TRI_B;
		goto done;
	}
	double vc = d1 * d4 - d3 * d2;
	if (vc <= 0 && d1 >= 0 && d3 <= 0) {
		fct_v3_axpy(q, a, d1 / (d1 - d3), ab);
		r = FCT_TRI_AB;
		goto done;
	}
	fct_v3_sub(cp, p, c);
	double d5 = fct_v3_dot(ab, cp), d6 = fct_v3_dot(ac, cp);
	if (d6 >= 0 && d5 <= d6) {
		q[0] = c[0], q[1] = c[1], q[2] = c[2];
		r = FCT_TRI_C;
		goto done;
	}
	double vb = d5 * d2 - d1 * d6;
	if (vb <= 0 && d2 >= 0 && d6 <= 0) {
		fct_v3_axpy(q, a, d2 / (d2 - d6), ac);
		r = FCT_TRI_CA;
		goto done;
	}
	double va = d3 * d6 - d5 * d4;
	if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
		double bc[3];
		fct_v3_sub(bc, c, b);
		fct_v3_axpy(q, b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), bc);
		r = FCT_TRI_BC;
		goto done;
	}
	{
		double denom = 1.0 / (va + vb + vc);
		double v = vb * denom, w = vc * denom;
		q[0] = a[0] + ab[0] * v + ac[0] * w;
		q[1] = a[1] + ab[1] * v + ac[1] * w;
		q[2] = a[2] + ab[2] * v + ac[2] * w;
		r = FCT_TRI_FACE;
	}
done:
	if (region)
		*region = r;
	return fct_v3_dist2(p, q);
}

/* (b - a) x (c - a): triangle abc's normal, its length twice the area. */
static inline void fct_triangle_cross(double n[3], const double a[3], const double b[3], const double c[3])
{
	double ab[3], ac[3];
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ac, c, a);
	fct_v3_cross(n, ab, ac);
}

/* Twice the area of triangle abc (|(b - a) x (c - a)|). */
double fct_triangle_area2(const double a[3], const double b[3], const double c[3]);

/* qsort's comparison of doubles, ascending (NaN not expected). */
int fct_cmp_double(const void *a, const void *b);

/* The value a[k] would hold were a[0..n) sorted ascending (k < n), a
 * partly reordered: Hoare's selection with the median of three as pivot,
 * linear on average (NaN not expected). */
double fct_select_kth(double *a, size_t n, size_t k);

#endif

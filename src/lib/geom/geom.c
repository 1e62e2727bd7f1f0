/* geom.c - closest points on segments and triangles (see geom.h).
 * Ericson, "Real-Time Collision Detection", 5.1.2 (segment) and 5.1.5
 * (triangle). */
#include "geom/geom.h"

#include <math.h>

double fct_closest_on_segment(const double p[3], const double a[3], const double b[3],
                              double q[3])
{
	double ab[3], ap[3];
	fct_v3_sub(ab, b, a);
	fct_v3_sub(ap, p, a);
	double t = fct_v3_dot(ap, ab), len2 = fct_v3_dot(ab, ab);
	/* Clamping before dividing keeps a zero-length segment (a point) exact. */
	if (t <= 0 || len2 <= 0) {
		q[0] = a[0], q[1] = a[1], q[2] = a[2];
	} else if (t >= len2) {
		q[0] = b[0], q[1] = b[1], q[2] = b[2];
	} else {
		fct_v3_axpy(q, a, t / len2, ab);
	}
	return fct_v3_dist2(p, q);
}

double fct_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                               const double c[3], double q[3], enum fct_tri_region *region)
{
	if (!fct_triangle_degenerate(a, b, c))
		return fct_closest_on_triangle_nd(p, a, b, c, q, region);
	/* No usable face: the nearest of the three edges (ties keep the first). */
	double t[3];
	double best = fct_closest_on_segment(p, a, b, q);
	double d = fct_closest_on_segment(p, b, c, t);
	if (d < best) {
		best = d;
		q[0] = t[0], q[1] = t[1], q[2] = t[2];
	}
	d = fct_closest_on_segment(p, c, a, t);
	if (d < best) {
		best = d;
		q[0] = t[0], q[1] = t[1], q[2] = t[2];
	}
	if (region)
		*region = FCT_TRI_DEGENERATE;
	return best;
}

double fct_triangle_area2(const double a[3], const double b[3], const double c[3])
{
	double n[3];
	fct_triangle_cross(n, a, b, c);
	return sqrt(fct_v3_dot(n, n));
}

int fct_cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

double fct_select_kth(double *a, size_t n, size_t k)
{
	size_t lo = 0, hi = n - 1;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		double x = a[lo], y = a[mid], z = a[hi];
		double pivot = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
		size_t i = lo, j = hi;
		while (i <= j) {
			while (a[i] < pivot)
				i++;
			while (a[j] > pivot)
				j--;
			if (i <= j) {
				double t = a[i];
				a[i] = a[j], a[j] = t;
				i++;
				if (j == 0)
					break;
				j--;
			}
		}
		/* a[lo..j] <= pivot <= a[i..hi], and between them equal to it */
		if (k <= j)
			hi = j;
		else if (k >= i)
			lo = i;
		else
			return a[k];
	}
	return a[k];
}

/* predicates.h - exact orientation and in-circle tests for points in the plane.
 *
 * The idea is Shewchuk's ("Adaptive Precision Floating-Point Arithmetic and
 * Fast Robust Geometric Predicates", Discrete & Computational Geometry 18,
 * 1997): evaluate the determinant in ordinary double arithmetic together
 * with a bound on its rounding error; when the value is farther from zero
 * than the bound its sign is certain, and only otherwise is the determinant
 * evaluated exactly, as a floating-point expansion (a sum of doubles whose
 * bits do not overlap, added and multiplied with error-free transformations).
 * The code is our own; see predicates.c for the error bounds and why they
 * hold.
 *
 * The sign returned is the exact sign of the determinant of the given
 * doubles, for every finite input: expansions are exact while no partial
 * product underflows or overflows, which holds when every coordinate is 0
 * or between 2^-180 and 2^180 in magnitude; outside that range (subnormal,
 * tiny or huge coordinates) the exact stage uses a small big-integer
 * evaluation instead.  Non-finite coordinates give an unspecified sign.
 *
 * Assumptions: IEEE 754 binary64 doubles evaluated in double precision with
 * round-to-nearest-even (FLT_EVAL_METHOD 0, as with SSE2 on x86-64 or any
 * AArch64; not x87 extended precision), and no contraction of a*b+c into a
 * fused multiply-add: the build sets -ffp-contract=off, and predicates.c
 * refuses to compile when FLT_EVAL_METHOD is not 0.  Neither -ffast-math
 * nor a change of rounding mode may be used around these calls.
 *
 * Only the sign of the result is meaningful; its magnitude approximates the
 * determinant (twice the signed area for orient2d) but is not exact. */
#ifndef FCT_PREDICATES_H
#define FCT_PREDICATES_H

/* Positive when a, b, c turn counter-clockwise (c lies to the left of the
 * directed line a->b in a frame with x right and y up), negative when they
 * turn clockwise, zero when they are collinear.  The value approximates
 * (b - a) x (c - a) = (ax - cx)(by - cy) - (ay - cy)(bx - cx).  In an image
 * frame with u right and v down, "positive" looks clockwise on screen. */
double fct_orient2d(const double a[2], const double b[2], const double c[2]);

/* For a, b, c in counter-clockwise order (fct_orient2d > 0): positive when d
 * lies strictly inside the circle through a, b, c, negative when strictly
 * outside, zero when the four points are cocircular.  The sign is reversed
 * when a, b, c are clockwise.  Always the sign of the determinant
 *   | ax-dx  ay-dy  (ax-dx)^2+(ay-dy)^2 |
 *   | bx-dx  by-dy  (bx-dx)^2+(by-dy)^2 |
 *   | cx-dx  cy-dy  (cx-dx)^2+(cy-dy)^2 |
 * (also when a, b, c are collinear). */
double fct_incircle(const double a[2], const double b[2], const double c[2], const double d[2]);

#endif

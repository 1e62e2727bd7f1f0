/* lanes.h - a few numbers at once: GCC's and Clang's vector extension,
 * which every target compiles (to SSE2 on x86-64, NEON on arm64, scalar
 * code elsewhere).  Lane by lane the same IEEE operations as scalar code,
 * so the same bits; comparisons give a lane of all ones where true. */
#ifndef FCT_LANES_H
#define FCT_LANES_H

#include <stdint.h>
#include <string.h>

typedef double v2d __attribute__((vector_size(16)));
typedef int64_t v2i __attribute__((vector_size(16)));
typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));

static inline v2d load2(const double *p)
{
	v2d v;
	memcpy(&v, p, sizeof v);
	return v;
}

static inline void store2(double *p, v2d v)
{
	memcpy(p, &v, sizeof v);
}

static inline v4f load4(const float *p)
{
	v4f v;
	memcpy(&v, p, sizeof v);
	return v;
}

static inline void store4(float *p, v4f v)
{
	memcpy(p, &v, sizeof v);
}

/* Lane by lane: where m is all ones, a, else b. */
static inline v2d select2(v2i m, v2d a, v2d b)
{
	return (v2d)(((v2i)a & m) | ((v2i)b & ~m));
}

static inline v4f select4(v4i m, v4f a, v4f b)
{
	return (v4f)(((v4i)a & m) | ((v4i)b & ~m));
}

#endif

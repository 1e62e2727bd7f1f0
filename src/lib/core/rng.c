/* rng.c - xoshiro256** seeded by splitmix64 (see rng.h).  The constants are
 * those of the reference implementations at https://prng.di.unimi.it/. */
#include "core/rng.h"

#include <math.h>

uint64_t fct_splitmix64(uint64_t *state)
{
	uint64_t z = (*state += 0x9e3779b97f4a7c15u);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
	return z ^ (z >> 31);
}

void fct_rng_seed(struct fct_rng *r, uint64_t seed)
{
	/* splitmix64 never yields four zero words, the one state xoshiro must avoid. */
	for (int i = 0; i < 4; i++)
		r->s[i] = fct_splitmix64(&seed);
}

static inline uint64_t rotl(uint64_t x, int k)
{
	return (x << k) | (x >> (64 - k));
}

uint64_t fct_rng_next(struct fct_rng *r)
{
	uint64_t *s = r->s;
	uint64_t result = rotl(s[1] * 5, 7) * 9;
	uint64_t t = s[1] << 17;
	s[2] ^= s[0];
	s[3] ^= s[1];
	s[1] ^= s[2];
	s[0] ^= s[3];
	s[2] ^= t;
	s[3] = rotl(s[3], 45);
	return result;
}

double fct_rng_uniform(struct fct_rng *r)
{
	return (double)(fct_rng_next(r) >> 11) * 0x1.0p-53;
}

uint64_t fct_rng_below(struct fct_rng *r, uint64_t n)
{
	/* Reject the lowest (2^64 mod n) values so every residue is equally likely. */
	uint64_t lim = (0 - n) % n;
	for (;;) {
		uint64_t x = fct_rng_next(r);
		if (x >= lim)
			return x % n;
	}
}

double fct_rng_normal(struct fct_rng *r)
{
	for (;;) {
		double u = 2 * fct_rng_uniform(r) - 1, v = 2 * fct_rng_uniform(r) - 1;
		double s = u * u + v * v;
		if (s > 0 && s < 1)
			return u * sqrt(-2 * log(s) / s);
	}
}

void fct_rng_jump(struct fct_rng *r)
{
	static const uint64_t jump[4] = {
		0x180ec6d33cfd0abau, 0xd5a61266f0c9392cu, 0xa9582618e03fc9aau, 0x39abdc4529b1661cu
	};
	uint64_t s0 = 0, s1 = 0, s2 = 0, s3 = 0;
	for (int i = 0; i < 4; i++) {
		for (int b = 0; b < 64; b++) {
			if (jump[i] & (UINT64_C(1) << b)) {
				s0 ^= r->s[0];
				s1 ^= r->s[1];
				s2 ^= r->s[2];
				s3 ^= r->s[3];
			}
			fct_rng_next(r);
		}
	}
	r->s[0] = s0;
	r->s[1] = s1;
	r->s[2] = s2;
	r->s[3] = s3;
}

/* rng.h - the project's one random number generator: seeded, in-tree, and
 * the same sequence on every platform, so sampling and synthetic data are
 * reproducible byte for byte.
 *
 * xoshiro256** 1.0 (Blackman and Vigna, "Scrambled linear pseudorandom number
 * generators", 2018), its 256-bit state filled from a 64-bit seed by
 * splitmix64, as the authors recommend.  Not for cryptography. */
#ifndef FCT_RNG_H
#define FCT_RNG_H

#include <stdint.h>

struct fct_rng {
	uint64_t s[4];
};

/* One step of splitmix64: advance *state and return the next output. */
uint64_t fct_splitmix64(uint64_t *state);

/* Seed r from a 64-bit seed (any value, 0 included). */
void fct_rng_seed(struct fct_rng *r, uint64_t seed);

/* The next 64 random bits. */
uint64_t fct_rng_next(struct fct_rng *r);

/* Uniform double in [0, 1): the top 53 bits of the next output times 2^-53. */
double fct_rng_uniform(struct fct_rng *r);

/* Uniform integer in [0, n), without modulo bias; n must be > 0. */
uint64_t fct_rng_below(struct fct_rng *r, uint64_t n);

/* Standard normal deviate (Marsaglia's polar method; uses two or more
 * outputs per call, none kept between calls). */
double fct_rng_normal(struct fct_rng *r);

/* Advance r by 2^128 steps: calling it k times on copies of one generator
 * gives k non-overlapping streams, e.g. one per thread or per block. */
void fct_rng_jump(struct fct_rng *r);

#endif

/* test_rng - the seeded generator (rng.h) against the reference
 * implementations' known outputs, and the statistics of its derived draws. */
#include <stdint.h>

#include "check.h"
#include "core/rng.h"

static void test_rng(void)
{
	/* splitmix64 from 0: the published first outputs. */
	uint64_t st = 0;
	CHECK(fct_splitmix64(&st) == UINT64_C(0xe220a8397b1dcdaf));
	CHECK(fct_splitmix64(&st) == UINT64_C(0x6e789e6aa1b965f4));
	/* xoshiro256** seeded with 1, as computed by a transliteration of the
	 * reference C code into Python's big integers. */
	struct fct_rng r;
	fct_rng_seed(&r, 1);
	CHECK(fct_rng_next(&r) == UINT64_C(0xb3f2af6d0fc710c5));
	CHECK(fct_rng_next(&r) == UINT64_C(0x853b559647364cea));
	CHECK(fct_rng_next(&r) == UINT64_C(0x92f89756082a4514));
	fct_rng_seed(&r, 1);
	CHECK_NEAR(fct_rng_uniform(&r), 0.7029218331588505, 0);
	fct_rng_seed(&r, 1);
	fct_rng_jump(&r);
	CHECK(fct_rng_next(&r) == UINT64_C(0x332802f81eaae9d0));

	/* below(n) covers [0, n) evenly; normal has mean 0 and variance 1. */
	fct_rng_seed(&r, 7);
	int hist[6] = {0};
	int out_of_range = 0;
	for (int i = 0; i < 60000; i++) {
		uint64_t v = fct_rng_below(&r, 6);
		if (v < 6) hist[v]++;
		else out_of_range++;
	}
	CHECK_INT(out_of_range, 0);
	for (int k = 0; k < 6; k++)   /* 10000 expected, sd 91 */
		CHECK_MSG(hist[k] > 9600 && hist[k] < 10400, "bin %d: %d", k, hist[k]);
	double s = 0, s2 = 0;
	for (int i = 0; i < 100000; i++) {
		double x = fct_rng_normal(&r);
		s += x;
		s2 += x * x;
	}
	CHECK_NEAR(s / 100000, 0, 0.015);        /* sd of the mean 0.0032 */
	CHECK_NEAR(s2 / 100000, 1, 0.03);        /* sd of the variance 0.0045 */
}

int main(void)
{
	test_rng();
	CHECK_DONE();
}

/* test_arena.c - scratch arrays freed together; growth keeps the contents
 * and the arena's hold on the moved block (make sanitize checks that
 * nothing leaks and nothing is freed twice). */
#include <stdint.h>
#include <string.h>

#include "core/arena.h"
#include "check.h"

static void test_arrays(void)
{
	struct fct_arena a = {0};
	struct fct_err err = {0};
	int *x = fct_arena_array(&a, 100, sizeof *x, &err);
	double *z = fct_arena_zeroed(&a, 1000, sizeof *z, &err);
	CHECK(x && z);
	CHECK_INT(a.n, 2);
	double sum = 0;
	for (int i = 0; i < 1000; i++)
		sum += z[i];
	CHECK(sum == 0);
	/* n == 0 is one element, as fct_alloc_array: NULL always means failure */
	CHECK(fct_arena_array(&a, 0, 8, &err) != NULL);
	/* an overflowing size fails with a message and leaves the arena whole */
	CHECK(fct_arena_array(&a, SIZE_MAX / 2, 4, &err) == NULL);
	CHECK(strstr(err.msg, "overflow") != NULL);
	CHECK_INT(a.n, 3);
	fct_arena_free(&a);
	CHECK_INT(a.n, 0);
	CHECK(a.blocks == NULL);
	fct_arena_free(&a); /* twice is harmless */
	fct_arena_free(NULL);
}

static void test_grow(void)
{
	struct fct_arena a = {0};
	struct fct_err err = {0};
	int *keep = fct_arena_array(&a, 4, sizeof *keep, &err);
	uint32_t *v = NULL;
	size_t cap = 0, n = 0;
	for (uint32_t i = 0; i < 5000; i++) {
		if (fct_arena_grow(&a, (void **)&v, &cap, n + 1, sizeof *v, &err))
			break;
		v[n++] = i * 3;
	}
	CHECK_INT(n, 5000);
	CHECK(cap >= 5000);
	int ok = 1;
	for (uint32_t i = 0; i < n; i++)
		ok &= v[i] == i * 3;
	CHECK(ok);
	CHECK_INT(a.n, 2); /* keep and v: the moved block replaced its old self */
	CHECK(a.blocks[0] == keep && a.blocks[1] == v);
	/* a pointer the arena does not hold is refused, not freed */
	int local[4];
	void *p = local;
	size_t pcap = 4;
	CHECK(fct_arena_grow(&a, &p, &pcap, 8, sizeof(int), &err) == -1);
	CHECK(p == local && pcap == 4);
	fct_arena_free(&a);
}

int main(void)
{
	test_arrays();
	test_grow();
	CHECK_DONE();
}

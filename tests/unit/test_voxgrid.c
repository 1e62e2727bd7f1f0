/* test_voxgrid.c - the sparse block volume: floor division of negative
 * indices, creation order, lookups after many rehashes, the memory limit,
 * dropping blocks (order kept, lookups, storage reused zeroed). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fusion/voxgrid.h"

static struct fct_err err;

static void test_floor(void)
{
	CHECK_INT(fct_vox_block_of(0), 0);
	CHECK_INT(fct_vox_block_of(7), 0);
	CHECK_INT(fct_vox_block_of(8), 1);
	CHECK_INT(fct_vox_block_of(-1), -1);
	CHECK_INT(fct_vox_block_of(-8), -1);
	CHECK_INT(fct_vox_block_of(-9), -2);
	CHECK_INT(fct_vox_block_of(INT32_MIN), INT32_MIN / 8);
	CHECK_INT(fct_vox_block_of(INT32_MAX), INT32_MAX / 8);
	CHECK_INT(fct_vox_local_of(-1), 7);
	CHECK_INT(fct_vox_local_of(-8), 0);
	CHECK_INT(fct_vox_local_of(13), 5);
	CHECK_INT(fct_vox_local_of(INT32_MIN), 0);
	int ok = 1;
	for (int32_t i = -100; i <= 100; i++)
		ok &= fct_vox_block_of(i) == (int32_t)floor(i / 8.0) &&
		      fct_vox_local_of(i) == i - 8 * (int32_t)floor(i / 8.0);
	CHECK(ok);
}

static void test_blocks(void)
{
	struct fct_voxgrid *g = fct_voxgrid_new(0.01, 0, &err);
	CHECK(g != NULL);
	CHECK_NEAR(fct_voxgrid_voxel(g), 0.01, 0);
	CHECK_INT(fct_voxgrid_count(g), 0);
	CHECK(fct_voxgrid_block(g, 1, 2, 3, 0, &err) == NULL);
	CHECK_INT(fct_voxgrid_count(g), 0);
	/* 20^3 = 8000 blocks over negative and positive coordinates, in a
	 * scrambled order; creation order must be kept */
	int n = 0, ok = 1, zero = 1;
	for (int s = 0; s < 8000; s++) {
		int q = (s * 4099) % 8000;
		int32_t bx = q % 20 - 10, by = (q / 20) % 20 - 10, bz = q / 400 - 10;
		struct fct_voxblock *b = fct_voxgrid_block(g, bx, by, bz, 1, &err);
		ok &= b != NULL && b->bx == bx && b->by == by && b->bz == bz && b->rgb == NULL;
		if (!b)
			break;
		for (int v = 0; v < 512; v++)
			zero &= b->sdf[v] == 0 && b->weight[v] == 0;
		b->sdf[0] = (float)s;
		n++;
	}
	CHECK(ok);
	CHECK(zero);
	CHECK_INT(fct_voxgrid_count(g), 8000);
	ok = 1;
	for (int s = 0; s < 8000; s++) {
		int q = (s * 4099) % 8000;
		int32_t bx = q % 20 - 10, by = (q / 20) % 20 - 10, bz = q / 400 - 10;
		struct fct_voxblock *b = fct_voxgrid_at(g, (size_t)s);
		ok &= b && b->bx == bx && b->by == by && b->bz == bz && b->sdf[0] == (float)s;
		ok &= fct_voxgrid_block(g, bx, by, bz, 0, &err) == b;
		ok &= fct_voxgrid_block(g, bx, by, bz, 1, &err) == b;
	}
	CHECK(ok);
	CHECK_INT(fct_voxgrid_count(g), 8000);
	CHECK(fct_voxgrid_at(g, 8000) == NULL);
	CHECK(fct_voxgrid_block(g, 10, 0, 0, 0, &err) == NULL);

	/* voxel access: voxel (-1, 8, 17) is block (-1, 1, 2), local 7 + 8*(0 + 8*1) */
	int local;
	struct fct_voxblock *b = fct_voxgrid_voxel_at(g, -1, 8, 17, 0, &local, &err);
	CHECK(b == fct_voxgrid_block(g, -1, 1, 2, 0, &err));
	CHECK_INT(local, 7 + 64);
	b->sdf[local] = -0.5f;
	b->weight[local] = 2;
	float s, w;
	CHECK_INT(fct_voxgrid_get(g, -1, 8, 17, &s, &w), 1);
	CHECK_NEAR(s, -0.5, 0);
	CHECK_NEAR(w, 2, 0);
	CHECK_INT(fct_voxgrid_get(g, 1000, 8, 17, &s, &w), 0);
	CHECK_NEAR(w, 0, 0);
	/* at least the blocks themselves, at most twice the estimate */
	CHECK(fct_voxgrid_bytes(g) >= 8000 * sizeof(struct fct_voxblock));
	CHECK(fct_voxgrid_bytes(g) <= 2 * 8000 * fct_voxgrid_block_bytes(0));
	fct_voxgrid_free(g);
}

static void test_colour_and_limit(void)
{
	struct fct_voxgrid *g = fct_voxgrid_new(0.5, 1, &err);
	CHECK(g != NULL);
	CHECK_INT(fct_voxgrid_has_colour(g), 1);
	fct_voxgrid_set_limit(g, 20 * fct_voxgrid_block_bytes(1) * 64);
	size_t made = 0;
	int ok = 1;
	for (int32_t i = 0; i < 100000; i++) {
		struct fct_voxblock *b = fct_voxgrid_block(g, i, -i, 0, 1, &err);
		if (!b)
			break;
		ok &= b->rgb != NULL;
		for (int v = 0; v < 3 * 512; v++)
			ok &= b->rgb[v] == 0;
		b->rgb[3 * 511 + 2] = 255;
		made++;
	}
	CHECK(ok);
	/* refused after some 1200 blocks, with the figure, not at 100000 */
	CHECK(made >= 1000 && made < 1400);
	CHECK(strstr(err.msg, "over the limit of") != NULL);
	CHECK_INT(fct_voxgrid_count(g), made);
	CHECK(fct_voxgrid_bytes(g) <= 20 * fct_voxgrid_block_bytes(1) * 64);
	CHECK_NEAR(fct_voxgrid_at(g, made - 1)->rgb[3 * 511 + 2], 255, 0);
	fct_voxgrid_free(g);
	fct_voxgrid_free(NULL);

	CHECK(fct_voxgrid_new(0, 0, &err) == NULL);
	CHECK(fct_voxgrid_new(-1, 0, &err) == NULL);
	CHECK(fct_voxgrid_new(NAN, 0, &err) == NULL);
	CHECK(fct_voxgrid_new(INFINITY, 0, &err) == NULL);
}

/* Blocks 100 + 3000 scrambled ones; drop every third of the 3000 and
 * check the order, the lookups of kept and dropped blocks, that no slab
 * grows while the dropped storage is reused, and that it comes back zero. */
static void test_drop(void)
{
	struct fct_voxgrid *g = fct_voxgrid_new(0.1, 1, &err);
	CHECK(g != NULL);
	int ok = 1;
	for (int32_t i = 0; i < 100; i++)
		ok &= fct_voxgrid_block(g, i, 0, 0, 1, &err) != NULL;
	enum { N = 3000 };
	static unsigned char keep[N];
	int32_t key[N];
	for (int i = 0; i < N; i++) {
		key[i] = (int32_t)((i * 7919) % N) - N / 2;   /* 7919 is prime to 3000 */
		struct fct_voxblock *b = fct_voxgrid_block(g, key[i], key[i], 5, 1, &err);
		ok &= b != NULL;
		keep[i] = i % 3 != 1;
		b->sdf[7] = 1, b->weight[300] = 2, b->rgb[1000] = 3;
	}
	CHECK(ok);
	size_t bytes = fct_voxgrid_bytes(g);
	fct_voxgrid_drop(g, 100, keep);
	CHECK_INT(fct_voxgrid_count(g), 100 + 2000);
	size_t j = 100;
	for (int i = 0; i < N; i++) {
		long idx = fct_voxgrid_index(g, key[i], key[i], 5);
		if (keep[i]) {
			ok &= idx == (long)j && fct_voxgrid_at(g, j)->bx == key[i];
			j++;
		} else {
			ok &= idx == -1 && fct_voxgrid_block(g, key[i], key[i], 5, 0, &err) == NULL;
		}
	}
	for (int32_t i = 0; i < 100; i++)
		ok &= fct_voxgrid_index(g, i, 0, 0) == i;
	CHECK(ok);
	/* 1000 new blocks take the dropped ones' storage, zeroed */
	for (int32_t i = 0; i < 1000; i++) {
		struct fct_voxblock *b = fct_voxgrid_block(g, i, 0, 9, 1, &err);
		ok &= b != NULL && b->bz == 9 && b->rgb != NULL;
		for (int v = 0; v < 512 && b; v++)
			ok &= b->sdf[v] == 0 && b->weight[v] == 0 && b->rgb[3 * v] == 0 &&
			      b->rgb[3 * v + 1] == 0 && b->rgb[3 * v + 2] == 0;
	}
	CHECK(ok);
	CHECK_INT(fct_voxgrid_count(g), 3100);
	CHECK_INT(fct_voxgrid_bytes(g), bytes);
	CHECK_INT(fct_voxgrid_index(g, 999, 0, 9), 3099);
	/* drop all from 3000, then keep all (nothing changes) */
	fct_voxgrid_drop(g, 3000, NULL);
	CHECK_INT(fct_voxgrid_count(g), 3000);
	CHECK_INT(fct_voxgrid_index(g, 999, 0, 9), -1);
	CHECK_INT(fct_voxgrid_index(g, 899, 0, 9), 2999);
	memset(keep, 1, sizeof keep);
	fct_voxgrid_drop(g, 0, keep);
	CHECK_INT(fct_voxgrid_count(g), 3000);
	CHECK_INT(fct_voxgrid_index(g, 899, 0, 9), 2999);
	fct_voxgrid_free(g);
}

int main(void)
{
	test_floor();
	test_blocks();
	test_colour_and_limit();
	test_drop();
	CHECK_DONE();
}

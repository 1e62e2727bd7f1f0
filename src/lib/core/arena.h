/* arena.h - scratch memory freed in one call.
 *
 * A long stage function takes a dozen work arrays; written with malloc,
 * each failure point must free all of them, and the exit path grows a
 * release per array.  Taken from an arena instead, they are freed together
 * by fct_arena_free at the function's single exit, whatever path led there.
 * meshoptimizer's meshopt_Allocator is the model: a list of blocks, each a
 * plain malloc, not a bump allocator, so that ASan still sees every array's
 * bounds and a large array costs no more than malloc's.
 *
 *   struct fct_arena a = {0};
 *   double *d = fct_arena_array(&a, n, sizeof *d, err);
 *   if (!d) goto done;
 *   ...
 * done:
 *   fct_arena_free(&a);
 */
#ifndef FCT_ARENA_H
#define FCT_ARENA_H

#include <stddef.h>

#include "core/err.h"

struct fct_arena {
	void **blocks;
	size_t n, cap;
};

/* n elements of size elem, uninitialised, overflow-checked as
 * fct_alloc_array; NULL with a message in err when out of memory. */
void *fct_arena_array(struct fct_arena *a, size_t n, size_t elem, struct fct_err *err);

/* The same, zeroed. */
void *fct_arena_zeroed(struct fct_arena *a, size_t n, size_t elem, struct fct_err *err);

/* fct_grow for an array taken from a: *ptr (NULL, or a block of a) grows,
 * doubling, to at least need elements.  0, or -1 with a message; *ptr is
 * still a's on failure. */
int fct_arena_grow(struct fct_arena *a, void **ptr, size_t *cap, size_t need, size_t elem,
                   struct fct_err *err);

/* Frees every block of a; a is empty and reusable after.  a may be NULL. */
void fct_arena_free(struct fct_arena *a);

#endif

/* arena.c - scratch memory freed in one call (see arena.h). */
#include "core/arena.h"

#include <stdlib.h>
#include <string.h>

/* Records p as a's block; frees it and fails when the list cannot grow. */
static void *keep(struct fct_arena *a, void *p, struct fct_err *err)
{
	if (!p)
		return NULL;
	if (fct_grow((void **)&a->blocks, &a->cap, a->n + 1, sizeof *a->blocks, err)) {
		free(p);
		return NULL;
	}
	a->blocks[a->n++] = p;
	return p;
}

void *fct_arena_array(struct fct_arena *a, size_t n, size_t elem, struct fct_err *err)
{
	return keep(a, fct_alloc_array(n, elem, err), err);
}

void *fct_arena_zeroed(struct fct_arena *a, size_t n, size_t elem, struct fct_err *err)
{
	void *p = fct_alloc_array(n, elem, err);
	if (p)
		memset(p, 0, (n ? n : 1) * elem);
	return keep(a, p, err);
}

int fct_arena_grow(struct fct_arena *a, void **ptr, size_t *cap, size_t need, size_t elem,
                   struct fct_err *err)
{
	if (*ptr && need <= *cap)
		return 0;
	size_t slot = 0;
	if (*ptr) {
		slot = a->n;
		while (slot > 0 && a->blocks[slot - 1] != *ptr)
			slot--;
		if (!slot)
			return fct_fail(err, "arena: growing an array it does not hold");
	} else {
		*cap = 0;
	}
	void *old = *ptr;
	if (fct_grow(ptr, cap, need, elem, err))
		return -1;
	if (old) {
		a->blocks[slot - 1] = *ptr;
	} else if (!keep(a, *ptr, err)) {
		*ptr = NULL;
		*cap = 0;
		return -1;
	}
	return 0;
}

void fct_arena_free(struct fct_arena *a)
{
	if (!a)
		return;
	while (a->n > 0)
		free(a->blocks[--a->n]);
	free(a->blocks);
	a->blocks = NULL;
	a->cap = 0;
}

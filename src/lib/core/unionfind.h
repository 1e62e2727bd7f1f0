/* unionfind.h - the root of a union-find forest held in one array:
 * parent[x] >= 0 is x's parent and a negative entry marks a root (its
 * users keep minus the set's size there, and join sets their own way). */
#ifndef FCT_UNIONFIND_H
#define FCT_UNIONFIND_H

#include <stdint.h>

/* The root of x's set, halving the path on the way. */
static inline uint32_t fct_uf_root(int32_t *parent, uint32_t x)
{
	while (parent[x] >= 0) {
		int32_t p = parent[x];
		if (parent[p] >= 0)
			parent[x] = parent[p];
		x = (uint32_t)p;
	}
	return x;
}

#endif

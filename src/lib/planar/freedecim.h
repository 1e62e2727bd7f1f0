/* freedecim.h - the planar model's free-form faces decimated piece by
 * piece, each piece remembered across the model's rounds (planemodel.c).
 *
 * The free-form faces of a mesh fall into pieces that share no vertex.
 * Quadric decimation (qem.h) of all of them at once does to each piece
 * exactly what it does to that piece alone, given the same arithmetic
 * centre and the vertices in the same order: no collapse, cost or heap
 * order crosses from one piece to another (the heap's order is a total
 * order on costs and vertex numbers).  The model's rounds change a few
 * pieces at a time (a patch turned free-form, a chain's points kept as
 * corners), so each round decimates only the pieces that changed and takes
 * the others from the round before: the result, faces, vertices and
 * figures, is the whole decimation's bit for bit. */
#ifndef FCT_FREEDECIM_H
#define FCT_FREEDECIM_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"
#include "core/mesh.h"
#include "geom/qem.h"

/* What one round left for the next (zeroed to start; the same mesh every
 * round). */
struct fct_free_cache {
	int valid;
	size_t nv, nf;
	double centre[3];
	size_t nattr;             /* m's float and double scalar vertex properties */
	unsigned char *dead;      /* per vertex: collapsed away */
	double *xyz;              /* per vertex: position after decimation */
	double *attr;             /* per vertex: nattr interpolated values */
	unsigned char *corner;    /* per vertex: the corner flag its piece was decimated with */
	double *in;               /* per vertex: where it was when its piece was decimated */
	int32_t *piece;           /* per face: its piece, or -1 (not free-form) */
	struct fct_free_piece *pieces;
	size_t npieces;
	struct fct_free_tri *tri; /* the surviving triangles, in face order */
	size_t ntri;
};

void fct_free_cache_free(struct fct_free_cache *c);

/* The faces of m with is_free[f] set decimated by fct_qem_decimate with qp
 * (its corner and sigma per vertex of m) as one mesh of m's vertices would
 * be: into F, whose vertices are the survivors (vmap[i] is m's number of
 * F's vertex i, nmap of them) with their positions and m's float and double
 * scalar properties, and whose faces name m's vertices; qs gets the
 * figures.  Pieces unchanged since the last call with c (the same faces,
 * corners and vertex positions) are taken from it. */
int fct_free_decimate(struct fct_mesh *F, uint32_t **vmap, size_t *nmap, const struct fct_mesh *m,
                      const unsigned char *is_free, const struct fct_qem_params *qp,
                      struct fct_free_cache *c, struct fct_qem_stats *qs, struct fct_err *err);

#endif

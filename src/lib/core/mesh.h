/* mesh.h - the indexed polygon mesh that flows between facet's programs.
 *
 * Positions and face connectivity are held in flat arrays the algorithms use
 * directly (double xyz, faces as compressed rows).  Every other property of
 * the vertex and face elements, and every other element of a PLY file, is kept
 * as typed columns in the type it was read, so that a program carries what it
 * does not understand through unchanged.  Header comments (camera, pose,
 * TextureFile, provenance) are kept in order; see header.h for their meaning.
 */
#ifndef FCT_MESH_H
#define FCT_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"

/* The PLY scalar types; 0 means "none". */
enum fct_type {
	FCT_NONE = 0,
	FCT_INT8, FCT_UINT8, FCT_INT16, FCT_UINT16,
	FCT_INT32, FCT_UINT32, FCT_FLOAT32, FCT_FLOAT64
};

/* Size in bytes of one value of type t (0 for FCT_NONE). */
size_t fct_type_size(enum fct_type t);
/* PLY name of t ("char", "uchar", ..., "double"). */
const char *fct_type_name(enum fct_type t);
/* Parse a PLY type name (both "uchar" and "uint8" spellings); FCT_NONE if unknown. */
enum fct_type fct_type_parse(const char *name);

/* One property of an element: a scalar column, or a list column when
 * count_type is not FCT_NONE.  Scalars: data holds `count` values of `type`
 * in native byte order.  Lists: data holds all items of `type` back to back,
 * and off[i]..off[i+1] are the items of row i (off has count+1 entries). */
struct fct_prop {
	char *name;
	enum fct_type type;
	enum fct_type count_type;
	void *data;
	size_t cap;     /* capacity of data, in values */
	size_t *off;
	size_t off_cap; /* capacity of off, in entries */
	/* NULL, or the block that data lies in with other scalar columns' data
	 * (fct_elem_add_scalars_big) instead of being allocated on its own;
	 * the functions below give the column its own copy before it grows. */
	struct fct_block *block;
};

/* A PLY element: a name, a row count and its properties in order. */
struct fct_elem {
	char *name;
	size_t count;
	size_t nprops;
	struct fct_prop *props;
};

/* A header line that travels with the data: "comment ..." or "obj_info ...". */
struct fct_comment {
	int obj_info;   /* 1 for obj_info lines */
	char *text;     /* the text after the keyword and one space */
};

struct fct_mesh {
	/* Vertex positions, 3 per vertex. */
	size_t nv;
	double *xyz;
	size_t xyz_cap;
	enum fct_type xyz_type;       /* on-disk type: FCT_FLOAT32 unless read as double */

	/* Faces as compressed rows: face f has vertices fvert[fstart[f] .. fstart[f+1]). */
	size_t nf;
	uint32_t *fstart;             /* nf + 1 entries, fstart[0] = 0 */
	size_t fstart_cap;
	uint32_t *fvert;
	size_t fvert_cap;
	int has_faces;                /* a face element is written even when nf == 0 */
	enum fct_type fcount_type;    /* on-disk list count type (FCT_UINT8 by default) */
	enum fct_type findex_type;    /* on-disk index type (FCT_INT32 by default) */

	/* The other properties of the vertex and face elements (name and props
	 * used; count is nv / nf). */
	struct fct_elem vertex;
	struct fct_elem face;

	/* Elements other than vertex and face, in file order. */
	size_t nelems;
	struct fct_elem *elems;

	size_t ncomments;
	struct fct_comment *comments;
};

/* An empty mesh (no allocation). */
void fct_mesh_init(struct fct_mesh *m);
/* Free everything the mesh owns and make it empty; m may be NULL. */
void fct_mesh_free(struct fct_mesh *m);

/* Append a vertex / a face; return its index or -1 (out of memory).  A new
 * row of every extra property is zero-filled. */
long fct_mesh_add_vertex(struct fct_mesh *m, double x, double y, double z, struct fct_err *err);
long fct_mesh_add_face(struct fct_mesh *m, const uint32_t *v, size_t n, struct fct_err *err);

/* Bulk construction: make m hold nv vertices (positions uninitialised, new
 * rows of extra properties zeroed) / nf triangles (fvert[3f..3f+2]
 * uninitialised for the caller to fill).  0 or -1. */
int fct_mesh_set_vertex_count(struct fct_mesh *m, size_t nv, struct fct_err *err);
int fct_mesh_set_triangle_count(struct fct_mesh *m, size_t nf, struct fct_err *err);
/* Both, for a mesh that is then written whole once (a depth map's grid
 * mesh): xyz, fstart and fvert not allocated yet are taken from
 * fct_alloc_big. */
int fct_mesh_set_counts_big(struct fct_mesh *m, size_t nv, size_t nf, struct fct_err *err);

/* Number of vertices of face f. */
static inline uint32_t fct_face_size(const struct fct_mesh *m, size_t f)
{
	return m->fstart[f + 1] - m->fstart[f];
}

/* Properties -------------------------------------------------------------- */

/* The property called name in e, or NULL. */
struct fct_prop *fct_elem_find(const struct fct_elem *e, const char *name);
/* The element called name among m's other elements, or NULL. */
struct fct_elem *fct_mesh_find_elem(const struct fct_mesh *m, const char *name);

/* Adding a property may move e->props: pointers to e's properties taken
 * before it are stale afterwards; look them up again (fct_elem_find).
 *
 * Add a zero-filled scalar column of type t to e (which has e->count rows);
 * an existing column of that name is returned as it is if its type is t and
 * replaced otherwise.  Returns the column or NULL. */
struct fct_prop *fct_elem_add_scalar(struct fct_elem *e, const char *name,
                                     enum fct_type t, struct fct_err *err);
/* New columns that are then written whole once: n zero-filled scalar
 * columns of type t called names[0..n) added to e, their data one after
 * the other in one block from fct_alloc_big (a 640x480 depth map's
 * vertices' s, t and sigma floats fill two 2 MB pages together, three
 * apart).  Columns of those names are replaced.  0, or -1 (out of memory:
 * none of them added, e as it was unless a name could not be copied). */
int fct_elem_add_scalars_big(struct fct_elem *e, const char *const *names, size_t n, enum fct_type t,
                             struct fct_err *err);
/* Add a list column to the faces of m with per_corner zeroed values of type
 * t for each corner of each face, in the face's vertex order (list uchar,
 * as MeshLab's per-wedge "texcoord", 2 per corner; the PLY writer widens
 * the count type when a face has too many corners for uchar); an existing
 * property of that name is replaced.  Returns the column or NULL. */
struct fct_prop *fct_mesh_add_corner_list(struct fct_mesh *m, const char *name, enum fct_type t,
                                          unsigned per_corner, struct fct_err *err);
/* Add a new element with no properties and count rows, after the others. */
struct fct_elem *fct_mesh_add_elem(struct fct_mesh *m, const char *name, size_t count,
                                   struct fct_err *err);
/* Remove the property / element of that name if present. */
void fct_elem_remove(struct fct_elem *e, const char *name);
void fct_mesh_remove_elem(struct fct_mesh *m, const char *name);

/* Scalar value i of p as a double / set from a double (rounded to p's type,
 * integers saturated). */
double fct_prop_get(const struct fct_prop *p, size_t i);
void fct_prop_set(struct fct_prop *p, size_t i, double v);

/* Resize every column of e to count rows (new rows zeroed, lists empty). */
int fct_elem_resize(struct fct_elem *e, size_t count, struct fct_err *err);

/* Keep rows src[0..n) of e, in that order (src entries < e->count, may repeat). */
int fct_elem_gather(struct fct_elem *e, const size_t *src, size_t n, struct fct_err *err);

/* Keep the vertices src[0..n) in that order, with all their properties; faces
 * are renumbered and a face that uses a dropped vertex is dropped. */
int fct_mesh_gather_vertices(struct fct_mesh *m, const size_t *src, size_t n, struct fct_err *err);
/* Keep the faces src[0..n) in that order, with all their properties. */
int fct_mesh_gather_faces(struct fct_mesh *m, const size_t *src, size_t n, struct fct_err *err);

/* Append src's vertices and faces to dst, src's face indices shifted past
 * dst's vertices.  The vertex elements must have the same properties (names,
 * types, list or scalar, in order), and so must the face elements; the
 * positions are stored as double on disk when either mesh had them so.
 * src's other elements and comments are not taken.  Returns 0, or -1 with
 * the first difference named (dst then unchanged) or when out of memory or
 * past 2^32 - 1 vertices. */
int fct_mesh_append(struct fct_mesh *dst, const struct fct_mesh *src, struct fct_err *err);

/* Positions far from the origin (a georeferenced pose: float rounds
 * coordinates of 4000 km to 0.25 m) stored as double on disk: m->xyz_type
 * becomes FCT_FLOAT64 when float would move some coordinate by more than
 * resolution (> 0).  Returns 1 when it did, 0 when float holds them. */
int fct_mesh_keep_precision(struct fct_mesh *m, double resolution);

/* Deep copy of src into dst (dst is overwritten without being freed). */
int fct_mesh_copy(struct fct_mesh *dst, const struct fct_mesh *src, struct fct_err *err);

/* Comments ---------------------------------------------------------------- */

/* Append a comment (obj_info = 0) or obj_info line; text must hold no newline. */
int fct_mesh_add_comment(struct fct_mesh *m, const char *text, int obj_info, struct fct_err *err);

#endif

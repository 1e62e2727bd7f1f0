/* obj.c - Wavefront OBJ reader and writer (see obj.h).
 *
 * The reader is one pass over the lines: positions, texture coordinates and
 * normals go to flat arrays of their own, each face corner keeps its
 * position as its vertex and its vt / vn in per-corner arrays, and the
 * mesh's columns are filled once at the end: vertex columns when every
 * corner of each position agrees, per-corner face lists otherwise.
 * Numbers go through fct_parse_double; indices are parsed by hand, since a
 * triangle mesh file is mostly indices. */
#include "io/obj.h"

#include "io/header.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/numparse.h"
#include "core/path.h"
#include "io/texcoord.h"

/* A corner's vt or vn is stored as index + 1, 0 meaning "none"; a position
 * not yet used by a face has UNUSED as its first vt. */
#define UNUSED UINT32_MAX
#define MAX_COUNT (UINT32_MAX - 1)

static inline int is_blank(char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

static inline int is_end(char c)
{
	return c == 0 || is_blank(c);
}

static inline int is_digit(char c)
{
	return (unsigned)(c - '0') < 10;
}

static inline const char *skip_blanks(const char *p)
{
	while (is_blank(*p))
		p++;
	return p;
}

/* Does line start with keyword kw followed by a blank or the end? */
static int is_keyword(const char *line, const char *kw, size_t n)
{
	return !strncmp(line, kw, n) && is_end(line[n]);
}

/* String -> index hash map -------------------------------------------------
 * Keys point to strings owned elsewhere (material names, texture paths);
 * used so that hostile files with many materials stay linear. */

struct strmap {
	struct strmap_slot {
		const char *key;
		size_t val;
	} *slot;
	size_t n, cap;
};

static uint64_t str_hash(const char *s)
{
	uint64_t h = UINT64_C(14695981039346656037);
	for (; *s; s++)
		h = (h ^ (unsigned char)*s) * UINT64_C(1099511628211);
	return h;
}

/* The value of key, or -1. */
static long strmap_get(const struct strmap *t, const char *key)
{
	if (!t->cap)
		return -1;
	for (size_t i = str_hash(key) & (t->cap - 1);; i = (i + 1) & (t->cap - 1)) {
		if (!t->slot[i].key)
			return -1;
		if (!strcmp(t->slot[i].key, key))
			return (long)t->slot[i].val;
	}
}

static void strmap_insert(struct strmap *t, const char *key, size_t val)
{
	size_t i = str_hash(key) & (t->cap - 1);
	while (t->slot[i].key)
		i = (i + 1) & (t->cap - 1);
	t->slot[i].key = key;
	t->slot[i].val = val;
	t->n++;
}

/* Add key (not present) with value val. */
static int strmap_put(struct strmap *t, const char *key, size_t val, struct fct_err *err)
{
	if (2 * (t->n + 1) > t->cap) {
		size_t ncap = t->cap ? 2 * t->cap : 16;
		struct strmap_slot *old = t->slot;
		size_t ocap = t->cap;
		if (!(t->slot = calloc(ncap, sizeof *t->slot))) {
			t->slot = old;
			return fct_fail(err, "out of memory");
		}
		t->cap = ncap;
		t->n = 0;
		for (size_t i = 0; i < ocap; i++)
			if (old[i].key)
				strmap_insert(t, old[i].key, old[i].val);
		free(old);
	}
	strmap_insert(t, key, val);
	return 0;
}

/* Reader ----------------------------------------------------------------- */

struct material {
	char *name;
	char *map;      /* map_Kd path relative to the current folder, or NULL */
	long tex;       /* TextureFile index; -1 untextured; -2 not yet used by a face */
};

struct obj {
	struct fct_mesh *m;
	struct fct_reader *r;
	struct fct_err *err;
	const char *dir;
	uint64_t line;          /* first line of the statement being parsed */

	double *pos;            /* 3 per position; the mesh's xyz in the end */
	size_t npos, pos_cap;
	unsigned char *rgb;     /* 3 per position once a coloured v is seen */
	size_t rgb_cap;
	float *vt, *vn;         /* 2 per vt, 3 per vn */
	size_t nvt, vt_cap, nvn, vn_cap;
	int xyz_double;         /* a coordinate has more digits than a float holds */

	uint32_t *first;        /* per position: vt+1, vn+1 of its first use by a face */
	size_t nfirst, first_cap;
	uint32_t *ct, *cn;      /* per face corner: vt+1, vn+1 (NULL while all are 0) */
	size_t ct_cap, cn_cap;
	int corner_vt, corner_vn;  /* some corner refers to a vt / a vn */
	int split_vt, split_vn;    /* some position's corners refer to different ones */

	int32_t *ftex;          /* per face TextureFile index, once one is textured */
	size_t ftex_cap;

	struct material *mat;
	size_t nmat, mat_cap;
	struct strmap mat_by_name;
	long cur_mat;
	long cur_tex;           /* texture of cur_mat; -2 until a face needs it */
	char **tex;             /* TextureFile paths in comment order (owned) */
	size_t ntex, tex_cap;
	struct strmap tex_by_path;
	char **mtllibs;         /* material libraries already read */
	size_t nmtllibs, mtllibs_cap;
	struct strmap mtllib_seen;

	char *joined;           /* a statement continued over several lines */
	size_t joined_cap;
	const char *end;        /* where v, vt, vn and f parsing stopped: at the
	                           line's end unless the line holds a NUL byte */
};

static int fail_at(struct obj *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* "FILE:LINE: what" for the statement being parsed. */
static int fail_at(struct obj *o, const char *fmt, ...)
{
	char what[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(what, sizeof what, fmt, ap);
	va_end(ap);
	return fct_fail(o->err, "%s:%" PRIu64 ": %s", o->r->name, o->line, what);
}

static int fail_no_vertex(struct obj *o)
{
	return fct_fail(o->err, "%s: not a PLY or OBJ file (no vertex)", o->r->name);
}

/* Binary junk: before any vertex the input is not OBJ at all. */
static int fail_binary(struct obj *o)
{
	if (!o->npos)
		return fail_no_vertex(o);
	return fail_at(o, "binary data in a text file");
}

/* The next statement with continuation lines ("\" at the end) joined, or
 * NULL at the end of input (o->err->msg empty) or on error. */
static char *next_statement(struct obj *o, size_t *len)
{
	char *line = fct_reader_line(o->r, len, o->err);
	if (!line)
		return NULL;
	o->line = o->r->line;
	if (o->line == 1 && *len >= 3 && !memcmp(line, "\xEF\xBB\xBF", 3))
		line += 3, *len -= 3;
	/* A comment ends at its line even with a "\\" there: a Windows path in a
	 * provenance comment must not swallow the next statement. */
	if (!*len || line[*len - 1] != '\\' || *skip_blanks(line) == '#')
		return line;
	size_t n = 0;
	for (;;) {
		/* The backslash becomes a blank, the next line follows. */
		if (fct_grow((void **)&o->joined, &o->joined_cap, n + *len + 1, 1, o->err))
			return NULL;
		memcpy(o->joined + n, line, *len);
		n += *len;
		int more = n && o->joined[n - 1] == '\\';
		if (more)
			o->joined[n - 1] = ' ';
		o->joined[n] = 0;
		if (!more || !(line = fct_reader_line(o->r, len, o->err)))
			break;
		if (strlen(line) != *len) {
			fail_binary(o);
			return NULL;
		}
	}
	if (o->err->msg[0])
		return NULL;
	*len = n;
	return o->joined;
}

/* Significant digits of the number text [s, e), trailing zeros left out. */
static int significant_digits(const char *s, const char *e)
{
	int n = 0, zeros = 0, started = 0;
	for (; s < e && *s != 'e' && *s != 'E'; s++) {
		if (!is_digit(*s))
			continue;
		if (*s == '0') {
			zeros += started;
			continue;
		}
		started = 1;
		n += zeros + 1;
		zeros = 0;
	}
	return n;
}

/* Parse up to max numbers after a keyword into v; *count gets how many were
 * there (all of them, even past max). */
static int parse_numbers(struct obj *o, const char *p, const char *kw, double *v, int max,
                         int *count, int check_digits)
{
	int n = 0;
	for (;;) {
		p = skip_blanks(p);
		if (!*p)
			break;
		double d;
		const char *e = fct_parse_double(p, &d);
		if (!e || !is_end(*e)) {
			const char *w = p;
			while (!is_end(*w))
				w++;
			return fail_at(o, "%s: \"%.*s\" is not a number", kw, (int)(w - p > 40 ? 40 : w - p), p);
		}
		if (n < max) {
			v[n] = d;
			if (check_digits && n < 3 && e - p > 10 && significant_digits(p, e) > 9)
				o->xyz_double = 1;
		}
		n++;
		p = e;
	}
	*count = n;
	o->end = p;
	return 0;
}

static int parse_v(struct obj *o, const char *p)
{
	double c[6];
	int n;
	if (parse_numbers(o, p, "v", c, 6, &n, 1))
		return -1;
	if (n != 3 && n != 4 && n != 6)
		return fail_at(o, "v: expected 3, 4 or 6 numbers, got %d", n);
	for (int k = 0; k < n; k++)
		if (!isfinite(c[k]))
			return fail_at(o, "v: %s is not a finite number", k < 3 ? "coordinate" : "colour");
	for (int k = 0; k < 3; k++)
		if (isinf((float)c[k]))
			o->xyz_double = 1;  /* finite, but not as a float */
	if (o->npos >= MAX_COUNT)
		return fail_at(o, "too many vertices");
	if (fct_grow((void **)&o->pos, &o->pos_cap, 3 * (o->npos + 1), sizeof *o->pos, o->err))
		return -1;
	double *d = o->pos + 3 * o->npos;
	d[0] = c[0], d[1] = c[1], d[2] = c[2];
	if (n == 6 || o->rgb) {
		size_t had = o->rgb ? o->rgb_cap : 0;
		if (fct_grow((void **)&o->rgb, &o->rgb_cap, 3 * (o->npos + 1), 1, o->err))
			return -1;
		/* Vertices without a colour are black, as a new mesh row is zero. */
		memset(o->rgb + had, 0, o->rgb_cap - had);
		for (int k = 0; k < 3 && n == 6; k++) {
			double x = nearbyint(c[3 + k] * 255);
			o->rgb[3 * o->npos + (size_t)k] = (unsigned char)(x < 0 ? 0 : x > 255 ? 255 : x);
		}
	}
	o->npos++;
	return 0;
}

static int parse_vt(struct obj *o, const char *p)
{
	double c[2] = {0, 0};
	int n;
	if (parse_numbers(o, p, "vt", c, 2, &n, 0))
		return -1;
	if (n < 1 || n > 3)
		return fail_at(o, "vt: expected 1 to 3 numbers, got %d", n);
	if (o->nvt >= MAX_COUNT)
		return fail_at(o, "too many texture coordinates");
	if (fct_grow((void **)&o->vt, &o->vt_cap, 2 * (o->nvt + 1), sizeof *o->vt, o->err))
		return -1;
	o->vt[2 * o->nvt] = (float)c[0];
	o->vt[2 * o->nvt + 1] = (float)c[1];
	o->nvt++;
	return 0;
}

static int parse_vn(struct obj *o, const char *p)
{
	double c[3];
	int n;
	if (parse_numbers(o, p, "vn", c, 3, &n, 0))
		return -1;
	if (n != 3)
		return fail_at(o, "vn: expected 3 numbers, got %d", n);
	if (o->nvn >= MAX_COUNT)
		return fail_at(o, "too many normals");
	if (fct_grow((void **)&o->vn, &o->vn_cap, 3 * (o->nvn + 1), sizeof *o->vn, o->err))
		return -1;
	for (int k = 0; k < 3; k++)
		o->vn[3 * o->nvn + (size_t)k] = (float)c[k];
	o->nvn++;
	return 0;
}

/* "face: "1/x/2" is not a vertex reference" for the corner at c. */
static int bad_corner(struct obj *o, const char *c)
{
	const char *e = c;
	while (!is_end(*e))
		e++;
	return fail_at(o, "face: \"%.*s\" is not a vertex reference", (int)(e - c > 40 ? 40 : e - c), c);
}

/* Parse an OBJ index (1-based, or negative: relative to the count so far)
 * at p and turn it into a 0-based index below count.  Returns the end of the
 * number, or NULL with a message naming `what`. */
static const char *parse_index(struct obj *o, const char *p, size_t count, const char *what,
                               const char *plural, const char *corner, uint32_t *out)
{
	const char *s = p;
	int neg = *p == '-';
	if (*p == '-' || *p == '+')
		p++;
	if (!is_digit(*p)) {
		bad_corner(o, corner);
		return NULL;
	}
	uint64_t v = 0;
	for (; is_digit(*p); p++)
		if (v <= UINT64_C(0xffffffffff))  /* far past any count; saturates */
			v = v * 10 + (uint64_t)(*p - '0');
	if (v == 0 || v > count) {
		fail_at(o, "face: %s index %.*s out of range (%zu %s)", what, (int)(p - s > 40 ? 40 : p - s), s,
		        count, plural);
		return NULL;
	}
	*out = (uint32_t)(neg ? count - v : v - 1);
	return p;
}

/* The common case of parse_index, inline: a positive index of at most 9
 * digits, in range; NULL for anything else (parse_index then decides). */
static inline const char *fast_index(const char *p, size_t count, uint32_t *out)
{
	const char *s = p;
	uint32_t v = 0;
	while (is_digit(*p) && p - s < 9)
		v = v * 10 + (uint32_t)(*p++ - '0');
	if (p == s || is_digit(*p) || v == 0 || v > count)
		return NULL;
	*out = v - 1;
	return p;
}

/* Set entry i of a per-corner array to v, growing it (new entries 0). */
static int corner_store(struct obj *o, uint32_t **a, size_t *cap, size_t i, uint32_t v)
{
	if (i >= *cap) {
		size_t had = *cap;
		if (fct_grow((void **)a, cap, i + 1, sizeof **a, o->err))
			return -1;
		memset(*a + had, 0, (*cap - had) * sizeof **a);
	}
	(*a)[i] = v;
	return 0;
}

/* Corner i of the faces uses position p with vt+1 t and vn+1 n.  The
 * position stays the corner's vertex whatever t and n are (splitting it
 * would disconnect the mesh); a pair that differs from the position's first
 * one makes vt or vn per-corner. */
static inline int note_corner(struct obj *o, uint32_t p, uint32_t t, uint32_t n, size_t i)
{
	if (p >= o->nfirst) {
		if (fct_grow((void **)&o->first, &o->first_cap, 2 * o->npos, sizeof *o->first, o->err))
			return -1;
		memset(o->first + 2 * o->nfirst, 0xff, 2 * (o->npos - o->nfirst) * sizeof *o->first);
		o->nfirst = o->npos;
	}
	uint32_t *f = o->first + 2 * (size_t)p;
	if (f[0] == UNUSED) {
		f[0] = t, f[1] = n;
	} else {
		o->split_vt |= f[0] != t;
		o->split_vn |= f[1] != n;
	}
	if ((t || o->ct) && corner_store(o, &o->ct, &o->ct_cap, i, t))
		return -1;
	if ((n || o->cn) && corner_store(o, &o->cn, &o->cn_cap, i, n))
		return -1;
	return 0;
}

/* Append path to the TextureFile list (whose order is that of the mesh's
 * TextureFile comments); returns its index. */
static long add_texture(struct obj *o, const char *path)
{
	if (fct_grow((void **)&o->tex, &o->tex_cap, o->ntex + 1, sizeof *o->tex, o->err))
		return -1;
	if (!(o->tex[o->ntex] = fct_strdup(path, o->err)))
		return -1;
	o->ntex++;
	if (strmap_get(&o->tex_by_path, path) < 0 &&
	    strmap_put(&o->tex_by_path, o->tex[o->ntex - 1], o->ntex - 1, o->err))
		return -1;
	return (long)o->ntex - 1;
}

/* Add "comment TextureFile path". */
static int add_texture_comment(struct obj *o, const char *path)
{
	size_t n = strlen(path) + 16;
	char *c = malloc(n);
	if (!c)
		return fct_fail(o->err, "out of memory");
	snprintf(c, n, "TextureFile %s", path);
	int rc = fct_mesh_add_comment(o->m, c, 0, o->err);
	free(c);
	return rc;
}

/* TextureFile index of a material's texture path: the first TextureFile of
 * that path (so a file facet wrote, which has both the comment and the
 * material, keeps one), or a new one. */
static long material_texture(struct obj *o, const char *path)
{
	long at = strmap_get(&o->tex_by_path, path);
	if (at >= 0)
		return at;
	if ((at = add_texture(o, path)) < 0 || add_texture_comment(o, path))
		return -1;
	return at;
}

/* TextureFile index of the current material (-1 untextured). */
static long current_texture(struct obj *o)
{
	if (o->cur_tex != -2)
		return o->cur_tex;
	o->cur_tex = -1;
	if (o->cur_mat >= 0) {
		struct material *mt = &o->mat[o->cur_mat];
		if (mt->tex == -2)
			mt->tex = mt->map ? material_texture(o, mt->map) : -1;
		if (mt->map && mt->tex < 0)
			return -3;  /* out of memory */
		o->cur_tex = mt->tex;
	}
	return o->cur_tex;
}

static int parse_f(struct obj *o, const char *p)
{
	struct fct_mesh *m = o->m;
	size_t base = m->nf ? m->fstart[m->nf] : 0, k = 0;
	for (;; k++) {
		p = skip_blanks(p);
		if (!*p)
			break;
		uint32_t v, t = 0, n = 0;
		const char *corner = p, *q = fast_index(p, o->npos, &v);
		if (!(p = q ? q : parse_index(o, p, o->npos, "vertex", "vertices", corner, &v)))
			return -1;
		if (*p == '/') {
			p++;
			if (*p != '/' && !is_end(*p)) {
				q = fast_index(p, o->nvt, &t);
				if (!(p = q ? q : parse_index(o, p, o->nvt, "texture coordinate", "texture coordinates", corner, &t)))
					return -1;
				t++;
				o->corner_vt = 1;
			}
			if (*p == '/') {
				p++;
				if (!is_end(*p)) {
					q = fast_index(p, o->nvn, &n);
					if (!(p = q ? q : parse_index(o, p, o->nvn, "normal", "normals", corner, &n)))
						return -1;
					n++;
					o->corner_vn = 1;
				}
			}
		}
		if (!is_end(*p))
			return bad_corner(o, corner);
		if (base + k >= UINT32_MAX)
			return fail_at(o, "too many face vertices in all");
		if (base + k >= m->fvert_cap &&
		    fct_grow((void **)&m->fvert, &m->fvert_cap, base + k + 1, sizeof *m->fvert, o->err))
			return -1;
		if (note_corner(o, v, t, n, base + k))
			return -1;
		m->fvert[base + k] = v;
	}
	o->end = p;
	if (k < 3)
		return fail_at(o, "face: a face needs 3 or more vertices, got %zu", k);
	if (fct_grow((void **)&m->fstart, &m->fstart_cap, m->nf + 2, sizeof *m->fstart, o->err))
		return -1;
	m->fstart[0] = 0;
	m->fstart[m->nf + 1] = (uint32_t)(base + k);
	long tex = current_texture(o);
	if (tex == -3)
		return -1;
	if (tex >= 0 || o->ftex) {
		size_t had = o->ftex ? o->ftex_cap : 0;
		if (fct_grow((void **)&o->ftex, &o->ftex_cap, m->nf + 1, sizeof *o->ftex, o->err))
			return -1;
		for (size_t i = had; i < o->ftex_cap; i++)
			o->ftex[i] = -1;
		o->ftex[m->nf] = (int32_t)tex;
	}
	m->nf++;
	return 0;
}

/* The rest of a statement after its keyword, trimmed, in place. */
static char *rest_of(char *s, size_t kwlen)
{
	char *p = (char *)skip_blanks(s + kwlen);
	size_t n = strlen(p);
	while (n && is_blank(p[n - 1]))
		p[--n] = 0;
	return p;
}

static void to_slashes(char *s)
{
	for (; *s; s++)
		if (*s == '\\')
			*s = '/';
}

/* The material called name, made when new. */
static long material(struct obj *o, const char *name)
{
	long at = strmap_get(&o->mat_by_name, name);
	if (at >= 0)
		return at;
	if (fct_grow((void **)&o->mat, &o->mat_cap, o->nmat + 1, sizeof *o->mat, o->err))
		return -1;
	struct material *mt = &o->mat[o->nmat];
	mt->map = NULL;
	mt->tex = -2;
	if (!(mt->name = fct_strdup(name, o->err)))
		return -1;
	o->nmat++;
	if (strmap_put(&o->mat_by_name, mt->name, o->nmat - 1, o->err))
		return -1;
	return (long)o->nmat - 1;
}

/* Read the material library at path (relative to the current folder): the
 * newmtl names and their map_Kd textures.  A library that cannot be opened
 * or read is skipped, since textures are optional; returns 1 read, 0
 * skipped, -1 out of memory. */
static int read_mtl(struct obj *o, const char *path)
{
	struct stat st;
	if (stat(path, &st) || !S_ISREG(st.st_mode))
		return 0;  /* never block on a FIFO or read a device forever */
	FILE *f = fopen(path, "rb");
	if (!f)
		return 0;
	struct fct_reader r;
	struct fct_err e;
	char *mdir = fct_path_dir(path, o->err);
	if (!mdir || fct_reader_init(&r, f, path, &e)) {
		free(mdir);
		fclose(f);
		return mdir ? 0 : -1;
	}
	long cur = -1;
	int rc = 1;
	size_t len;
	char *line;
	while ((line = fct_reader_line(&r, &len, &e))) {
		if (strlen(line) != len)
			break;  /* binary: not a material library (and maybe endless) */
		if (r.line == 1 && len >= 3 && !memcmp(line, "\xEF\xBB\xBF", 3))
			line += 3;
		line = (char *)skip_blanks(line);
		if (is_keyword(line, "newmtl", 6)) {
			char *name = rest_of(line, 6);
			if ((cur = material(o, name)) < 0) {
				rc = -1;
				break;
			}
		} else if (cur >= 0 && !strncasecmp(line, "map_Kd", 6) && is_end(line[6])) {
			/* Options (-s 1 1 1, -clamp on, ...) come first: the path is the last word. */
			char *p = rest_of(line, 6), *w = p + strlen(p);
			while (w > p && !is_blank(w[-1]))
				w--;
			if (!*w)
				continue;
			to_slashes(w);
			char *tex = fct_path_join(mdir, w, o->err);
			if (!tex) {
				rc = -1;
				break;
			}
			free(o->mat[cur].map);
			o->mat[cur].map = tex;
		}
	}
	fct_reader_free(&r);
	fclose(f);
	free(mdir);
	return rc;
}

/* mtllib: each library once; a name with blanks is tried whole first. */
static int parse_mtllib(struct obj *o, char *s)
{
	char *names = rest_of(s, 6);
	to_slashes(names);
	for (int whole = 1; whole >= 0; whole--) {
		char *p = names;
		while (*p) {
			char *w = (char *)skip_blanks(p), *e = w;
			if (!*w)
				break;
			if (whole)
				e = w + strlen(w);
			else
				while (*e && !is_blank(*e))
					e++;
			char save = *e;
			*e = 0;
			char *path = fct_path_join(o->dir, w, o->err);
			*e = save;
			if (!path)
				return -1;
			if (strmap_get(&o->mtllib_seen, path) >= 0) {
				free(path);
				if (whole)
					return 0;
				p = e;
				continue;
			}
			int got = read_mtl(o, path);
			if (got < 0 ||
			    fct_grow((void **)&o->mtllibs, &o->mtllibs_cap, o->nmtllibs + 1, sizeof *o->mtllibs, o->err)) {
				free(path);
				return -1;
			}
			o->mtllibs[o->nmtllibs++] = path;
			if (strmap_put(&o->mtllib_seen, path, 0, o->err))
				return -1;
			if (whole && (got || !strpbrk(names, " \t")))
				return 0;
			p = e;
		}
	}
	return 0;
}

static int parse_usemtl(struct obj *o, char *s)
{
	char *name = rest_of(s, 6);
	o->cur_mat = *name ? strmap_get(&o->mat_by_name, name) : -1;
	o->cur_tex = -2;
	return 0;
}

/* "# comment TEXT" and "# obj_info TEXT" carry a PLY header's lines; other
 * comments are only comments. */
static int parse_comment(struct obj *o, const char *s)
{
	const char *p = skip_blanks(s + 1);
	int info;
	if (is_keyword(p, "comment", 7))
		info = 0, p += 7;
	else if (is_keyword(p, "obj_info", 8))
		info = 1, p += 8;
	else
		return 0;
	if (*p)
		p++;  /* the one blank after the keyword, as in PLY */
	if (!info && !strncmp(p, "TextureFile", 11) && (p[11] == ' ' || p[11] == '\t' || !p[11])) {
		/* Kept where it is (as header.c finds it), its path made relative to
		 * the current folder. */
		const char *t = p + 11;
		while (*t == ' ' || *t == '\t')
			t++;
		char *path = *t ? fct_path_join(o->dir, t, o->err) : fct_strdup(t, o->err);
		int rc = path && !add_texture_comment(o, path) && add_texture(o, path) >= 0 ? 0 : -1;
		free(path);
		return rc;
	}
	return fct_mesh_add_comment(o->m, p, info, o->err);
}

/* An unknown statement is ignored, but a keyword that is not printable
 * ASCII means binary data. */
static int check_keyword(struct obj *o, const char *s)
{
	for (; !is_end(*s); s++)
		if ((unsigned char)*s <= ' ' || (unsigned char)*s >= 0x7f)
			return fail_binary(o);
	return 0;
}

/* Parse the statement s of len bytes.  The number parsers stop at the
 * first NUL, which must be the line's end; other statements check with
 * strlen, since they are rare. */
static int statement(struct obj *o, char *s, size_t len)
{
	const char *eol = s + len;
	s = (char *)skip_blanks(s);
	int rc;
	switch (s[0]) {
	case 'v':
		if (is_end(s[1]))
			rc = parse_v(o, s + 1);
		else if (s[1] == 't' && is_end(s[2]))
			rc = parse_vt(o, s + 2);
		else if (s[1] == 'n' && is_end(s[2]))
			rc = parse_vn(o, s + 2);
		else
			goto other;
		break;
	case 'f':
		if (!is_end(s[1]))
			goto other;
		rc = parse_f(o, s + 1);
		break;
	default:
		goto other;
	}
	/* A NUL byte explains a parse error better than the error itself. */
	if (rc ? s + strlen(s) != eol : o->end != eol)
		return fail_binary(o);
	return rc;
other:
	if (s + strlen(s) != eol)
		return fail_binary(o);
	switch (s[0]) {
	case 0:
		return 0;
	case '#':
		return parse_comment(o, s);
	case 'u':
		if (is_keyword(s, "usemtl", 6))
			return parse_usemtl(o, s);
		break;
	case 'm':
		if (is_keyword(s, "mtllib", 6))
			return parse_mtllib(o, s);
		break;
	}
	return check_keyword(o, s);
}

/* Fill the vertex columns: a position takes the vt / vn of the faces that
 * use it when, for every position, they all agree (else the faces carry them
 * per corner: build_corner_lists).  A position no face uses takes the vt /
 * vn of its own index when there are as many as positions (the
 * matching-index files facet writes); a file whose faces name no vn at all
 * but has one per position (point clouds, some scanners) gets them by
 * index. */
static int build_vertex_columns(struct obj *o)
{
	struct fct_mesh *m = o->m;
	size_t nv = m->nv;
	int by_index_vn = !o->corner_vn && o->nvn == o->npos;
	int by_index_vt = !o->corner_vt && o->nvt == o->npos;
	int want_vn = o->nvn && !o->split_vn && (o->corner_vn || by_index_vn);
	int want_vt = o->nvt && !o->split_vt && (o->corner_vt || by_index_vt);
	struct fct_prop *c[8] = {0};
	static const char *names[8] = {"nx", "ny", "nz", "s", "t", "red", "green", "blue"};
	for (int k = 0; k < 8; k++) {
		int want = k < 3 ? want_vn : k < 5 ? want_vt : o->rgb != NULL;
		if (want && !fct_elem_add_scalar(&m->vertex, names[k], k < 5 ? FCT_FLOAT32 : FCT_UINT8, o->err))
			return -1;
	}
	/* Only now: adding a column moves the others. */
	for (int k = 0; k < 8; k++)
		c[k] = fct_elem_find(&m->vertex, names[k]);
	for (size_t j = 0; j < nv; j++) {
		uint32_t t = j < o->nfirst ? o->first[2 * j] : UNUSED;
		uint32_t n = j < o->nfirst ? o->first[2 * j + 1] : 0;
		if (want_vn) {
			const float *src = NULL;
			if (by_index_vn || (t == UNUSED && o->nvn == o->npos))
				src = o->vn + 3 * j;
			else if (n && t != UNUSED)
				src = o->vn + 3 * (size_t)(n - 1);
			for (int k = 0; k < 3 && src; k++)
				((float *)c[k]->data)[j] = src[k];
		}
		if (want_vt) {
			const float *src = NULL;
			if (by_index_vt || (t == UNUSED && o->nvt == o->npos))
				src = o->vt + 2 * j;
			else if (t && t != UNUSED)
				src = o->vt + 2 * (size_t)(t - 1);
			for (int k = 0; k < 2 && src; k++)
				((float *)c[3 + k]->data)[j] = src[k];
		}
		if (o->rgb)
			for (int k = 0; k < 3; k++)
				((unsigned char *)c[5 + k]->data)[j] = o->rgb[3 * j + (size_t)k];
	}
	return 0;
}

/* A face list column name of dim floats per corner from the corners'
 * indices idx (index + 1 into src; 0, a corner without one: zeros). */
static int corner_list(struct obj *o, const char *name, unsigned dim, const uint32_t *idx,
                       const float *src)
{
	struct fct_mesh *m = o->m;
	struct fct_prop *p = fct_mesh_add_corner_list(m, name, FCT_FLOAT32, dim, o->err);
	if (!p)
		return -1;
	float *d = p->data;
	for (size_t i = 0; i < m->fstart[m->nf]; i++)
		if (idx[i])
			memcpy(d + dim * i, src + dim * (size_t)(idx[i] - 1), dim * sizeof *d);
	return 0;
}

/* The faces' own texture coordinates and normals where the corners of some
 * position disagree: MeshLab's per-wedge "texcoord" (2 per corner) and
 * "corner_normal" (3 per corner). */
static int build_corner_lists(struct obj *o)
{
	if (o->split_vt && corner_list(o, "texcoord", 2, o->ct, o->vt))
		return -1;
	if (o->split_vn && corner_list(o, "corner_normal", 3, o->cn, o->vn))
		return -1;
	return 0;
}

/* texnumber (MeshLab's face property) when one texture index for all faces
 * would not say which texture a face shows: some face is textured and some
 * face is not on texture 0. */
static int build_texnumber(struct obj *o)
{
	struct fct_mesh *m = o->m;
	if (!o->ftex)
		return 0;
	int textured = 0, not_first = 0;
	for (size_t f = 0; f < m->nf; f++) {
		textured |= o->ftex[f] >= 0;
		not_first |= o->ftex[f] != 0;
	}
	if (!textured || !not_first)
		return 0;
	struct fct_prop *p = fct_elem_add_scalar(&m->face, "texnumber", FCT_INT32, o->err);
	if (!p)
		return -1;
	memcpy(p->data, o->ftex, m->nf * sizeof *o->ftex);
	return 0;
}

/* Hand the arrays over to the mesh and fill its columns. */
static int finish(struct obj *o)
{
	struct fct_mesh *m = o->m;
	if (!o->npos)
		return fail_no_vertex(o);
	size_t nv = o->npos;
	if (o->xyz_double) {
		m->xyz_type = FCT_FLOAT64;
	} else {
		/* Float on disk (DESIGN.md): hold what a float PLY would hold. */
		for (size_t i = 0; i < 3 * nv; i++)
			o->pos[i] = (float)o->pos[i];
	}
	m->xyz = o->pos, m->xyz_cap = o->pos_cap, m->nv = nv;
	o->pos = NULL;
	m->vertex.count = nv;
	if (fct_grow((void **)&m->fstart, &m->fstart_cap, m->nf + 1, sizeof *m->fstart, o->err))
		return -1;
	m->fstart[0] = 0;
	m->face.count = m->nf;
	m->has_faces = m->nf > 0;
	if (build_vertex_columns(o) || build_corner_lists(o) || build_texnumber(o))
		return -1;
	return 0;
}

static void obj_free(struct obj *o)
{
	free(o->pos), free(o->rgb), free(o->vt), free(o->vn);
	free(o->first), free(o->ct), free(o->cn), free(o->ftex);
	for (size_t i = 0; i < o->nmat; i++)
		free(o->mat[i].name), free(o->mat[i].map);
	free(o->mat);
	free(o->mat_by_name.slot);
	for (size_t i = 0; i < o->ntex; i++)
		free(o->tex[i]);
	free(o->tex);
	free(o->tex_by_path.slot);
	for (size_t i = 0; i < o->nmtllibs; i++)
		free(o->mtllibs[i]);
	free(o->mtllibs);
	free(o->mtllib_seen.slot);
	free(o->joined);
}

int fct_obj_read(struct fct_mesh *m, struct fct_reader *r, const char *dir, struct fct_err *err)
{
	struct obj o;
	memset(&o, 0, sizeof o);
	o.m = m, o.r = r, o.err = err, o.dir = dir;
	o.cur_mat = -1, o.cur_tex = -2;
	err->msg[0] = 0;
	int rc = 0;
	size_t len;
	char *s;
	while ((s = next_statement(&o, &len)))
		if ((rc = statement(&o, s, len)))
			break;
	if (!rc && err->msg[0])
		rc = -1;
	if (!rc)
		rc = finish(&o);
	obj_free(&o);
	if (rc)
		fct_mesh_free(m);
	return rc ? -1 : 0;
}

/* Writer ----------------------------------------------------------------- */

/* Buffered output: OBJ is many short lines. */
struct wbuf {
	FILE *f;
	char buf[1 << 16];
	size_t len;
};

static void w_flush(struct wbuf *w)
{
	if (w->len)
		fwrite(w->buf, 1, w->len, w->f);
	w->len = 0;
}

static inline char *w_reserve(struct wbuf *w, size_t n)
{
	if (w->len + n > sizeof w->buf)
		w_flush(w);
	return w->buf + w->len;
}

static void w_str(struct wbuf *w, const char *s)
{
	size_t n = strlen(s);
	if (n > sizeof w->buf / 2) {
		w_flush(w);
		fwrite(s, 1, n, w->f);
		return;
	}
	memcpy(w_reserve(w, n), s, n);
	w->len += n;
}

static void w_uint(struct wbuf *w, uint64_t v)
{
	char tmp[24];
	int n = 0;
	do
		tmp[n++] = (char)('0' + v % 10);
	while (v /= 10);
	char *p = w_reserve(w, (size_t)n);
	for (int i = 0; i < n; i++)
		p[i] = tmp[n - 1 - i];
	w->len += (size_t)n;
}

static void w_float(struct wbuf *w, float v)
{
	w->len += (size_t)fct_format_float(w_reserve(w, 40), 40, v);
}

static void w_double(struct wbuf *w, double v)
{
	w->len += (size_t)fct_format_double(w_reserve(w, 40), 40, v);
}

/* Value i of column p, as precisely as its type holds. */
static void w_value(struct wbuf *w, const struct fct_prop *p, size_t i)
{
	if (p->type == FCT_FLOAT32)
		w_float(w, ((const float *)p->data)[i]);
	else
		w_double(w, fct_prop_get(p, i));
}

/* A scalar vertex/face column called name, or NULL. */
static const struct fct_prop *scalar(const struct fct_elem *e, const char *name)
{
	const struct fct_prop *p = fct_elem_find(e, name);
	return p && !p->count_type ? p : NULL;
}

int fct_obj_wants_mtl(const struct fct_mesh *m)
{
	const struct fct_prop *s, *t;
	return (fct_texcoord_vertex(m, &s, &t) || fct_texcoord_face(m)) &&
	       fct_header_texture_count(m) > 0;
}

/* The material of face f: its texnumber when valid, else texture 0; -1 for
 * "untextured". */
static long face_material(const struct fct_prop *tn, size_t f, size_t ntex)
{
	if (!tn)
		return 0;
	double k = fct_prop_get(tn, f);
	return k >= 0 && k < (double)ntex ? (long)k : -1;
}

static int write_mtl(const struct fct_mesh *m, FILE *mtl, int untextured)
{
	fputs("# facet\n", mtl);
	size_t k = 0;
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *path = fct_comment_texture(&m->comments[i]);
		if (path)
			fprintf(mtl, "newmtl material_%zu\nKa 1 1 1\nKd 1 1 1\nmap_Kd %s\n\n", k++, path);
	}
	if (untextured)
		fputs("newmtl untextured\nKa 1 1 1\nKd 1 1 1\n", mtl);
	return ferror(mtl) ? -1 : 0;
}

/* The distinct values of a per-corner face list (dim values a corner, or
 * none for a face whose list is empty), in order of first use: the vt or
 * vn lines, and each corner's index among them. */
#define NO_VALUE UINT32_MAX
struct corner_values {
	size_t *first;     /* per distinct value: the list index of its first corner */
	size_t n;
	uint32_t *of;      /* per corner: the index of its value, or NO_VALUE */
};

static uint64_t corner_hash(const struct fct_prop *p, size_t at, unsigned dim)
{
	uint64_t h = UINT64_C(14695981039346656037);
	for (unsigned j = 0; j < dim; j++) {
		double v = fct_prop_get(p, at + j);
		uint64_t b;
		memcpy(&b, &v, sizeof b);
		h = (h ^ b) * UINT64_C(0x100000001B3);
		h ^= h >> 31;
	}
	return h;
}

/* Are the values at list indices a and b the same, bit for bit? */
static int same_corner(const struct fct_prop *p, size_t a, size_t b, unsigned dim)
{
	for (unsigned j = 0; j < dim; j++) {
		double x = fct_prop_get(p, a + j), y = fct_prop_get(p, b + j);
		if (memcmp(&x, &y, sizeof x))
			return 0;
	}
	return 1;
}

/* Collect the distinct values of p (fct_corner_list's, dim per corner) over
 * m's corners. */
static int corner_values_build(struct corner_values *cv, const struct fct_mesh *m, const struct fct_prop *p,
                               unsigned dim, struct fct_err *err)
{
	size_t corners = m->nf ? m->fstart[m->nf] : 0, nslot = 16;
	while (nslot < 2 * corners)
		nslot *= 2;
	uint32_t *slot = calloc(nslot, sizeof *slot);
	cv->first = fct_alloc_array(corners, sizeof *cv->first, err);
	cv->of = fct_alloc_array(corners, sizeof *cv->of, err);
	cv->n = 0;
	if (!slot || !cv->first || !cv->of) {
		free(slot);
		return fct_fail(err, "out of memory");
	}
	for (size_t f = 0; f < m->nf; f++) {
		int none = p->off[f + 1] == p->off[f];
		for (uint32_t c = m->fstart[f]; c < m->fstart[f + 1]; c++) {
			if (none) {
				cv->of[c] = NO_VALUE;
				continue;
			}
			size_t at = p->off[f] + (size_t)dim * (c - m->fstart[f]);
			size_t i = (size_t)corner_hash(p, at, dim) & (nslot - 1);
			for (; slot[i]; i = (i + 1) & (nslot - 1))
				if (same_corner(p, cv->first[slot[i] - 1], at, dim))
					break;
			if (!slot[i]) {
				cv->first[cv->n++] = at;
				slot[i] = (uint32_t)cv->n;
			}
			cv->of[c] = slot[i] - 1;
		}
	}
	free(slot);
	return 0;
}

static void corner_values_free(struct corner_values *cv)
{
	free(cv->first);
	free(cv->of);
}

/* The vt (dim 2) or vn (dim 3) lines: the distinct values of the
 * per-corner list when there is one, else one a vertex from the vertex
 * columns col[0..dim). */
static void w_attribute_lines(struct wbuf *w, const char *kw, const struct fct_prop *list,
                              const struct corner_values *cv, const struct fct_prop *const *col,
                              int dim, size_t nv)
{
	size_t n = list ? cv->n : nv;
	for (size_t i = 0; i < n; i++) {
		w_str(w, kw);
		for (int k = 0; k < dim; k++) {
			w_str(w, " ");
			if (list)
				w_value(w, list, cv->first[i] + (size_t)k);
			else
				w_value(w, col[k], i);
		}
		w_str(w, "\n");
	}
}

int fct_obj_write(const struct fct_mesh *m, FILE *f, const char *mtl_name, FILE *mtl,
                  struct fct_err *err)
{
	struct elem_cols {
		const struct fct_prop *nx, *ny, *nz, *s, *t, *r, *g, *b;
	} c = {
		scalar(&m->vertex, "nx"), scalar(&m->vertex, "ny"), scalar(&m->vertex, "nz"),
		NULL, NULL,
		scalar(&m->vertex, "red"), scalar(&m->vertex, "green"), scalar(&m->vertex, "blue"),
	};
	/* Texture coordinates and normals per face corner (face lists texcoord
	 * and corner_normal: seams, and what the OBJ reader makes when the
	 * corners round a vertex disagree) win over per vertex ones. */
	const struct fct_prop *corner_vt = fct_texcoord_face(m);
	const struct fct_prop *corner_vn = fct_corner_list(m, "corner_normal", 3);
	if (!corner_vt)
		fct_texcoord_vertex(m, &c.s, &c.t);
	int vertex_vt = c.s && c.t, vertex_vn = !corner_vn && c.nx && c.ny && c.nz;
	int has_rgb = c.r && c.g && c.b && c.r->type == FCT_UINT8 && c.g->type == FCT_UINT8 &&
	              c.b->type == FCT_UINT8;
	int textured = fct_obj_wants_mtl(m);
	size_t ntex = fct_header_texture_count(m);
	const struct fct_prop *tn = textured ? scalar(&m->face, "texnumber") : NULL;
	int untextured = 0;
	for (size_t i = 0; tn && i < m->nf; i++)
		untextured |= face_material(tn, i, ntex) < 0;

	struct corner_values vtv = {0}, vnv = {0};
	struct wbuf *w = malloc(sizeof *w);
	if (!w || (corner_vt && corner_values_build(&vtv, m, corner_vt, 2, err)) ||
	    (corner_vn && corner_values_build(&vnv, m, corner_vn, 3, err))) {
		free(w);
		corner_values_free(&vtv);
		corner_values_free(&vnv);
		return fct_fail(err, "out of memory");
	}
	w->f = f, w->len = 0;
	w_str(w, "# facet\n");
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *key = m->comments[i].obj_info ? "# obj_info " : "# comment ";
		char line[FCT_HEADER_LINE_MAX + 64];
		w_str(w, key);
		w_str(w, fct_comment_line(&m->comments[i], FCT_HEADER_LINE_MAX - strlen(key), line));
		w_str(w, "\n");
	}
	if (textured && mtl_name) {
		w_str(w, "mtllib ");
		w_str(w, mtl_name);
		w_str(w, "\n");
	}
	int dbl = m->xyz_type == FCT_FLOAT64;
	for (size_t i = 0; i < m->nv; i++) {
		w_str(w, "v");
		for (int k = 0; k < 3; k++) {
			w_str(w, " ");
			if (dbl)
				w_double(w, m->xyz[3 * i + (size_t)k]);
			else
				w_float(w, (float)m->xyz[3 * i + (size_t)k]);
		}
		if (has_rgb) {
			const struct fct_prop *rgb[3] = {c.r, c.g, c.b};
			for (int k = 0; k < 3; k++) {
				w_str(w, " ");
				w_float(w, (float)((const uint8_t *)rgb[k]->data)[i] / 255.0f);
			}
		}
		w_str(w, "\n");
	}
	if (corner_vt || vertex_vt) {
		const struct fct_prop *st[2] = {c.s, c.t};
		w_attribute_lines(w, "vt", corner_vt, &vtv, st, 2, m->nv);
	}
	if (corner_vn || vertex_vn) {
		const struct fct_prop *n[3] = {c.nx, c.ny, c.nz};
		w_attribute_lines(w, "vn", corner_vn, &vnv, n, 3, m->nv);
	}
	long cur = -2;
	for (size_t i = 0; i < m->nf; i++) {
		if (textured && mtl_name) {
			long k = face_material(tn, i, ntex);
			if (k != cur) {
				char line[64];
				if (k >= 0)
					snprintf(line, sizeof line, "usemtl material_%ld\n", k);
				else
					snprintf(line, sizeof line, "usemtl untextured\n");
				w_str(w, line);
				cur = k;
			}
		}
		w_str(w, "f");
		for (uint32_t k = m->fstart[i]; k < m->fstart[i + 1]; k++) {
			uint32_t v = m->fvert[k];
			uint32_t t = corner_vt ? vtv.of[k] : vertex_vt ? v : NO_VALUE;
			uint32_t n = corner_vn ? vnv.of[k] : vertex_vn ? v : NO_VALUE;
			w_str(w, " ");
			w_uint(w, (uint64_t)v + 1);
			if (t != NO_VALUE || n != NO_VALUE) {
				w_str(w, "/");
				if (t != NO_VALUE)
					w_uint(w, (uint64_t)t + 1);
				if (n != NO_VALUE) {
					w_str(w, "/");
					w_uint(w, (uint64_t)n + 1);
				}
			}
		}
		w_str(w, "\n");
	}
	w_flush(w);
	free(w);
	corner_values_free(&vtv);
	corner_values_free(&vnv);
	if (textured && mtl && write_mtl(m, mtl, untextured))
		return fct_fail(err, "material library: write error: %s", strerror(errno ? errno : EIO));
	if (ferror(f))
		return fct_fail(err, "write error: %s", strerror(errno ? errno : EIO));
	return 0;
}

/* ply.c - PLY reader and writer (see ply.h).
 *
 * The body is read element by element with a "slot" per property that says
 * where its values go (a position coordinate, the face lists, or a typed
 * column), so one loop serves every layout.  Binary values are copied as raw
 * bytes into columns of their own type, which is what makes the round trip
 * exact. */
#include "io/ply.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/header.h"
#include "core/numparse.h"

enum { MAX_PROPS = 4096, MAX_ELEMS = 4096, LIST_BATCH = 1 << 16 };

/* Header ------------------------------------------------------------------- */

struct hprop {
	char *name;
	enum fct_type type, count_type;
};

struct helem {
	char *name;
	uint64_t count;
	size_t nprops;
	struct hprop *props;
};

struct header {
	enum fct_ply_format fmt;
	size_t nelems;
	struct helem *elems;
};

static void header_free(struct header *h)
{
	for (size_t i = 0; i < h->nelems; i++) {
		for (size_t j = 0; j < h->elems[i].nprops; j++)
			free(h->elems[i].props[j].name);
		free(h->elems[i].props);
		free(h->elems[i].name);
	}
	free(h->elems);
}

int fct_ply_detect(struct fct_reader *r)
{
	size_t n = fct_reader_fill(r, 5);
	const unsigned char *p = r->buf + r->pos;
	return n >= 4 && !memcmp(p, "ply", 3) && (p[3] == '\n' || (n >= 5 && p[3] == '\r' && p[4] == '\n'));
}

/* Split s into at most max blank-separated words in place; returns the count. */
static int split_words(char *s, char **w, int max)
{
	int n = 0;
	while (n < max) {
		while (*s == ' ' || *s == '\t')
			s++;
		if (!*s)
			break;
		w[n++] = s;
		while (*s && *s != ' ' && *s != '\t')
			s++;
		if (*s)
			*s++ = 0;
	}
	while (*s == ' ' || *s == '\t')
		s++;
	return *s ? max + 1 : n;
}

/* Text after a keyword and the single blank that follows it. */
static const char *after_keyword(const char *line, size_t kwlen)
{
	line += kwlen;
	return *line ? line + 1 : line;
}

static int parse_header(struct header *h, struct fct_mesh *m, struct fct_reader *r,
                        struct fct_err *err)
{
	size_t len;
	char *line = fct_reader_line(r, &len, err);  /* "ply", checked by fct_ply_detect */
	int have_format = 0;
	for (;;) {
		if (!(line = fct_reader_line(r, &len, err))) {
			if (!err->msg[0])
				fct_fail(err, "%s:%" PRIu64 ": header ends without end_header", r->name, r->line);
			return -1;
		}
		if (strlen(line) != len)
			return fct_fail(err, "%s:%" PRIu64 ": NUL byte in header", r->name, r->line);
		if (!strncmp(line, "comment", 7) && (line[7] == ' ' || line[7] == '\t' || !line[7])) {
			if (fct_mesh_add_comment(m, after_keyword(line, 7), 0, err))
				return -1;
			continue;
		}
		if (!strncmp(line, "obj_info", 8) && (line[8] == ' ' || line[8] == '\t' || !line[8])) {
			if (fct_mesh_add_comment(m, after_keyword(line, 8), 1, err))
				return -1;
			continue;
		}
		char *w[6];
		int nw = split_words(line, w, 5);
		if (nw == 0)
			continue;  /* blank lines are tolerated */
		if (!strcmp(w[0], "end_header")) {
			if (nw != 1)
				return fct_fail(err, "%s:%" PRIu64 ": words after end_header", r->name, r->line);
			break;
		}
		if (!strcmp(w[0], "format")) {
			if (have_format)
				return fct_fail(err, "%s:%" PRIu64 ": second format line", r->name, r->line);
			if (nw != 3 || strcmp(w[2], "1.0"))
				return fct_fail(err, "%s:%" PRIu64 ": expected \"format <encoding> 1.0\"", r->name, r->line);
			if (!strcmp(w[1], "ascii"))
				h->fmt = FCT_PLY_ASCII;
			else if (!strcmp(w[1], "binary_little_endian"))
				h->fmt = FCT_PLY_BINARY_LE;
			else if (!strcmp(w[1], "binary_big_endian"))
				h->fmt = FCT_PLY_BINARY_BE;
			else
				return fct_fail(err, "%s:%" PRIu64 ": unknown format \"%s\"", r->name, r->line, w[1]);
			have_format = 1;
			continue;
		}
		if (!have_format)
			return fct_fail(err, "%s:%" PRIu64 ": \"%s\" before the format line", r->name, r->line, w[0]);
		if (!strcmp(w[0], "element")) {
			int64_t count;
			const char *end;
			if (nw != 3)
				return fct_fail(err, "%s:%" PRIu64 ": expected \"element <name> <count>\"", r->name, r->line);
			if (!(end = fct_parse_int64(w[2], &count)) || *end || count < 0 || w[2][0] == '+')
				return fct_fail(err, "%s:%" PRIu64 ": element %s: bad count \"%s\"", r->name, r->line, w[1], w[2]);
			for (size_t i = 0; i < h->nelems; i++)
				if (!strcmp(h->elems[i].name, w[1]))
					return fct_fail(err, "%s:%" PRIu64 ": second element %s", r->name, r->line, w[1]);
			if (h->nelems >= MAX_ELEMS)
				return fct_fail(err, "%s:%" PRIu64 ": more than %d elements", r->name, r->line, MAX_ELEMS);
			struct helem *ne = realloc(h->elems, (h->nelems + 1) * sizeof *ne);
			if (!ne)
				return fct_fail(err, "out of memory");
			h->elems = ne;
			struct helem *e = &ne[h->nelems];
			memset(e, 0, sizeof *e);
			if (!(e->name = fct_strdup(w[1], err)))
				return -1;
			e->count = (uint64_t)count;
			h->nelems++;
			continue;
		}
		if (!strcmp(w[0], "property")) {
			if (!h->nelems)
				return fct_fail(err, "%s:%" PRIu64 ": property before any element", r->name, r->line);
			struct helem *e = &h->elems[h->nelems - 1];
			struct hprop p = {0};
			const char *name;
			if (nw == 3) {
				p.type = fct_type_parse(w[1]);
				name = w[2];
				if (!p.type)
					return fct_fail(err, "%s:%" PRIu64 ": unknown type \"%s\"", r->name, r->line, w[1]);
			} else if (nw == 5 && !strcmp(w[1], "list")) {
				p.count_type = fct_type_parse(w[2]);
				p.type = fct_type_parse(w[3]);
				name = w[4];
				if (!p.count_type || !p.type)
					return fct_fail(err, "%s:%" PRIu64 ": unknown type \"%s\"", r->name, r->line,
					                p.count_type ? w[3] : w[2]);
				if (p.count_type == FCT_FLOAT32 || p.count_type == FCT_FLOAT64)
					return fct_fail(err, "%s:%" PRIu64 ": list count type %s is not an integer type",
					                r->name, r->line, w[2]);
			} else {
				return fct_fail(err, "%s:%" PRIu64 ": expected \"property <type> <name>\" or "
				                "\"property list <type> <type> <name>\"", r->name, r->line);
			}
			for (size_t i = 0; i < e->nprops; i++)
				if (!strcmp(e->props[i].name, name))
					return fct_fail(err, "%s:%" PRIu64 ": element %s: second property %s",
					                r->name, r->line, e->name, name);
			if (e->nprops >= MAX_PROPS)
				return fct_fail(err, "%s:%" PRIu64 ": more than %d properties", r->name, r->line, MAX_PROPS);
			struct hprop *np = realloc(e->props, (e->nprops + 1) * sizeof *np);
			if (!np)
				return fct_fail(err, "out of memory");
			e->props = np;
			if (!(p.name = fct_strdup(name, err)))
				return -1;
			np[e->nprops++] = p;
			continue;
		}
		return fct_fail(err, "%s:%" PRIu64 ": unknown header line \"%s\"", r->name, r->line, w[0]);
	}
	if (!have_format)
		return fct_fail(err, "%s:%" PRIu64 ": no format line", r->name, r->line);
	return 0;
}

/* Body --------------------------------------------------------------------- */

enum slot_kind { SLOT_X, SLOT_Y, SLOT_Z, SLOT_FACE, SLOT_COLUMN };

struct slot {
	enum slot_kind kind;
	enum fct_type type, count_type;
	size_t size, count_size;
	size_t off;               /* byte offset in a row, for the fast paths */
	struct fct_prop *col;
	const char *name;
};

struct body {
	struct fct_mesh *m;
	struct fct_reader *r;
	struct fct_err *err;
	const struct helem *he;
	struct fct_elem *dest;    /* where SLOT_COLUMN values go */
	struct slot *slots;
	int swap;                 /* big-endian file on this little-endian reading */
	char *cur;                /* ascii: rest of the current line */
	enum { FAST_NONE, FAST_SCALARS, FAST_FACE } fast;  /* see plan_fast */
	size_t fast_rest;
};

static int host_is_big_endian(void)
{
	const uint16_t one = 1;
	return *(const unsigned char *)&one == 0;
}

/* Copy a value of sz bytes from the file's byte order to the host's. */
static inline void load_raw(void *dst, const unsigned char *src, size_t sz, int swap)
{
	if (!swap) {
		/* Constant sizes, so that the copies are moves, not calls. */
		switch (sz) {
		case 1: memcpy(dst, src, 1); return;
		case 2: memcpy(dst, src, 2); return;
		case 4: memcpy(dst, src, 4); return;
		case 8: memcpy(dst, src, 8); return;
		default: memcpy(dst, src, sz); return;
		}
	}
	unsigned char *d = dst;
	for (size_t k = 0; k < sz; k++)
		d[k] = src[sz - 1 - k];
}

static inline double raw_to_double(const void *raw, enum fct_type t)
{
	union { int8_t i8; uint8_t u8; int16_t i16; uint16_t u16; int32_t i32; uint32_t u32; float f; double d; } v;
	memcpy(&v, raw, fct_type_size(t));
	switch (t) {
	case FCT_INT8: return v.i8;
	case FCT_UINT8: return v.u8;
	case FCT_INT16: return v.i16;
	case FCT_UINT16: return v.u16;
	case FCT_INT32: return v.i32;
	case FCT_UINT32: return v.u32;
	case FCT_FLOAT32: return v.f;
	case FCT_FLOAT64: return v.d;
	default: abort();
	}
}

/* An integer value (list count or vertex index); *ok = 0 when it is not a whole number. */
static inline int64_t raw_to_int(const void *raw, enum fct_type t, int *ok)
{
	double d = raw_to_double(raw, t);
	*ok = d == d && d >= -9e18 && d <= 9e18 && d == (double)(int64_t)d;
	return *ok ? (int64_t)d : 0;
}

/* Describe where we are, for messages: "FILE:LINE" or "FILE: byte N". */
static void where(const struct body *b, char *buf, size_t n)
{
	if (b->cur)
		snprintf(buf, n, "%s:%" PRIu64, b->r->name, b->r->line);
	else
		snprintf(buf, n, "%s: byte %" PRIu64, b->r->name, fct_reader_offset(b->r));
}

/* The input ended (or failed) inside row `row` of the element. */
static int body_short(const struct body *b, uint64_t row)
{
	char what[300];
	snprintf(what, sizeof what, "element %s %" PRIu64, b->he->name, row);
	return fct_reader_fail_short(b->r, b->err, what);
}

static int body_fail(const struct body *b, uint64_t row, const struct slot *s, const char *what)
{
	char w[600];
	where(b, w, sizeof w);
	if (s)
		return fct_fail(b->err, "%s: element %s %" PRIu64 ": property %s: %s", w, b->he->name, row, s->name, what);
	return fct_fail(b->err, "%s: element %s %" PRIu64 ": %s", w, b->he->name, row, what);
}

/* Storage for exactly rows [0, rows) of every scalar destination of the
 * element (grow_rows does the doubling when the count is not vouched for). */
static int reserve_rows(struct body *b, size_t rows)
{
	struct fct_mesh *m = b->m;
	for (size_t j = 0; j < b->he->nprops; j++) {
		struct slot *s = &b->slots[j];
		if (s->kind <= SLOT_Z) {
			if (fct_reserve((void **)&m->xyz, &m->xyz_cap, 3 * rows, sizeof *m->xyz, b->err))
				return -1;
		} else if (s->kind == SLOT_FACE) {
			if (fct_reserve((void **)&m->fstart, &m->fstart_cap, rows + 1, sizeof *m->fstart, b->err))
				return -1;
		} else if (s->count_type) {
			if (fct_reserve((void **)&s->col->off, &s->col->off_cap, rows + 1, sizeof *s->col->off, b->err))
				return -1;
		} else if (fct_reserve(&s->col->data, &s->col->cap, rows, s->size, b->err)) {
			return -1;
		}
	}
	return 0;
}

/* All rows are read: double the storage, up to the element's count. */
static int grow_rows(struct body *b, size_t count, size_t *reserved)
{
	size_t i = *reserved;
	*reserved = count - i < i ? count : 2 * i;
	return reserve_rows(b, *reserved);
}

/* Storage for the first rows, and the first offset of every list. */
static int start_rows(struct body *b, size_t rows)
{
	if (reserve_rows(b, rows))
		return -1;
	for (size_t j = 0; j < b->he->nprops; j++) {
		struct slot *s = &b->slots[j];
		if (s->kind == SLOT_FACE)
			b->m->fstart[0] = 0;
		else if (s->kind == SLOT_COLUMN && s->count_type)
			s->col->off[0] = 0;
	}
	return 0;
}

/* Room for n more list items after `used` in the slot's destination. */
static int reserve_items(struct body *b, struct slot *s, size_t used, size_t n)
{
	if (s->kind == SLOT_FACE)
		return fct_grow((void **)&b->m->fvert, &b->m->fvert_cap, used + n, sizeof *b->m->fvert, b->err);
	return fct_grow(&s->col->data, &s->col->cap, used + n, s->size, b->err);
}

static size_t *list_offsets_used(struct body *b, struct slot *s, uint64_t row, size_t *used)
{
	if (s->kind == SLOT_FACE) {
		*used = b->m->fstart[row];
		return NULL;
	}
	*used = s->col->off[row];
	return s->col->off;
}

static int store_index(struct body *b, uint64_t row, const struct slot *s, int64_t v, size_t at)
{
	if (v < 0 || v > (int64_t)UINT32_MAX - 1) {
		char what[80];
		snprintf(what, sizeof what, "vertex index %" PRId64 " out of range", v);
		return body_fail(b, row, s, what);
	}
	b->m->fvert[at] = (uint32_t)v;
	return 0;
}

/* Check a list length against what the list is for. */
static int check_list_length(struct body *b, uint64_t row, const struct slot *s, int64_t n)
{
	if (n < 0)
		return body_fail(b, row, s, "negative list length");
	if (s->kind == SLOT_FACE && n < 3) {
		char what[80];
		snprintf(what, sizeof what, "a face needs 3 or more vertices, got %" PRId64, n);
		return body_fail(b, row, s, what);
	}
	if (s->kind == SLOT_FACE && (uint64_t)n + b->m->fstart[row] > UINT32_MAX)
		return body_fail(b, row, s, "too many face vertices in all");
	return 0;
}

static int check_position(struct body *b, uint64_t row, const struct slot *s, double v)
{
	return isfinite(v) ? 0 : body_fail(b, row, s, "coordinate is not a finite number");
}

/* Store the scalar of slot s for row i from the file bytes at p (host order). */
static inline int store_scalar_fast(struct body *b, const struct slot *s, size_t i, const unsigned char *p)
{
	if (s->kind == SLOT_COLUMN) {
		char *d = (char *)s->col->data + i * s->size;
		switch (s->size) {
		case 1: *d = (char)*p; break;
		case 2: memcpy(d, p, 2); break;
		case 4: memcpy(d, p, 4); break;
		default: memcpy(d, p, 8); break;
		}
		return 0;
	}
	double v;
	if (s->type == FCT_FLOAT32) {
		float f;
		memcpy(&f, p, 4);
		v = f;
	} else {
		v = raw_to_double(p, s->type);
	}
	if (!isfinite(v))
		return -1;
	b->m->xyz[3 * i + (s->kind - SLOT_X)] = v;
	return 0;
}

/* Which fast path the element's layout allows, decided once per element:
 * FAST_NONE, FAST_SCALARS (host byte order, no lists) or FAST_FACE (a face
 * list of uchar count and 32-bit indices first, then scalars).  Sets each
 * scalar slot's offset and b->fast_rest, the bytes of scalars in a row. */
static void plan_fast(struct body *b)
{
	size_t ns = b->he->nprops, first = 0, rest = 0;
	b->fast = FAST_NONE;
	if (b->swap || !ns)
		return;
	const struct slot *s0 = &b->slots[0];
	if (s0->kind == SLOT_FACE) {
		if (s0->count_size != 1 || (s0->type != FCT_INT32 && s0->type != FCT_UINT32))
			return;
		first = 1;
	}
	for (size_t j = first; j < ns; j++) {
		if (b->slots[j].count_type)
			return;
		b->slots[j].off = rest;
		rest += b->slots[j].size;
	}
	b->fast = first ? FAST_FACE : FAST_SCALARS;
	b->fast_rest = rest;
}

/* Rows [i, limit) that lie whole in the read buffer, for the layouts
 * plan_fast accepted.  Returns the number of rows stored; stops early,
 * without consuming the row, at anything unusual so that the general path
 * reads it again and reports it.  (size_t)-1 on failure. */
static size_t fast_rows(struct body *b, size_t i, size_t limit)
{
	struct fct_reader *r = b->r;
	size_t ns = b->he->nprops, rest = b->fast_rest;
	int face = b->fast == FAST_FACE;
	size_t first = face ? 1 : 0;
	const unsigned char *p = r->buf + r->pos, *end = r->buf + r->len;
	size_t k = i;
	struct fct_mesh *m = b->m;
	for (; k < limit; k++) {
		const unsigned char *row = p;
		if (face) {
			if (end - p < 1)
				break;
			size_t c = *p;
			if (c < 3 || (size_t)(end - p) < 1 + 4 * c + rest)
				break;
			size_t used = m->fstart[k];
			if (used + c > UINT32_MAX)
				break;
			if (used + c > m->fvert_cap &&
			    fct_grow((void **)&m->fvert, &m->fvert_cap, used + c, sizeof *m->fvert, b->err))
				return (size_t)-1;
			uint32_t *dst = m->fvert + used, neg = 0;
			if (c == 3) {  /* the rule: a constant-size copy the compiler inlines */
				memcpy(dst, p + 1, 12);
				neg = dst[0] | dst[1] | dst[2];
			} else {
				memcpy(dst, p + 1, 4 * c);
				for (size_t q = 0; q < c; q++)
					neg |= dst[q];
			}
			if (b->slots[0].type == FCT_INT32 && (neg >> 31))
				break;
			m->fstart[k + 1] = (uint32_t)(used + c);
			row = p + 1 + 4 * c;
		} else if ((size_t)(end - p) < rest) {
			break;
		}
		size_t j;
		for (j = first; j < ns; j++)
			if (store_scalar_fast(b, &b->slots[j], k, row + b->slots[j].off))
				break;
		if (j < ns)
			break;
		p = row + rest;
	}
	r->pos = (size_t)(p - r->buf);
	return k - i;
}

/* Binary body of one element. */
static int read_binary_elem(struct body *b)
{
	struct fct_reader *r = b->r;
	const struct helem *he = b->he;
	size_t ns = he->nprops;
	int fixed = 1;
	uint64_t rowmin = 0;
	for (size_t j = 0; j < ns; j++) {
		fixed &= !b->slots[j].count_type;
		rowmin += b->slots[j].count_type ? b->slots[j].count_size : b->slots[j].size;
	}
	uint64_t left = fct_reader_remaining(r);
	if (rowmin && left != UINT64_MAX && he->count > left / rowmin)
		return fct_fail(b->err, "%s: byte %" PRIu64 ": element %s: %" PRIu64 " rows of at least %"
		                PRIu64 " bytes cannot fit in the %" PRIu64 " bytes left",
		                r->name, fct_reader_offset(r), he->name, he->count, rowmin, left);
	if (!rowmin && he->count)
		return fct_fail(b->err, "%s: byte %" PRIu64 ": element %s: %" PRIu64 " rows with no properties",
		                r->name, fct_reader_offset(r), he->name, he->count);
	if (he->count > SIZE_MAX / 16)
		return fct_fail(b->err, "%s: element %s: count too large", r->name, he->name);
	size_t count = (size_t)he->count;
	/* Reserve all rows when the file's size vouches for them, else grow as rows arrive. */
	size_t reserved = left != UINT64_MAX ? count : (count < 4096 ? count : 4096);
	if (start_rows(b, reserved))
		return -1;
	struct fct_mesh *m = b->m;
	if (b->slots[0].kind == SLOT_FACE && left != UINT64_MAX) {
		/* Triangles are the rule; the bytes left bound how many indices can come. */
		size_t guess = left / b->slots[0].size < 3 * (uint64_t)count ? (size_t)(left / b->slots[0].size) : 3 * count;
		if (fct_reserve((void **)&m->fvert, &m->fvert_cap, guess, sizeof *m->fvert, b->err))
			return -1;
	}
	plan_fast(b);
	for (size_t i = 0; i < count; i++) {
		if (i == reserved && grow_rows(b, count, &reserved))
			return -1;
		size_t done = b->fast ? fast_rows(b, i, reserved) : 0;
		if (done == (size_t)-1)
			return -1;
		if (done) {
			i += done - 1;
			continue;
		}
		if (fixed && fct_reader_fill(r, (size_t)rowmin) < rowmin)
			return body_short(b, i);
		for (size_t j = 0; j < ns; j++) {
			struct slot *s = &b->slots[j];
			if (!s->count_type) {
				if (!fixed && fct_reader_fill(r, s->size) < s->size)
					return body_short(b, i);
				const unsigned char *p = r->buf + r->pos;
				r->pos += s->size;
				if (s->kind == SLOT_COLUMN) {
					load_raw((char *)s->col->data + i * s->size, p, s->size, b->swap);
				} else {
					unsigned char raw[8];
					load_raw(raw, p, s->size, b->swap);
					double v = raw_to_double(raw, s->type);
					if (check_position(b, i, s, v))
						return -1;
					m->xyz[3 * i + (s->kind - SLOT_X)] = v;
				}
				continue;
			}
			if (fct_reader_fill(r, s->count_size) < s->count_size)
				return body_short(b, i);
			unsigned char raw[8];
			int ok;
			load_raw(raw, r->buf + r->pos, s->count_size, b->swap);
			int64_t n = raw_to_int(raw, s->count_type, &ok);
			if (check_list_length(b, i, s, n))
				return -1;
			r->pos += s->count_size;
			size_t used;
			size_t *off = list_offsets_used(b, s, i, &used);
			for (int64_t k = 0; k < n;) {
				size_t batch = n - k < LIST_BATCH ? (size_t)(n - k) : LIST_BATCH;
				if (reserve_items(b, s, used + (size_t)k, batch))
					return -1;
				if (fct_reader_fill(r, batch * s->size) < batch * s->size)
					return body_short(b, i);
				const unsigned char *p = r->buf + r->pos;
				if (s->kind == SLOT_COLUMN) {
					char *d = (char *)s->col->data + (used + (size_t)k) * s->size;
					if (!b->swap)
						memcpy(d, p, batch * s->size);
					else
						for (size_t q = 0; q < batch; q++)
							load_raw(d + q * s->size, p + q * s->size, s->size, 1);
				} else {
					for (size_t q = 0; q < batch; q++) {
						load_raw(raw, p + q * s->size, s->size, b->swap);
						int64_t v = raw_to_int(raw, s->type, &ok);
						if (!ok)
							return body_fail(b, i, s, "vertex index is not an integer");
						if (store_index(b, i, s, v, used + (size_t)k + q))
							return -1;
					}
				}
				r->pos += batch * s->size;
				k += (int64_t)batch;
			}
			if (off)
				off[i + 1] = used + (size_t)n;
			else
				m->fstart[i + 1] = (uint32_t)(used + (size_t)n);
		}
	}
	return 0;
}

/* Ascii: the next blank-separated word, across line ends; NULL at end of input. */
static char *next_word(struct body *b)
{
	for (;;) {
		char *c = b->cur;
		while (*c == ' ' || *c == '\t' || *c == '\r' || *c == '\f' || *c == '\v')
			c++;
		if (*c) {
			b->cur = c;
			return c;
		}
		size_t len;
		char *line = fct_reader_line(b->r, &len, b->err);
		if (!line)
			return NULL;
		if (strlen(line) != len) {
			body_fail(b, 0, NULL, "NUL byte in text");
			return NULL;
		}
		b->cur = line;
	}
}

static int is_word_end(char c)
{
	return c == 0 || c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/* Parse one ascii value of type t at the current word into *d (as a double)
 * and raw (in the host's representation of t). */
static int ascii_value(struct body *b, uint64_t row, const struct slot *s, enum fct_type t,
                       double *d, void *raw)
{
	char *w = next_word(b);
	if (!w) {
		if (!b->err->msg[0])
			return body_fail(b, row, s, "unexpected end of file");
		return -1;
	}
	const char *end;
	if (t == FCT_FLOAT32 || t == FCT_FLOAT64) {
		end = fct_parse_double(w, d);
		if (!end || !is_word_end(*end))
			goto bad;
		if (t == FCT_FLOAT32) {
			float f = (float)*d;
			memcpy(raw, &f, 4);
		} else {
			memcpy(raw, d, 8);
		}
	} else {
		int64_t v;
		end = fct_parse_int64(w, &v);
		if (!end || !is_word_end(*end))
			goto bad;
		static const int64_t lo[] = {0, INT8_MIN, 0, INT16_MIN, 0, INT32_MIN, 0};
		static const int64_t hi[] = {0, INT8_MAX, UINT8_MAX, INT16_MAX, UINT16_MAX, INT32_MAX, UINT32_MAX};
		if (v < lo[t] || v > hi[t])
			goto bad;
		*d = (double)v;
		switch (t) {
		case FCT_INT8: { int8_t x = (int8_t)v; memcpy(raw, &x, 1); break; }
		case FCT_UINT8: { uint8_t x = (uint8_t)v; memcpy(raw, &x, 1); break; }
		case FCT_INT16: { int16_t x = (int16_t)v; memcpy(raw, &x, 2); break; }
		case FCT_UINT16: { uint16_t x = (uint16_t)v; memcpy(raw, &x, 2); break; }
		case FCT_INT32: { int32_t x = (int32_t)v; memcpy(raw, &x, 4); break; }
		default: { uint32_t x = (uint32_t)v; memcpy(raw, &x, 4); break; }
		}
	}
	b->cur = (char *)end;
	return 0;
bad:;
	char what[160];
	size_t n = 0;
	while (!is_word_end(w[n]) && n < 40)
		n++;
	snprintf(what, sizeof what, "\"%.*s%s\" is not a %s", (int)n, w, is_word_end(w[n]) ? "" : "...",
	         fct_type_name(t));
	return body_fail(b, row, s, what);
}

static int read_ascii_elem(struct body *b)
{
	const struct helem *he = b->he;
	struct fct_mesh *m = b->m;
	if (!he->nprops && he->count)
		return fct_fail(b->err, "%s:%" PRIu64 ": element %s: %" PRIu64 " rows with no properties",
		                b->r->name, b->r->line, he->name, he->count);
	if (he->count > SIZE_MAX / 16)
		return fct_fail(b->err, "%s: element %s: count too large", b->r->name, he->name);
	size_t count = (size_t)he->count;
	/* Every value takes at least two bytes: a digit and a separator. */
	uint64_t left = fct_reader_remaining(b->r), rowmin = 2 * (uint64_t)he->nprops;
	size_t reserved = left != UINT64_MAX && rowmin && he->count <= left / rowmin + 1 ? count
	                  : (count < 4096 ? count : 4096);
	if (start_rows(b, reserved))
		return -1;
	for (size_t i = 0; i < count; i++) {
		if (i == reserved && grow_rows(b, count, &reserved))
			return -1;
		for (size_t j = 0; j < he->nprops; j++) {
			struct slot *s = &b->slots[j];
			double d;
			unsigned char raw[8];
			if (!s->count_type) {
				if (ascii_value(b, i, s, s->type, &d, raw))
					return -1;
				if (s->kind == SLOT_COLUMN) {
					memcpy((char *)s->col->data + i * s->size, raw, s->size);
				} else {
					if (s->type == FCT_FLOAT32)  /* the value is the float, as in binary */
						d = (float)d;
					if (check_position(b, i, s, d))
						return -1;
					m->xyz[3 * i + (s->kind - SLOT_X)] = d;
				}
				continue;
			}
			if (ascii_value(b, i, s, s->count_type, &d, raw))
				return -1;
			int64_t n = (int64_t)d;
			if (check_list_length(b, i, s, n))
				return -1;
			size_t used;
			size_t *off = list_offsets_used(b, s, i, &used);
			for (int64_t k = 0; k < n; k++) {
				if ((k & (LIST_BATCH - 1)) == 0 &&
				    reserve_items(b, s, used + (size_t)k, n - k < LIST_BATCH ? (size_t)(n - k) : LIST_BATCH))
					return -1;
				if (ascii_value(b, i, s, s->type, &d, raw))
					return -1;
				if (s->kind == SLOT_COLUMN) {
					memcpy((char *)s->col->data + (used + (size_t)k) * s->size, raw, s->size);
				} else {
					if (d != floor(d))
						return body_fail(b, i, s, "vertex index is not an integer");
					if (store_index(b, i, s, d < -1e18 ? -1 : d > 1e18 ? INT64_MAX : (int64_t)d,
					                used + (size_t)k))
						return -1;
				}
			}
			if (off)
				off[i + 1] = used + (size_t)n;
			else
				m->fstart[i + 1] = (uint32_t)(used + (size_t)n);
		}
	}
	return 0;
}

/* Give element he its destination columns in m and a slot per property. */
static int plan_elem(struct fct_mesh *m, const struct helem *he, struct slot *slots,
                     struct fct_elem **dest_out, const char *name, struct fct_err *err)
{
	int is_vertex = !strcmp(he->name, "vertex"), is_face = !strcmp(he->name, "face");
	struct fct_elem *dest;
	if (is_vertex)
		dest = &m->vertex;
	else if (is_face)
		dest = &m->face;
	else if (!(dest = fct_mesh_add_elem(m, he->name, 0, err)))
		return -1;
	*dest_out = dest;
	size_t ncols = 0;
	int have_face_list = 0;
	for (size_t j = 0; j < he->nprops; j++) {
		const struct hprop *hp = &he->props[j];
		struct slot *s = &slots[j];
		memset(s, 0, sizeof *s);
		s->kind = SLOT_COLUMN;
		s->type = hp->type;
		s->count_type = hp->count_type;
		s->size = fct_type_size(hp->type);
		s->count_size = fct_type_size(hp->count_type);
		s->name = hp->name;
		if (is_vertex && !hp->count_type && hp->name[0] >= 'x' && hp->name[0] <= 'z' && !hp->name[1]) {
			s->kind = (enum slot_kind)(SLOT_X + (hp->name[0] - 'x'));
			if (hp->type == FCT_FLOAT64)
				m->xyz_type = FCT_FLOAT64;
		} else if (is_face && hp->count_type && !have_face_list &&
		           (!strcmp(hp->name, "vertex_indices") || !strcmp(hp->name, "vertex_index"))) {
			if (hp->type == FCT_FLOAT32 || hp->type == FCT_FLOAT64)
				return fct_fail(err, "%s: element face: property %s: index type %s is not an integer type",
				                name, hp->name, fct_type_name(hp->type));
			s->kind = SLOT_FACE;
			have_face_list = 1;
			m->fcount_type = hp->count_type;
			m->findex_type = hp->type;
		} else {
			ncols++;
		}
	}
	if (is_face && !have_face_list)
		return fct_fail(err, "%s: element face has no vertex_indices list", name);
	if (ncols && !(dest->props = calloc(ncols, sizeof *dest->props)))
		return fct_fail(err, "out of memory");
	for (size_t j = 0; j < he->nprops; j++) {
		struct slot *s = &slots[j];
		if (s->kind != SLOT_COLUMN)
			continue;
		struct fct_prop *p = &dest->props[dest->nprops];
		if (!(p->name = fct_strdup(s->name, err)))
			return -1;
		p->type = s->type;
		p->count_type = s->count_type;
		dest->nprops++;
		s->col = p;
	}
	return 0;
}

int fct_ply_read(struct fct_mesh *m, struct fct_reader *r, enum fct_ply_format *fmt,
                 struct fct_err *err)
{
	struct header h = {0};
	struct slot *slots = NULL;
	int rc = -1, have_vertex = 0;
	err->msg[0] = 0;
	if (parse_header(&h, m, r, err))
		goto out;
	if (fmt)
		*fmt = h.fmt;
	for (size_t i = 0; i < h.nelems; i++) {
		const struct helem *he = &h.elems[i];
		if (!strcmp(he->name, "vertex")) {
			int seen[3] = {0};
			for (size_t j = 0; j < he->nprops; j++) {
				const char *n = he->props[j].name;
				if (!he->props[j].count_type && n[0] >= 'x' && n[0] <= 'z' && !n[1])
					seen[n[0] - 'x'] = 1;
			}
			if (!seen[0] || !seen[1] || !seen[2]) {
				fct_fail(err, "%s: element vertex lacks x, y or z", r->name);
				goto out;
			}
			have_vertex = 1;
		}
	}
	if (!have_vertex) {
		fct_fail(err, "%s: no vertex element", r->name);
		goto out;
	}
	for (size_t i = 0; i < h.nelems; i++) {
		const struct helem *he = &h.elems[i];
		struct body b = {.m = m, .r = r, .err = err, .he = he};
		free(slots);
		if (!(slots = calloc(he->nprops ? he->nprops : 1, sizeof *slots))) {
			fct_fail(err, "out of memory");
			goto out;
		}
		b.slots = slots;
		b.swap = (h.fmt == FCT_PLY_BINARY_BE) != host_is_big_endian();
		if (plan_elem(m, he, slots, &b.dest, r->name, err))
			goto out;
		if (!strcmp(he->name, "face"))
			m->has_faces = 1;
		if (h.fmt == FCT_PLY_ASCII) {
			char empty[1] = "";
			b.cur = empty;
			rc = read_ascii_elem(&b);
			/* the next element continues on the same line only in odd files; keep it simple */
			if (!rc && b.cur && *b.cur) {
				char *rest = b.cur;
				while (*rest == ' ' || *rest == '\t' || *rest == '\r')
					rest++;
				if (*rest)
					rc = body_fail(&b, he->count, NULL, "more values on a row than its properties");
			}
		} else {
			rc = read_binary_elem(&b);
		}
		if (rc)
			goto out;
		rc = -1;
		b.dest->count = (size_t)he->count;
		if (!strcmp(he->name, "vertex"))
			m->nv = (size_t)he->count;
		else if (!strcmp(he->name, "face"))
			m->nf = (size_t)he->count;
	}
	/* Anything after the last element means the counts lied. */
	if (h.fmt == FCT_PLY_ASCII) {
		size_t len;
		char *line;
		while ((line = fct_reader_line(r, &len, err))) {
			line += strspn(line, " \t\r\f\v");
			if (*line) {
				fct_fail(err, "%s:%" PRIu64 ": data after the last element", r->name, r->line);
				goto out;
			}
		}
		if (err->msg[0])
			goto out;
	} else if (fct_reader_fill(r, 1)) {
		fct_fail(err, "%s: byte %" PRIu64 ": data after the last element", r->name, fct_reader_offset(r));
		goto out;
	} else if (r->ioerr) {
		fct_reader_fail_short(r, err, "reading");
		goto out;
	}
	if (fct_grow((void **)&m->fstart, &m->fstart_cap, m->nf + 1, sizeof *m->fstart, err))
		goto out;
	m->fstart[0] = 0;
	uint32_t maxv = 0;
	for (size_t k = 0; k < m->fstart[m->nf]; k++)
		maxv = m->fvert[k] > maxv ? m->fvert[k] : maxv;
	for (size_t f = 0; maxv >= m->nv && f < m->nf; f++)
		for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++)
			if (m->fvert[k] >= m->nv) {
				fct_fail(err, "%s: element face %zu: vertex index %" PRIu32 " out of range (%zu vertices)",
				         r->name, f, m->fvert[k], m->nv);
				goto out;
			}
	rc = 0;
out:
	free(slots);
	header_free(&h);
	if (rc)
		fct_mesh_free(m);
	return rc;
}

/* Writer ------------------------------------------------------------------- */

struct wbuf {
	FILE *f;
	unsigned char *buf;
	size_t n, cap;
	int swap;
	int failed;
};

static void wflush(struct wbuf *w)
{
	if (w->n && fwrite(w->buf, 1, w->n, w->f) != w->n)
		w->failed = 1;
	w->n = 0;
}

static inline unsigned char *wreserve(struct wbuf *w, size_t n)
{
	if (w->cap - w->n < n)
		wflush(w);
	return w->buf + w->n;
}

/* Append one value of type t, converted from d. */
static inline void wvalue(struct wbuf *w, enum fct_type t, double d)
{
	union { int8_t i8; uint8_t u8; int16_t i16; uint16_t u16; int32_t i32; uint32_t u32; float f; double d; } v;
	switch (t) {
	case FCT_INT8: v.i8 = (int8_t)d; break;
	case FCT_UINT8: v.u8 = (uint8_t)d; break;
	case FCT_INT16: v.i16 = (int16_t)d; break;
	case FCT_UINT16: v.u16 = (uint16_t)d; break;
	case FCT_INT32: v.i32 = (int32_t)d; break;
	case FCT_UINT32: v.u32 = (uint32_t)d; break;
	case FCT_FLOAT32: v.f = (float)d; break;
	default: v.d = d; break;
	}
	size_t sz = fct_type_size(t);
	load_raw(wreserve(w, sz), (const unsigned char *)&v, sz, w->swap);
	w->n += sz;
}

static inline void wraw(struct wbuf *w, const void *src, size_t sz)
{
	load_raw(wreserve(w, sz), src, sz, w->swap);
	w->n += sz;
}

/* The smallest list count type at least as wide as `want` that holds n. */
static enum fct_type count_type_for(enum fct_type want, uint64_t n)
{
	static const uint64_t max[] = {0, INT8_MAX, UINT8_MAX, INT16_MAX, UINT16_MAX, INT32_MAX, UINT32_MAX};
	if (want >= FCT_INT8 && want <= FCT_UINT32 && n <= max[want])
		return want;
	return n <= INT32_MAX ? FCT_INT32 : FCT_UINT32;
}

/* Largest row length of list column p (0 for no rows). */
static size_t max_list_length(const struct fct_prop *p, size_t count)
{
	size_t mx = 0;
	for (size_t i = 0; i < count; i++)
		if (p->off[i + 1] - p->off[i] > mx)
			mx = p->off[i + 1] - p->off[i];
	return mx;
}


/* The count type a list column is written with: its own, widened when a row
 * has grown longer than that type can say. */
static enum fct_type list_count_type(const struct fct_prop *p, size_t count)
{
	return count_type_for(p->count_type, max_list_length(p, count));
}

/* Write row i of every column of e, binary; ct[j] is column j's count type. */
static void write_columns_binary(struct wbuf *w, const struct fct_elem *e, size_t i,
                                 const enum fct_type *ct)
{
	for (size_t j = 0; j < e->nprops; j++) {
		const struct fct_prop *p = &e->props[j];
		size_t sz = fct_type_size(p->type);
		if (!p->count_type) {
			wraw(w, (const char *)p->data + i * sz, sz);
			continue;
		}
		size_t k0 = p->off[i], k1 = p->off[i + 1];
		wvalue(w, ct[j], (double)(k1 - k0));
		for (size_t k = k0; k < k1; k++)
			wraw(w, (const char *)p->data + k * sz, sz);
	}
}

/* Binary rows of a fixed size, written a chunk of rows at a time one column
 * after the other, in host byte order: a vertex (x y z and scalars) or a
 * triangle (count 3, three 32-bit indices, scalars).  Per row and per value,
 * write_columns_binary's calls and the type switch took a third of what
 * dm2mesh spent writing a 640x480 frame's mesh. */

/* n values of sz bytes from src to dst, stride bytes apart there. */
static void scatter_column(unsigned char *dst, size_t stride, const unsigned char *src, size_t sz,
                           size_t n)
{
	switch (sz) {   /* constant sizes: moves, not calls */
	case 1:
		for (size_t i = 0; i < n; i++)
			dst[i * stride] = src[i];
		break;
	case 2:
		for (size_t i = 0; i < n; i++)
			memcpy(dst + i * stride, src + 2 * i, 2);
		break;
	case 4:
		for (size_t i = 0; i < n; i++)
			memcpy(dst + i * stride, src + 4 * i, 4);
		break;
	default:
		for (size_t i = 0; i < n; i++)
			memcpy(dst + i * stride, src + 8 * i, 8);
	}
}

/* Does every column of e hold scalars? */
static int all_scalar(const struct fct_elem *e)
{
	for (size_t j = 0; j < e->nprops; j++)
		if (e->props[j].count_type)
			return 0;
	return 1;
}

/* The scalar columns of e, rows [i, i + n), into rows of stride bytes
 * starting at offset `at` of d. */
static void scatter_scalars(unsigned char *d, size_t stride, size_t at, const struct fct_elem *e,
                            size_t i, size_t n)
{
	for (size_t j = 0; j < e->nprops; j++) {
		const struct fct_prop *p = &e->props[j];
		size_t sz = fct_type_size(p->type);
		scatter_column(d + at, stride, (const unsigned char *)p->data + i * sz, sz, n);
		at += sz;
	}
}

/* The row size of e's scalar columns. */
static size_t scalars_size(const struct fct_elem *e)
{
	size_t n = 0;
	for (size_t j = 0; j < e->nprops; j++)
		n += fct_type_size(e->props[j].type);
	return n;
}

/* Does a row of `fixed` bytes and e's scalar columns fit w's buffer? */
static int row_fits(const struct wbuf *w, const struct fct_elem *e, size_t fixed)
{
	return fixed + scalars_size(e) <= w->cap;
}

/* The vertices, positions as float or double, then the scalar columns. */
static void write_vertices_fast(struct wbuf *w, const struct fct_mesh *m, int dbl)
{
	size_t xs = dbl ? 24 : 12, stride = xs + scalars_size(&m->vertex);
	size_t chunk = w->cap / stride;
	for (size_t i = 0; i < m->nv && !w->failed; i += chunk) {
		size_t n = m->nv - i < chunk ? m->nv - i : chunk;
		unsigned char *d = wreserve(w, n * stride);
		const double *p = m->xyz + 3 * i;
		if (dbl)
			for (size_t k = 0; k < n; k++)
				memcpy(d + k * stride, p + 3 * k, 24);
		else
			for (size_t k = 0; k < n; k++) {
				float v[3] = {(float)p[3 * k], (float)p[3 * k + 1], (float)p[3 * k + 2]};
				memcpy(d + k * stride, v, 12);
			}
		scatter_scalars(d, stride, xs, &m->vertex, i, n);
		w->n += n * stride;
	}
}

/* The faces, all triangles: count 3 as uchar, 32-bit indices, then the
 * scalar columns. */
static void write_triangles_fast(struct wbuf *w, const struct fct_mesh *m)
{
	size_t stride = 13 + scalars_size(&m->face), chunk = w->cap / stride;
	for (size_t i = 0; i < m->nf && !w->failed; i += chunk) {
		size_t n = m->nf - i < chunk ? m->nf - i : chunk;
		unsigned char *d = wreserve(w, n * stride);
		const uint32_t *v = m->fvert + 3 * i;
		for (size_t k = 0; k < n; k++) {
			d[k * stride] = 3;
			memcpy(d + k * stride + 1, v + 3 * k, 12);
		}
		scatter_scalars(d, stride, 13, &m->face, i, n);
		w->n += n * stride;
	}
}

/* Numbers in ascii PLY: the shortest form that reads back exactly. */
static void print_float(FILE *f, float v)
{
	char buf[40];
	fct_format_float(buf, sizeof buf, v);
	fputs(buf, f);
}

static void print_double(FILE *f, double v)
{
	char buf[40];
	fct_format_double(buf, sizeof buf, v);
	fputs(buf, f);
}

static void print_value(FILE *f, const struct fct_prop *p, size_t k)
{
	const void *d = p->data;
	switch (p->type) {
	case FCT_INT8: fprintf(f, "%d", ((const int8_t *)d)[k]); break;
	case FCT_UINT8: fprintf(f, "%u", ((const uint8_t *)d)[k]); break;
	case FCT_INT16: fprintf(f, "%d", ((const int16_t *)d)[k]); break;
	case FCT_UINT16: fprintf(f, "%u", ((const uint16_t *)d)[k]); break;
	case FCT_INT32: fprintf(f, "%" PRId32, ((const int32_t *)d)[k]); break;
	case FCT_UINT32: fprintf(f, "%" PRIu32, ((const uint32_t *)d)[k]); break;
	case FCT_FLOAT32: print_float(f, ((const float *)d)[k]); break;
	case FCT_FLOAT64: print_double(f, ((const double *)d)[k]); break;
	default: abort();
	}
}

static void write_columns_ascii(FILE *f, const struct fct_elem *e, size_t i, int first)
{
	for (size_t j = 0; j < e->nprops; j++) {
		const struct fct_prop *p = &e->props[j];
		if (!first)
			putc(' ', f);
		first = 0;
		if (!p->count_type) {
			print_value(f, p, i);
			continue;
		}
		fprintf(f, "%zu", p->off[i + 1] - p->off[i]);
		for (size_t k = p->off[i]; k < p->off[i + 1]; k++) {
			putc(' ', f);
			print_value(f, p, k);
		}
	}
}

static void write_prop_decls(FILE *f, const struct fct_elem *e, const enum fct_type *ct)
{
	for (size_t j = 0; j < e->nprops; j++) {
		const struct fct_prop *p = &e->props[j];
		if (p->count_type)
			fprintf(f, "property list %s %s %s\n", fct_type_name(ct[j]), fct_type_name(p->type), p->name);
		else
			fprintf(f, "property %s %s\n", fct_type_name(p->type), p->name);
	}
}

/* Count types of every list column of e, freshly allocated (NULL on no memory). */
static enum fct_type *elem_count_types(const struct fct_elem *e)
{
	enum fct_type *ct = calloc(e->nprops ? e->nprops : 1, sizeof *ct);
	if (ct)
		for (size_t j = 0; j < e->nprops; j++)
			if (e->props[j].count_type)
				ct[j] = list_count_type(&e->props[j], e->count);
	return ct;
}

typedef uint32_t v4u __attribute__((vector_size(16)));

/* Is every face of m a triangle?  The header's count type needs the
 * largest face before a byte is written, and one face at a time the scan
 * of fstart was 0.2 ms of dm2mesh's 1.7 ms write of a 640x480 frame (534k
 * faces); four a step with GCC's and Clang's vector extension. */
static int all_triangles(const struct fct_mesh *m)
{
	const v4u three = {3, 3, 3, 3};
	v4u off = {0, 0, 0, 0};
	size_t i = 0;
	for (; i + 4 <= m->nf; i += 4) {
		v4u lo, hi;
		memcpy(&lo, m->fstart + i, sizeof lo);
		memcpy(&hi, m->fstart + i + 1, sizeof hi);
		off |= (hi - lo) ^ three;
	}
	uint32_t any = off[0] | off[1] | off[2] | off[3];
	for (; i < m->nf; i++)
		any |= fct_face_size(m, i) ^ 3;
	return !any;
}

int fct_ply_write(const struct fct_mesh *m, FILE *f, enum fct_ply_format fmt, struct fct_err *err)
{
	static const char *fmt_name[] = {"ascii", "binary_little_endian", "binary_big_endian"};
	size_t maxface = 0;
	if (m->nf && all_triangles(m))
		maxface = 3;
	else
		for (size_t i = 0; i < m->nf; i++)
			if (fct_face_size(m, i) > maxface)
				maxface = fct_face_size(m, i);
	enum fct_type ctype = count_type_for(m->fcount_type, maxface);
	enum fct_type itype = count_type_for(m->findex_type, m->nv ? m->nv - 1 : 0);
	int faces = m->has_faces || m->nf;

	/* The columns in writing order: vertex extras, face extras, other elements. */
	size_t ne = 2 + m->nelems;
	const struct fct_elem **el = calloc(ne, sizeof *el);
	enum fct_type **ct = calloc(ne, sizeof *ct);
	int rc = -1;
	if (!el || !ct)
		goto oom;
	el[0] = &m->vertex, el[1] = &m->face;
	for (size_t e = 0; e < m->nelems; e++)
		el[2 + e] = &m->elems[e];
	for (size_t e = 0; e < ne; e++)
		if (!(ct[e] = elem_count_types(el[e])))
			goto oom;

	/* Lines that cannot be shortened (a camera, a texture's path) and are
	 * too long for MeshLab or Open3D: refused before a byte is written. */
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *key = m->comments[i].obj_info ? "obj_info" : "comment";
		char line[FCT_HEADER_LINE_MAX + 64];
		const char *text = fct_comment_line(&m->comments[i], FCT_HEADER_LINE_MAX - strlen(key) - 1, line);
		size_t n = strlen(key) + 1 + strlen(text);
		if (n > FCT_HEADER_LINE_MAX) {
			fct_fail(err, "header line \"%s %.24s...\": %zu bytes, over the %d that MeshLab and "
			         "Open3D read (a shorter texture path?)", key, text, n, FCT_HEADER_LINE_MAX);
			goto out;
		}
	}
	fprintf(f, "ply\nformat %s 1.0\n", fmt_name[fmt]);
	for (size_t i = 0; i < m->ncomments; i++) {
		const char *key = m->comments[i].obj_info ? "obj_info" : "comment";
		char line[FCT_HEADER_LINE_MAX + 64];
		fprintf(f, "%s %s\n", key, fct_comment_line(&m->comments[i],
		        FCT_HEADER_LINE_MAX - strlen(key) - 1, line));
	}
	const char *xt = fct_type_name(m->xyz_type == FCT_FLOAT64 ? FCT_FLOAT64 : FCT_FLOAT32);
	fprintf(f, "element vertex %zu\nproperty %s x\nproperty %s y\nproperty %s z\n", m->nv, xt, xt, xt);
	write_prop_decls(f, el[0], ct[0]);
	if (faces) {
		fprintf(f, "element face %zu\nproperty list %s %s vertex_indices\n", m->nf,
		        fct_type_name(ctype), fct_type_name(itype));
		write_prop_decls(f, el[1], ct[1]);
	}
	for (size_t e = 2; e < ne; e++) {
		fprintf(f, "element %s %zu\n", el[e]->name, el[e]->count);
		write_prop_decls(f, el[e], ct[e]);
	}
	fputs("end_header\n", f);

	if (fmt == FCT_PLY_ASCII) {
		int dbl = m->xyz_type == FCT_FLOAT64;
		for (size_t i = 0; i < m->nv; i++) {
			const double *p = m->xyz + 3 * i;
			for (int k = 0; k < 3; k++) {
				if (k)
					putc(' ', f);
				if (dbl)
					print_double(f, p[k]);
				else
					print_float(f, (float)p[k]);
			}
			write_columns_ascii(f, el[0], i, 0);
			putc('\n', f);
		}
		for (size_t i = 0; i < m->nf; i++) {
			fprintf(f, "%" PRIu32, fct_face_size(m, i));
			for (uint32_t k = m->fstart[i]; k < m->fstart[i + 1]; k++)
				fprintf(f, " %" PRIu32, m->fvert[k]);
			write_columns_ascii(f, el[1], i, 0);
			putc('\n', f);
		}
		for (size_t e = 2; e < ne; e++)
			for (size_t i = 0; i < el[e]->count; i++) {
				write_columns_ascii(f, el[e], i, 1);
				putc('\n', f);
			}
	} else {
		struct wbuf w = {f, NULL, 0, 1 << 16, (fmt == FCT_PLY_BINARY_BE) != host_is_big_endian(), 0};
		if (!(w.buf = malloc(w.cap)))
			goto oom;
		int dbl = m->xyz_type == FCT_FLOAT64;
		int fast = !w.swap && all_scalar(el[0]) && row_fits(&w, el[0], dbl ? 24 : 12);
		for (size_t i = 0; i < m->nv && !w.failed && !fast; i++) {
			const double *p = m->xyz + 3 * i;
			if (!dbl && !w.swap) {  /* the rule: constant-size stores */
				float v[3] = {(float)p[0], (float)p[1], (float)p[2]};
				memcpy(wreserve(&w, 12), v, 12);
				w.n += 12;
			} else if (dbl) {
				wraw(&w, &p[0], 8), wraw(&w, &p[1], 8), wraw(&w, &p[2], 8);
			} else {
				float v[3] = {(float)p[0], (float)p[1], (float)p[2]};
				wraw(&w, &v[0], 4), wraw(&w, &v[1], 4), wraw(&w, &v[2], 4);
			}
			write_columns_binary(&w, el[0], i, ct[0]);
		}
		if (fast)
			write_vertices_fast(&w, m, dbl);
		fast = !w.swap && ctype == FCT_UINT8 && (itype == FCT_INT32 || itype == FCT_UINT32) &&
		       maxface == 3 && m->fstart[m->nf] == 3 * m->nf && all_scalar(el[1]) &&
		       row_fits(&w, el[1], 13);
		if (fast)
			write_triangles_fast(&w, m);
		for (size_t i = 0; i < m->nf && !w.failed && !fast; i++) {
			uint32_t n = fct_face_size(m, i);
			if (ctype == FCT_UINT8 && (itype == FCT_INT32 || itype == FCT_UINT32) && !w.swap) {
				unsigned char *d = wreserve(&w, 1 + 4 * (size_t)n);
				*d = (unsigned char)n;
				if (n == 3)   /* a constant size: a move, not a call */
					memcpy(d + 1, m->fvert + m->fstart[i], 12);
				else
					memcpy(d + 1, m->fvert + m->fstart[i], 4 * (size_t)n);
				w.n += 1 + 4 * (size_t)n;
				write_columns_binary(&w, el[1], i, ct[1]);
				continue;
			}
			wvalue(&w, ctype, n);
			if (itype == FCT_INT32 || itype == FCT_UINT32) {
				for (uint32_t k = m->fstart[i]; k < m->fstart[i + 1]; k++)
					wraw(&w, &m->fvert[k], 4);
			} else {
				for (uint32_t k = m->fstart[i]; k < m->fstart[i + 1]; k++)
					wvalue(&w, itype, m->fvert[k]);
			}
			write_columns_binary(&w, el[1], i, ct[1]);
		}
		for (size_t e = 2; e < ne; e++)
			for (size_t i = 0; i < el[e]->count && !w.failed; i++)
				write_columns_binary(&w, el[e], i, ct[e]);
		wflush(&w);
		free(w.buf);
	}
	if (ferror(f))
		fct_fail(err, "write error: %s", strerror(errno ? errno : EIO));
	else
		rc = 0;
	goto out;
oom:
	fct_fail(err, "out of memory");
out:
	if (ct)
		for (size_t e = 0; e < ne; e++)
			free(ct[e]);
	free(ct);
	free(el);
	return rc;
}

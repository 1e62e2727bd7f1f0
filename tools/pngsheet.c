/* pngsheet - several pictures side by side on one contact sheet, each with
 * a caption, in the style of the figures of Kang, Johnson and Szeliski (DEC
 * CRL 95/7); and, with -d, the per-pixel comparison of two pictures within a
 * tolerance that the golden-picture tests use. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "io/image.h"
#include "io/output.h"
#include "core/path.h"
#include "render/raster.h"

static const char usage[] =
	"usage: pngsheet [-qv] [-b pixels] [-c columns] [-o file] [--bg r,g,b]\n"
	"                [--title text] image[=caption] ...\n"
	"       pngsheet -d tolerance A B\n"
	"Put PNG, JPEG, PFM or PNM pictures side by side on one PNG contact sheet, in\n"
	"rows of equal cells, each with its caption (default the file name) below it.\n"
	"The sheet may have at most 32768 pixels a side and 2^28 in all.\n"
	"  -b pixels       border between cells and around them (default 8)\n"
	"  -c columns      pictures per row (default: as square a sheet as may be)\n"
	"  -d tolerance    compare pictures A and B instead: exit 0 when every\n"
	"                  sample differs by at most tolerance (0-255), 1 otherwise\n"
	"  -o file         the sheet (default standard output)\n"
	"  -q              quiet\n"
	"  -v              report sizes on stderr (with -d: the figures)\n"
	"      --bg r,g,b  background colour, 0-255 each (default 255,255,255)\n"
	"      --title text     a title above the cells\n"
	"  -h, --help      this help\n"
	"      --version   print the version\n";

/* The largest sheet, and so the largest picture: 2^28 pixels (768 MB of
 * RGB), no side over 32768. */
#define SHEET_MAX_SIDE 32768
#define SHEET_MAX_PIXELS ((size_t)1 << 28)

struct cell {
	char *path;
	const char *caption;
	struct fct_image img;    /* RGB U8; before decoding, only the shape */
};

/* Read the picture at path as 8-bit RGB over bg, refusing before decoding
 * one of more than max_pixels pixels. */
static int read_rgb(const char *path, const unsigned char bg[3], size_t max_pixels,
                    struct fct_image *img)
{
	struct fct_err err;
	struct fct_image raw;
	if (fct_image_read_file_max(&raw, path, max_pixels, NULL, &err) ||
	    fct_image_to_rgb8(&raw, bg, img, &err)) {
		fct_image_free(&raw);
		fct_die_err(&err);
	}
	fct_image_free(&raw);
	return 0;
}

/* -d: 0 when A and B agree within tol, else a one-line message and 1. */
static int compare(const char *a, const char *b, double tol)
{
	static const unsigned char white[3] = { 255, 255, 255 };
	struct fct_image ia, ib;
	read_rgb(a, white, SHEET_MAX_PIXELS, &ia);
	read_rgb(b, white, SHEET_MAX_PIXELS, &ib);
	if (ia.width != ib.width || ia.height != ib.height)
		fct_die(1, "%s %s: sizes differ (%dx%d and %dx%d)", fct_path_display(a),
		        fct_path_display(b), ia.width, ia.height, ib.width, ib.height);
	size_t n = (size_t)ia.width * (size_t)ia.height, bad = 0;
	int maxd = 0;
	const unsigned char *pa = ia.data, *pb = ib.data;
	for (size_t i = 0; i < n; i++) {
		int worst = 0;
		for (int k = 0; k < 3; k++) {
			int d = abs(pa[3 * i + k] - pb[3 * i + k]);
			worst = d > worst ? d : worst;
		}
		maxd = worst > maxd ? worst : maxd;
		bad += worst > tol;
	}
	fct_report("pixels", "%zu", n);
	fct_report("differing", "%zu", bad);
	fct_report("max_diff", "%d", maxd);
	fct_image_free(&ia);
	fct_image_free(&ib);
	if (bad)
		fct_die(1, "%s %s: %zu of %zu pixels differ by more than %g (at most %d)",
		        fct_path_display(a), fct_path_display(b), bad, n, tol, maxd);
	return 0;
}

int main(int argc, char **argv)
{
	enum { BG = 256, TITLE, VERSION };
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, VERSION},
		{"bg", required_argument, NULL, BG}, {"title", required_argument, NULL, TITLE},
		{NULL, 0, NULL, 0},
	};
	static const char optstring[] = "b:c:d:ho:qv";
	fct_cli_init("pngsheet");
	const char *out = NULL, *title = NULL;
	long border = 8, cols = 0;
	double tol = -1, v[3];
	unsigned char bg[3] = { 255, 255, 255 };
	int c;
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'b': border = fct_opt_long("-b", optarg, 0, 1000); break;
		case 'c': cols = fct_opt_long("-c", optarg, 1, 1000); break;
		case 'd': tol = fct_opt_double("-d", optarg, 0, 255); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'o': out = optarg; break;
		case 'q': fct_quiet = 1; break;
		case 'v': fct_verbose = 1; break;
		case BG:
			fct_opt_doubles("--bg", optarg, v, 3);
			for (int k = 0; k < 3; k++) {
				if (!(v[k] >= 0 && v[k] <= 255))
					fct_usage_error("--bg: \"%s\": each value must be in [0, 255]", optarg);
				bg[k] = (unsigned char)lround(v[k]);
			}
			break;
		case TITLE: title = optarg; break;
		case VERSION: puts("pngsheet (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	int n = argc - optind;
	if (tol >= 0) {
		if (n != 2)
			fct_usage_error("-d: two pictures A and B are needed");
		return compare(argv[optind], argv[optind + 1], tol);
	}
	if (n < 1)
		fct_usage_error("no pictures");
	if (n > 10000)
		fct_usage_error("too many pictures (at most 10000)");
	struct fct_err err;
	struct cell *cells = fct_alloc_array((size_t)n, sizeof *cells, &err);
	if (!cells)
		fct_die_err(&err);
	int cw = 1, ch = 1;
	for (int i = 0; i < n; i++) {
		const char *arg = argv[optind + i];
		struct stat st;
		const char *eq = strrchr(arg, '=');
		cells[i].path = fct_strdup(arg, &err);
		if (!cells[i].path)
			fct_die_err(&err);
		if (eq && stat(arg, &st) != 0) {       /* image=caption, unless that is a file's name */
			cells[i].path[eq - arg] = 0;
			cells[i].caption = eq + 1;
		} else {
			const char *slash = strrchr(arg, '/');
			cells[i].caption = slash ? slash + 1 : arg;
		}
		if (fct_path_is_std(cells[i].path))
			fct_usage_error("the pictures must be files");
		/* The shapes first: the sheet's size is checked before any picture
		 * is decoded. */
		if (fct_image_probe_file(&cells[i].img, cells[i].path, NULL, &err))
			fct_die_err(&err);
		cw = cells[i].img.width > cw ? cells[i].img.width : cw;
		ch = cells[i].img.height > ch ? cells[i].img.height : ch;
	}
	if (!cols)
		for (cols = 1; cols * cols < n; cols++)
			;
	long rows = (n + cols - 1) / cols;
	int scale = ch >= 300 ? 2 : 1;
	int caph = 11 * scale, tw = 0, th = 0;
	if (title)
		fct_text_size(title, 2 * scale, &tw, &th);
	double W = (double)cols * (cw + border) + border;
	double H = (double)rows * (ch + caph + border) + border + (title ? th + border : 0);
	if (W > SHEET_MAX_SIDE || H > SHEET_MAX_SIDE || W * H > (double)SHEET_MAX_PIXELS)
		fct_die(1, "the sheet would be %.0fx%.0f pixels, over %d a side or 2^28 in all; "
		        "use smaller pictures or -c", W, H, SHEET_MAX_SIDE);
	for (int i = 0; i < n; i++)
		read_rgb(cells[i].path, bg, (size_t)cells[i].img.width * (size_t)cells[i].img.height,
		         &cells[i].img);
	struct fct_image sheet;
	if (fct_image_alloc(&sheet, (int)W, (int)H, 3, FCT_PIX_U8, &err))
		fct_die_err(&err);
	fct_draw_rect(&sheet, 0, 0, sheet.width, sheet.height, bg);
	unsigned char ink[3];
	int lum = (299 * bg[0] + 587 * bg[1] + 114 * bg[2]) / 1000;
	ink[0] = ink[1] = ink[2] = lum > 128 ? 0 : 255;
	int top = (int)border;
	if (title) {
		fct_draw_text(&sheet, ((int)W - tw) / 2, top, 2 * scale, ink, title);
		top += th + (int)border;
	}
	for (int i = 0; i < n; i++) {
		int x0 = (int)border + (int)(i % cols) * (cw + (int)border);
		int y0 = top + (int)(i / cols) * (ch + caph + (int)border);
		const struct fct_image *im = &cells[i].img;
		int ox = x0 + (cw - im->width) / 2, oy = y0 + (ch - im->height) / 2;
		unsigned char *dst = sheet.data;
		const unsigned char *src = im->data;
		for (int y = 0; y < im->height; y++)
			memcpy(dst + 3 * ((size_t)(oy + y) * (size_t)sheet.width + (size_t)ox),
			       src + 3 * (size_t)y * (size_t)im->width, 3 * (size_t)im->width);
		int w, h;
		fct_text_size(cells[i].caption, scale, &w, &h);
		fct_draw_text(&sheet, x0 + (cw - w) / 2 > x0 ? x0 + (cw - w) / 2 : x0, y0 + ch + 3 * scale,
		              scale, ink, cells[i].caption);
	}
	fct_write_image_or_die(&sheet, out);
	fct_report("pictures", "%d", n);
	fct_report("size", "%dx%d", sheet.width, sheet.height);
	fct_report("cell", "%dx%d", cw, ch);
	for (int i = 0; i < n; i++) {
		fct_image_free(&cells[i].img);
		free(cells[i].path);
	}
	free(cells);
	fct_image_free(&sheet);
	return 0;
}

/* imginfo - describe PNG and PFM images: shape, sample type, and per channel
 * the range and mean of the finite samples and how many are zero or not
 * finite (the "no data" of a depth map). */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "io/image.h"
#include "core/path.h"

static const char usage[] =
	"usage: imginfo [-h] [--version] [file ...]\n"
	"Describe PNG and PFM images (detected from the content; stdin when no\n"
	"file is given, or for \"-\"): format, width, height, channels, sample type,\n"
	"and per channel the minimum, maximum and mean of the finite samples and\n"
	"the number of zero and of non-finite samples.\n"
	"  -h, --help    this help\n"
	"      --version print the version\n";

struct stats {
	double min, max, sum;
	uint64_t finite, zero, nonfinite;
};

/* Per-channel figures over every pixel, in pixel order (deterministic). */
static void channel_stats(const struct fct_image *img, int c, struct stats *s)
{
	memset(s, 0, sizeof *s);
	s->min = INFINITY;
	s->max = -INFINITY;
	size_t n = fct_image_samples(img);
	for (size_t i = (size_t)c; i < n; i += (size_t)img->channels) {
		double v = fct_image_sample(img, i);
		if (!isfinite(v)) {
			s->nonfinite++;
			continue;
		}
		s->finite++;
		s->zero += v == 0;
		s->sum += v;
		if (v < s->min)
			s->min = v;
		if (v > s->max)
			s->max = v;
	}
}

static void print_image(const char *name, const struct fct_image *img,
                        enum fct_image_format fmt)
{
	printf("file %s\n", name);
	printf("format %s\n", fct_image_format_name(fmt));
	printf("width %d\n", img->width);
	printf("height %d\n", img->height);
	printf("channels %d\n", img->channels);
	printf("type %s\n", fct_pix_name(img->type));
	for (int c = 0; c < img->channels; c++) {
		struct stats s;
		channel_stats(img, c, &s);
		printf("channel %d", c);
		if (s.finite)
			printf(" min %.17g max %.17g mean %.17g", s.min, s.max,
			       s.sum / (double)s.finite);
		else
			printf(" min nan max nan mean nan");
		printf(" zero %llu nonfinite %llu\n", (unsigned long long)s.zero,
		       (unsigned long long)s.nonfinite);
	}
}

int main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"help", no_argument, NULL, 'h'},
		{"version", no_argument, NULL, 'V'},
		{NULL, 0, NULL, 0},
	};
	fct_cli_init("imginfo");
	int c;
	static const char optstring[] = "h";
	while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
		switch (c) {
		case 'h': fputs(usage, stdout); return 0;
		case 'V': puts("imginfo (facet) " FCT_VERSION); return 0;
		default: fct_bad_option(optstring, argv);
		}
	}
	const char *stdin_only[] = { "-" };
	const char **files = (const char **)argv + optind;
	int nfiles = argc - optind;
	if (nfiles == 0) {
		files = stdin_only;
		nfiles = 1;
	}
	for (int i = 0; i < nfiles; i++) {
		struct fct_err err;
		struct fct_image img;
		enum fct_image_format fmt;
		if (fct_image_read_file(&img, files[i], &fmt, &err))
			fct_die_err(&err);
		if (i)
			putchar('\n');
		print_image(fct_path_display(files[i]), &img, fmt);
		fct_image_free(&img);
	}
	if (fflush(stdout) || ferror(stdout))
		fct_die(1, "stdout: %s", strerror(errno));
	return 0;
}

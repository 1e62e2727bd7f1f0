/* fuzz_image - libFuzzer target: any bytes, read as an image through a
 * memory stream (the pipe path: no size known in advance), then freed.
 * A crash, leak, sanitizer report or huge allocation is a bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "io/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size == 0)
		return 0;  /* fmemopen refuses an empty buffer */
	FILE *f = fmemopen((void *)data, size, "rb");
	if (!f)
		return 0;
	struct fct_image img;
	struct fct_err err;
	if (fct_image_read_stream(&img, f, "fuzz", NULL, &err) == 0) {
		/* Touch every sample so a wrong size shows up under ASan. */
		double s = 0;
		size_t n = fct_image_samples(&img);
		for (size_t i = 0; i < n; i++)
			s += fct_image_sample(&img, i);
		(void)s;
		fct_image_free(&img);
	}
	fclose(f);
	return 0;
}

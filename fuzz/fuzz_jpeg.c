/* fuzz_jpeg - libFuzzer target for the JPEG path of the image reader: any
 * bytes after the JPEG signature (FF D8 FF), so no run is spent on other
 * formats, read through a memory stream (the pipe path: no size known in
 * advance).  A decoded image must be 8-bit grey or RGB, decode to the same
 * bytes twice (nothing uninitialised), and convert to RGB for texturing.  A
 * crash, leak, sanitizer report, huge allocation or a libjpeg exit() is a
 * bug. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image.h"
#include "render/raster.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int decode(const unsigned char *bytes, size_t n, struct fct_image *img)
{
	FILE *f = fmemopen((void *)bytes, n, "rb");
	if (!f)
		return -1;
	struct fct_err err;
	int rc = fct_image_read_stream(img, f, "fuzz", NULL, &err);
	fclose(f);
	return rc;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	unsigned char *bytes = malloc(size + 3);
	if (!bytes)
		return 0;
	memcpy(bytes, "\xff\xd8\xff", 3);
	memcpy(bytes + 3, data, size);
	struct fct_image img, again;
	if (decode(bytes, size + 3, &img) == 0) {
		if (img.type != FCT_PIX_U8 || (img.channels != 1 && img.channels != 3))
			abort();
		if (decode(bytes, size + 3, &again) != 0 ||
		    memcmp(img.data, again.data, fct_image_samples(&img)))
			abort();
		fct_image_free(&again);
		static const unsigned char black[3] = { 0, 0, 0 };
		struct fct_image rgb;
		struct fct_err err;
		if (fct_image_to_rgb8(&img, black, &rgb, &err) == 0)
			fct_image_free(&rgb);
		fct_image_free(&img);
	}
	free(bytes);
	return 0;
}

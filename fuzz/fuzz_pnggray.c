/* fuzz_pnggray - libFuzzer target: the plain grey PNG decoder over zlib
 * (io/pnggray.h) against libpng.  The input's chunk CRCs are made right
 * first (on a copy), so that mutations reach the zlib stream and the
 * filters instead of failing the CRC; whatever the decoder takes, libpng
 * must take too and give the same samples.  A difference aborts. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "../tests/unit/pngref.h"
#include "io/pnggray.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Each whole chunk's CRC set to what its type and data give. */
static void fix_crcs(unsigned char *b, size_t n)
{
	size_t pos = 8;
	while (pos < n && n - pos >= 12) {
		uint32_t len = (uint32_t)b[pos] << 24 | (uint32_t)b[pos + 1] << 16 |
		               (uint32_t)b[pos + 2] << 8 | b[pos + 3];
		if (len > n - pos - 12)
			return;
		uint32_t crc = (uint32_t)crc32(0, b + pos + 4, (uInt)len + 4);
		for (int i = 0; i < 4; i++)
			b[pos + 8 + len + (size_t)i] = (unsigned char)(crc >> (24 - 8 * i));
		pos += (size_t)len + 12;
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	unsigned char *b = malloc(size + 1);
	if (!b)
		return 0;
	memcpy(b, data, size);
	fix_crcs(b, size);
	struct fct_image fast, ref;
	if (fct_png_gray_decode(&fast, b, size, (size_t)1 << 22)) {
		size_t bytes = (size_t)fast.width * (size_t)fast.height * (fast.type == FCT_PIX_U16 ? 2 : 1);
		if (png_ref_decode(&ref, b, size) || ref.width != fast.width ||
		    ref.height != fast.height || ref.type != fast.type ||
		    memcmp(ref.data, fast.data, bytes))
			abort();
		free(ref.data);
		free(fast.data);
	}
	free(b);
	return 0;
}

/* libFuzzer target: the PLY reader (and writer), via the format detection. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	/* Keep the fuzzer on PLY: give every input the magic line. */
	uint8_t *buf = malloc(size + 4);
	if (!buf)
		return 0;
	size_t n = 0;
	int magic = (size >= 4 && !memcmp(data, "ply\n", 4)) || (size >= 5 && !memcmp(data, "ply\r\n", 5));
	if (!magic)
		memcpy(buf, "ply\n", 4), n = 4;
	memcpy(buf + n, data, size);
	fuzz_mesh_bytes(buf, n + size);
	free(buf);
	return 0;
}

/* libFuzzer target: the OBJ reader (and writer); inputs that look like PLY
 * are bent away from the PLY magic so the OBJ parser sees them. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size >= 3 && !memcmp(data, "ply", 3))
		return 0;
	fuzz_mesh_bytes(data, size);
	return 0;
}

#!/bin/sh
# mcubes: marching-cubes throughput beside a plain pass reading every sdf and
# weight of the same grid in the same run (medians); and the memory a sparse
# block grid needs for a room.  Goal: >= 150 M voxels/s on one core
# (scikit-image and Open3D reach 90-115 on this machine).
#
# What is counted: M vox/s is the voxels of the allocated 8^3 blocks (every
# voxel the extraction must look at) divided by the time; "band" divides the
# observed voxels only (weight > 0, the truncation band a fusion leaves).
# One thread is timed in CPU seconds (the machine is shared; CPU time is
# ours alone); the wall-clock rows compare 1 and 2 threads and suffer from
# whatever else runs.  Every run extracts into fresh memory, so the times
# include the page faults of the whole output (counted on each scene's line).
set -eu
: "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
row() { printf '%-58s %10s %10s\n' "$1" "$2" "$3"; }
fig() { sed -n "s/^$1=//p" "$2"; }
. bench/lib.sh
bench_dir mc

echo "marching cubes (fct_mcubes: shared vertices, gradient normals), medians of $RUNS runs"
row "what" "M vox/s" "seconds"
for scene in room dense; do
	"$FCT_BENCH/gen_mcubes" -r "$RUNS" -t 1 $scene >"$dir/$scene"
	"$FCT_BENCH/gen_mcubes" -r "$RUNS" -t 2 $scene >"$dir/$scene.2"
	f=$dir/$scene
	case $scene in
	room) what="room band 4x4x2.5 m at 1 cm, trunc 4 voxels" ;;
	dense) what="dense 256^3 volume, ball r = 100 voxels" ;;
	esac
	echo "$what: $(fig blocks "$f") blocks ($(fig voxels "$f") voxels, $(fig band_voxels "$f") observed)," \
		"$(fig vertices "$f") vertices, $(fig faces "$f") faces, grid $(fig grid_mb "$f") MB," \
		"$(fig mcubes_faults "$f") page faults, output FNV-1a $(fig mesh_fnv "$f")"
	[ "$(fig mesh_fnv "$f")" = "$(fig mesh_fnv "$f.2")" ] || echo "  WARNING: 1 and 2 threads give different meshes"
	row "  reference: one pass over sdf and weight (CPU)" "$(fig ref_mvox_s "$f")" "$(fig ref_s "$f")"
	row "  fct_mcubes, 1 thread (CPU)" "$(fig mcubes_mvox_s "$f")" "$(fig mcubes_s "$f")"
	row "  fct_mcubes, 1 thread (CPU), band voxels only" "$(fig mcubes_band_mvox_s "$f")" "$(fig mcubes_s "$f")"
	row "  fct_mcubes, 1 thread (wall)" "$(fig mcubes_wall_mvox_s "$f")" "$(fig mcubes_wall_s "$f")"
	row "  fct_mcubes, 2 threads (wall)" "$(fig mcubes_wall_mvox_s "$f.2")" "$(fig mcubes_wall_s "$f.2")"
	echo "  1 thread, ms per phase (wall): $(fig phase_ms "$f" | awk '{ printf "pass 0 %s, pass 1 %s, pass 2 %s, allocation %s, vertices %s, triangles %s", $1, $2, $3, $4, $5, $6 }')"
done
"$FCT_BENCH/gen_mcubes" estimate >"$dir/est"
f=$dir/est
echo "memory: $(fig block_bytes "$f") bytes per 8^3 block ($(fig block_bytes_colour "$f") with colour)," \
	"a 10 x 10 x 3 m room band at 1 cm (trunc 4 cm): $(fig room_blocks "$f") blocks," \
	"$(fig room_gb "$f") GB ($(fig room_gb_colour "$f") GB with colour); dense: $(fig dense_gb "$f") GB"
echo "goal: >= 150 M voxels/s on one core (allocated voxels); scikit-image and Open3D reach 90-115 here"

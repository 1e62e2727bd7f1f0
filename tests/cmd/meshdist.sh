# meshdist: the distance figures of hand-made scenes, exact where the
# arithmetic is exact and within 1e-12 where it rounds; sampling; -o; errors.
. tests/lib.sh
D=tests/data

# value KEY: the figure KEY of the last run's output.
value() { awk -v k="$1" '$1 == k { print $2 }' "$TMP/out"; }
near() {  # description, value, want, tolerance
	check_num "$1" "$(awk -v a="$2" -v b="$3" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" "<=" "$4"
}

# Unit square at z = 0 against the rectangle [0,2]x[0,1] at z = 0.5 (OBJ):
# A to B every vertex is 0.5 away; B to A two corners are 0.5 and two are
# sqrt(1 + 0.25) away, so ba_mean = 0.25 + sqrt(1.25)/2, ba_stdev =
# (sqrt(1.25) - 0.5)/2, ba_rms = sqrt(0.75) and the Hausdorff distance is
# sqrt(1.25).
run_case 0 "meshdist -H $D/dist_sq.ply $D/dist_rect.obj" $D/dist_sq_rect.out
run_case 0 "meshdist -H $D/dist_sq.ply - <$D/dist_rect.obj" $D/dist_sq_rect.out
near "ba_mean" "$(value ba_mean)" 0.80901699437494742 1e-15
near "ba_rms" "$(value ba_rms)" 0.86602540378443865 1e-15
near "hausdorff" "$(value hausdorff)" 1.1180339887498949 1e-15

# Only degenerate faces: a collinear triangle (a segment from x = 0 to 2) and
# a point.  The square's corners are 0, 0, 1, 1 from the segment.
run_case 0 "meshdist $D/dist_sq.ply $D/dist_degen.ply" $D/dist_sq_degen.out

# The unit cube against the cube offset outward by 0.1: every corner is 0.1
# from an offset face; back, every offset corner is 0.1*sqrt(3) from a corner.
run_case 0 "meshdist -H $D/dist_cube.ply $D/dist_cube_off.ply"
near "cube mean" "$(value mean)" 0.1 1e-12
near "cube max" "$(value max)" 0.1 1e-12
near "cube stdev" "$(value stdev)" 0 1e-12
near "cube rms" "$(value rms)" 0.1 1e-12
check_num "cube count" "$(value count)" == 8
near "cube ba_mean" "$(value ba_mean)" 0.17320508075688772 1e-12
near "cube hausdorff" "$(value hausdorff)" 0.17320508075688772 1e-12
# Points sampled on the cube's faces are all 0.1 away too.
run_case 0 "meshdist -s 20000 $D/dist_cube.ply $D/dist_cube_off.ply"
near "cube sampled mean" "$(value mean)" 0.1 1e-12
near "cube sampled max" "$(value max)" 0.1 1e-12

# Sampling: the square z = 1 + x, x, y in [0,1], over the plane z = 0.  The
# distance is z, uniform on [1, 2]: mean 1.5, stdev 1/sqrt(12), rms
# sqrt(2.25 + 1/12), max 2.  The vertices give mean 1.5 and max 2 exactly.
run_case 0 "meshdist $D/dist_tilt.ply $D/dist_plane.ply"
check_num "tilt vertex mean" "$(value mean)" == 1.5
check_num "tilt vertex max" "$(value max)" == 2
run_case 0 "meshdist -s 200000 $D/dist_tilt.ply $D/dist_plane.ply"
cp "$TMP/out" "$TMP/tilt1"
check_num "tilt count" "$(value count)" == 200000
near "tilt sampled mean" "$(value mean)" 1.5 0.004            # sd of the mean 0.00065
near "tilt sampled stdev" "$(value stdev)" 0.28867513459481287 0.003
near "tilt sampled rms" "$(value rms)" 1.5275252316519468 0.004
near "tilt sampled max" "$(value max)" 2 0.001
# The same seed gives the same figures; another seed other ones; -H adds
# lines but leaves the A to B figures as they were.
run_case 0 "meshdist -s 200000 --seed 1 $D/dist_tilt.ply $D/dist_plane.ply" "$TMP/tilt1"
run_case 0 "meshdist -s 200000 --seed 2 $D/dist_tilt.ply $D/dist_plane.ply"
check_true "--seed changes the samples" sh -c "! cmp -s '$TMP/out' '$TMP/tilt1'"
run_case 0 "meshdist -H -s 200000 $D/dist_tilt.ply $D/dist_plane.ply | head -n 5" "$TMP/tilt1"
# A square parallel to its measure at 0.5: every sample is 0.5 away.
run_case 0 "meshdist -s 5000 $D/dist_sq.ply $D/dist_rect.obj"
near "parallel sampled mean" "$(value mean)" 0.5 1e-15
near "parallel sampled stdev" "$(value stdev)" 0 1e-15

# -o: A with a float vertex property "distance" (the provenance line names
# the temporary folder, so it is left out of the comparison).
run_case 0 "meshdist -a -o $TMP/o.ply $D/dist_sq.ply $D/dist_rect.obj >/dev/null && grep -v '^comment facet' $TMP/o.ply" $D/dist_sq_o.out
run_case 0 "meshdist -s 100 -o $TMP/o2.ply $D/dist_sq.ply $D/dist_rect.obj >/dev/null && meshconv -a $TMP/o2.ply | grep -v '^comment facet'" $D/dist_sq_o.out

# Empty A: count 0.  A with vertices and no faces: fine as A, not as B.
run_case 0 "meshdist $D/dist_empty.ply $D/dist_cube.ply" $D/dist_empty.out
run_case 0 "meshdist $D/dist_nofaces.ply $D/dist_cube.ply"
check_num "no-face A count" "$(value count)" == 2
run_case 1 "meshdist $D/dist_cube.ply $D/dist_nofaces.ply" "" "meshdist: $D/dist_nofaces.ply: no faces to measure the distance to"
run_case 1 "meshdist -H $D/dist_empty.ply $D/dist_cube.ply" "" "meshdist: $D/dist_empty.ply: no faces"
run_case 1 "meshdist -s 10 $D/dist_nofaces.ply $D/dist_cube.ply" "" "meshdist: $D/dist_nofaces.ply: -s: the faces have no area"
run_case 1 "meshdist $D/dist_nan.ply $D/dist_cube.ply" "" "meshdist: $D/dist_nan.ply:"
run_case 1 "meshdist $D/dist_far.ply $D/dist_cube.ply" "" "meshdist: $D/dist_far.ply: vertex 1: the distance overflows a double"
run_case 1 "meshdist $D/dist_cube.ply $D/no_such_file.ply" "" "meshdist: $D/no_such_file.ply"

# -v figures on stderr, stdout unchanged.
run_case 0 "meshdist -v -H $D/dist_sq.ply $D/dist_rect.obj 2>$TMP/v" $D/dist_sq_rect.out
check_true "-v queries" grep -q '^meshdist: queries=8$' "$TMP/v"
check_true "-v queries_per_s" grep -q '^meshdist: queries_per_s=[0-9]' "$TMP/v"

# -p: percentiles by nearest rank, by hand: five points 1..5 above a
# triangle in z = 0 are 1..5 away; p50 is the 3rd (ceil(2.5)), p90, p95
# and p99 the 5th.
printf 'ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 1\n0 0 2\n0 0 3\n0 0 4\n0 0 5\n' >"$TMP/five.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-10 -10 0\n10 -10 0\n0 10 0\n3 0 1 2\n' >"$TMP/tri.ply"
meshdist -p "$TMP/five.ply" "$TMP/tri.ply" >"$TMP/pct" 2>&1
check_num "-p p50" "$(sed -n 's/^p50 //p' "$TMP/pct")" == 3
check_num "-p p90" "$(sed -n 's/^p90 //p' "$TMP/pct")" == 5
check_num "-p p99" "$(sed -n 's/^p99 //p' "$TMP/pct")" == 5
check_true "no percentiles without -p" sh -c "! meshdist $TMP/five.ply $TMP/tri.ply | grep -q '^p50'"

# Usage.
run_case 2 "meshdist $D/dist_sq.ply" "" "meshdist: two meshes A and B are needed"
run_case 2 "meshdist a b c" "" "meshdist: too many operands"
run_case 2 "meshdist - - <$D/dist_sq.ply" "" "meshdist: A and B cannot both be standard input"
run_case 2 "meshdist -s -3 $D/dist_sq.ply $D/dist_sq.ply" "" "meshdist: -s: -3 must be in"
run_case 2 "meshdist --seed x $D/dist_sq.ply $D/dist_sq.ply" "" "meshdist: --seed: \"x\" is not an integer"
run_case 2 "meshdist -o - $D/dist_sq.ply $D/dist_sq.ply" "" "meshdist: -o: the figures go to standard output"
run_case 2 "meshdist -Z $D/dist_sq.ply $D/dist_sq.ply" "" "meshdist: -Z: unknown option"
run_case 2 "meshdist $D/dist_sq.ply $D/dist_sq.ply -s" "" "meshdist: -s: option requires an argument"
run_case 0 "meshdist --help | head -n 1 | grep -q '^usage: meshdist '"
run_case 0 "meshdist --version | grep -q '^meshdist (facet) '"

# The man page's examples, on the fixtures.
run_case 0 "meshdist $D/dist_cube.ply $D/dist_cube_off.ply >/dev/null"
run_case 0 "meshdist -H -s 100000 --seed 7 $D/dist_cube.ply $D/dist_cube_off.ply | grep -q '^hausdorff '"
run_case 0 "meshdist -o $TMP/err.ply $D/dist_cube.ply $D/dist_cube_off.ply | awk '\$1 == \"max\"' | grep -q '^max 0.1'"
finish

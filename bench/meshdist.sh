#!/bin/sh
# meshdist throughput: exact point-to-mesh queries per second, single core,
# from the vertices of a noisy copy of a mesh (moved by 1% of the mean edge
# length) to the mesh, beside brute force on a few of the same queries and
# the time to cat the input.  Goal: >= 1,000,000 queries/s.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir dist
N=${DIST_N:-400}
"$FCT_BENCH/gen_dist" "$N" >"$dir/b.ply"
"$FCT_BENCH/gen_dist" -p "$N" >"$dir/a.ply"

# figure KEY [meshdist options...]: median over RUNS of a -v figure.
figure() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		meshdist -v "$@" 2>&1 >/dev/null | sed -n "s/^meshdist: $key=//p"
		i=$((i + 1))
	done | median
}

tris=$(meshdist -v "$dir/a.ply" "$dir/b.ply" 2>&1 >/dev/null | sed -n 's/^meshdist: triangles_b=//p')
verts=$(meshdist -v "$dir/a.ply" "$dir/b.ply" 2>&1 >/dev/null | sed -n 's/^meshdist: vertices_a=//p')
echo "meshdist: $verts query vertices (noisy copy, 1% of the mean edge) to a bumpy sphere of $tris triangles; medians of $RUNS runs"
q=$(figure queries_per_s "$dir/a.ply" "$dir/b.ply")
build=$(figure build_s "$dir/a.ply" "$dir/b.ply")
read=$(figure read_s "$dir/a.ply" "$dir/b.ply")
qs=$(figure queries_per_s -s 1000000 "$dir/a.ply" "$dir/b.ply")
bf=$(i=0; while [ $i -lt "$RUNS" ]; do "$FCT_BENCH/gen_dist" -b 100 "$dir/a.ply" "$dir/b.ply"; i=$((i + 1)); done | median)
cat=$("$FCT_BENCH/timeit" "$RUNS" "cat '$dir/a.ply' '$dir/b.ply' >/dev/null")
whole=$("$FCT_BENCH/timeit" "$RUNS" "meshdist '$dir/a.ply' '$dir/b.ply' >/dev/null")
printf '%-52s %12s\n' "what" "figure"
printf '%-52s %12.0f\n' "meshdist: vertex queries/s (BVH, exact)" "$q"
printf '%-52s %12.0f\n' "meshdist: sampled queries/s (-s 1000000, incl. sampling)" "$qs"
printf '%-52s %12.0f\n' "reference: brute-force queries/s (100 vertices)" "$bf"
printf '%-52s %12.1f\n' "ratio BVH / brute force" "$(awk -v a="$q" -v b="$bf" 'BEGIN { print (b > 0 ? a / b : 0) }')"
printf '%-52s %12.3f\n' "meshdist: BVH build, seconds" "$build"
printf '%-52s %12.3f\n' "meshdist: read both meshes, seconds" "$read"
printf '%-52s %12.3f\n' "meshdist: whole run, seconds" "$whole"
printf '%-52s %12.3f\n' "reference: cat both inputs > /dev/null, seconds" "$cat"
echo "goal: >= 1000000 vertex queries/s on one core"

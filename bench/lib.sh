# bench/lib.sh - what the bench scripts share; sourced from the top folder.

# median: the median of the numbers on standard input, one per line.
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# seconds CMD...: the median wall time of RUNS runs of a command.
seconds() {
	i=0
	while [ $i -lt "$RUNS" ]; do
		s=$(date +%s.%N)
		"$@" >/dev/null 2>&1
		e=$(date +%s.%N)
		awk -v s="$s" -v e="$e" 'BEGIN { print e - s }'
		i=$((i + 1))
	done | median
}

# bench_dir NAME: sets dir to the script's scratch folder, removed at exit.
# With BENCH_KEEP set it is $BENCH_KEEP/NAME instead, and kept: what the
# programs wrote there is what tools/fingerprint compares across a change.
bench_dir() {
	if [ -n "${BENCH_KEEP:-}" ]; then
		dir=$BENCH_KEEP/$1
		rm -rf "$dir"
		mkdir -p "$dir"
	else
		dir=$(mktemp -d "${TMPDIR:-/tmp}/facet-bench-$1.XXXXXX")
		trap 'rm -rf "$dir"' EXIT
	fi
}

# kitchen_frames: sets kitchen to the shared 7-Scenes kitchen frames' folder
# (../shared/data/7scenes_redkitchen/frames or /work/shared/...), or empty.
kitchen_frames() {
	kitchen=
	for k in ../shared/data/7scenes_redkitchen /work/shared/data/7scenes_redkitchen; do
		[ -f "$k/frames/frame-000000.depth.png" ] && kitchen=$k/frames && break
	done
}

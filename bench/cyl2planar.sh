#!/bin/sh
# cyl2planar throughput: a 4096x1024 RGB panorama of mkscene's room split
# into 8 planar views of 1024x1024 (90 degrees), one core.  The resampling
# (split_s: rays, bilinear, seam) is the figure of the goal; reading the PNG
# and writing 8 PNGs are shown beside it, with two references from the same
# run: cat of the panorama, and imginfo decoding it.  Goal: split < 0.3 s.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir cyl
mkscene -q --views 0 --panorama 4096x1024 -o "$dir/room"
pano=$dir/room/pano.color.png
# figure KEY: median over RUNS of a -v figure.
figure() {
	i=0
	while [ $i -lt "$RUNS" ]; do
		cyl2planar -v --count 8 --fov 90 --size 1024x1024 -o "$dir/views" "$pano" 2>&1 |
			sed -n "s/^cyl2planar: $1=//p"
		i=$((i + 1))
	done | median
}
split=$(figure split_s)
pps=$(figure pixels_per_s)
read=$(figure read_s)
write=$(figure write_s)
total=$(figure total_s)
cat=$("$FCT_BENCH/timeit" "$RUNS" "cat '$pano' >/dev/null")
decode=$("$FCT_BENCH/timeit" "$RUNS" "imginfo '$pano' >/dev/null")
echo "cyl2planar: 4096x1024 RGB panorama ($(wc -c <"$pano") bytes PNG) to 8 views of 1024x1024; medians of $RUNS runs"
printf '%-52s %12s\n' "what" "figure"
printf '%-52s %12.4f\n' "cyl2planar: resample 8 views, seconds" "$split"
printf '%-52s %12.0f\n' "cyl2planar: view pixels per second" "$pps"
printf '%-52s %12.4f\n' "cyl2planar: read the panorama PNG, seconds" "$read"
printf '%-52s %12.4f\n' "cyl2planar: write 8 PNGs, seconds" "$write"
printf '%-52s %12.4f\n' "cyl2planar: whole run, seconds" "$total"
printf '%-52s %12.4f\n' "reference: cat the panorama > /dev/null, seconds" "$cat"
printf '%-52s %12.4f\n' "reference: imginfo (PNG decode + stats), seconds" "$decode"
echo "goal: resampling 8 views of 1024x1024 from 4096x1024 in < 0.3 s on one core"

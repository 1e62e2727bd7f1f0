#!/bin/sh
# tests/cmd/imginfo.sh - imginfo on the image fixtures (tests/data/img_*, made
# by tests/data/img_gen.py without libpng) and on every bad image input.
. tests/lib.sh

D=tests/data
# Golden output for each fixture; the figures in them were checked by hand
# against the values written in img_gen.py.
for n in grey8 grey16 ga8 rgb8 rgba16 grey1 pal2 adam7; do
	run_case 0 "imginfo $D/img_$n.png" "$D/img_$n.info"
done
for n in depth rgb_be crlf; do
	run_case 0 "imginfo $D/img_$n.pfm" "$D/img_$n.info"
done
run_case 0 "imginfo $D/img_grey8.png $D/img_depth.pfm" "$D/img_two.info"
# JPEG (tests/data/jpg_gen.py): goldens from Pillow's decode, told by content
# (also under a .png name and on stdin).
for n in 7scenes 7scenes_prog 7scenes_arith 7scenes_restart grey cmyk tiles; do
	run_case 0 "imginfo $D/jpg_$n.jpg" "$D/jpg_$n.info"
done
cp $D/jpg_7scenes.jpg "$TMP/frame.png"
sed "s|^file .*|file $TMP/frame.png|" $D/jpg_7scenes.info >"$TMP/frame.info"
run_case 0 "imginfo $TMP/frame.png" "$TMP/frame.info"
sed 's|^file .*|file <stdin>|' $D/jpg_cmyk.info >"$TMP/cmyk.info"
run_case 0 "cat $D/jpg_cmyk.jpg | imginfo" "$TMP/cmyk.info"

# stdin, as a pipe and as "-", names itself <stdin>.
sed 's|^file .*|file <stdin>|' "$D/img_depth.info" >"$TMP/stdin.info"
run_case 0 "cat $D/img_depth.pfm | imginfo" "$TMP/stdin.info"
run_case 0 "imginfo - <$D/img_depth.pfm" "$TMP/stdin.info"

# Every bad image: status 1 and one line naming the file.
for f in tests/bad/img_*.png tests/bad/img_*.pfm tests/bad/img_*.jpg tests/bad/img_*.pgm; do
	run_case 1 "imginfo $f" "" "imginfo: $f: "
done
# A bad file after a good one still fails, with the good one described.
run_case 1 "imginfo $D/img_grey8.png tests/bad/img_lying.pfm" "" \
	"imginfo: tests/bad/img_lying.pfm: byte 14: PFM header says 300x200"
run_case 1 "cat tests/bad/img_lying.pfm | imginfo" "" "imginfo: <stdin>: byte 14: "
run_case 1 "imginfo tests/bad/img_huge.png" "" \
	"imginfo: tests/bad/img_huge.png: byte 16: image size 1000000x1000000: more than 2^31 pixels"
run_case 1 "imginfo $D/no-such-file.png" "" "imginfo: $D/no-such-file.png: No such file"
# 661 bytes claiming 30000x30000: refused from the header, before libjpeg
# allocates (a 100 MB address space is plenty for the rest; not under the
# sanitizers, whose shadow memory needs more).
lim=
[ -z "${FCT_SANITIZE:-}" ] && lim="ulimit -v 102400;"
run_case 1 "$lim imginfo tests/bad/img_jpeg_lying.jpg" "" \
	"imginfo: tests/bad/img_jpeg_lying.jpg: byte 623: image size 30000x30000: more pixels than 661 bytes of JPEG can code"
run_case 1 "imginfo tests/bad/img_jpeg_truncated.jpg" "" \
	"imginfo: tests/bad/img_jpeg_truncated.jpg: byte 659: libjpeg: Premature end of JPEG file"

# Usage.
run_case 0 "imginfo -h | head -n 1 | grep -q '^usage: imginfo \[-h\] \[--version\] \[file \.\.\.\]\$'"
run_case 0 "imginfo --version | grep -q '^imginfo (facet) '"
run_case 2 "imginfo -x" "" "imginfo: -x: unknown option"
run_case 2 "imginfo --bogus" "" "imginfo: --bogus: unknown option"

# The man page's synopsis is the usage line (tests/cmd/man_examples.sh runs
# its examples; here their outputs are checked).
man=man/man1/imginfo.1
run_case 0 "grep -q '^\.Op Fl -version\$' $man && grep -q '^\.Op Ar\$' $man"
run_case 0 "imginfo $D/img_grey16.png" "$D/img_grey16.info"
echo 3 >"$TMP/nodata"
run_case 0 "imginfo $D/img_depth.pfm | awk '\$1 == \"channel\" { print \$10 + \$12 }'" "$TMP/nodata"

# A real depth map (7-Scenes, millimetres): its zero count was found with an
# independent Python decoder.
real=../shared/data/7scenes_redkitchen/frames/frame-000000.depth.png
if [ -f "$real" ]; then
	out=$(imginfo "$real")
	check_num "7scenes zero pixels" "$(echo "$out" | awk '$1 == "channel" { print $10 }')" == 33257
	check_num "7scenes max depth" "$(echo "$out" | awk '$1 == "channel" { print $6 }')" == 3493
	check_true "7scenes is 640x480 u16" sh -c "echo '$out' | grep -q '^type u16' && echo '$out' | grep -q '^width 640'"
fi

finish

#!/bin/sh
# tolcmp: equal, within and outside the tolerance, integers exact, words,
# line structure, options, exit statuses and the first-difference message.
. tests/lib.sh
T=$TMP

printf 'vertices: 8\nbbox_min: 0.5 -2 1e-3\nname x.ply 0.25\n' >$T/a
cp $T/a $T/same
# Differences of 1e-8 relative: within the default -r 1e-6; layout differs.
printf 'vertices:   8\r\nbbox_min: 0.500000005 -2.00000002\t0.001\nname x.ply 0.25\n' >$T/close
printf 'vertices: 8\nbbox_min: 0.5 -2 0.0011\nname x.ply 0.25\n' >$T/far
printf 'vertices: 9\nbbox_min: 0.5 -2 1e-3\nname x.ply 0.25\n' >$T/int
printf 'vertices: 8\nbbox_min: 0.5 -2 1e-3\nname y.ply 0.25\n' >$T/word
printf 'vertices: 8\nbbox_min: 0.5 -2 1e-3 4\nname x.ply 0.25\n' >$T/tokens
printf 'vertices: 8\nbbox_min: 0.5 -2 1e-3\n' >$T/short
printf 'vertices: 8\nbbox_min: 0.5 -2 1e-3\nname x.ply 0.25\n\n' >$T/long

run_case 0 "tolcmp $T/a $T/same" "" ""
run_case 0 "tolcmp $T/a $T/close" "" ""
run_case 1 "tolcmp $T/a $T/far" "" "tolcmp: $T/a:2: \"1e-3\" vs \"0.0011\" (difference 0.0001)"
run_case 1 "tolcmp $T/a $T/int" "" "tolcmp: $T/a:1: \"8\" vs \"9\" (difference 1)"
run_case 1 "tolcmp $T/a $T/word" "" "tolcmp: $T/a:3: \"x.ply\" vs \"y.ply\""
run_case 1 "tolcmp $T/a $T/tokens" "" "tolcmp: $T/a:2: 4 tokens vs 5"
run_case 1 "tolcmp $T/a $T/short" "" "tolcmp: $T/a: 3 lines vs 2 in $T/short"
run_case 1 "tolcmp $T/a $T/long" "" "tolcmp: $T/a: 3 lines vs 4 in $T/long"
run_case 1 "tolcmp $T/short $T/a" "" "tolcmp: $T/short: 2 lines vs 3 in $T/a"
# Nothing on stderr when they match, nothing at all with -s.
run_case 0 "tolcmp $T/a $T/close 2>&1 | wc -c | grep -qx ' *0'"
run_case 0 "tolcmp -s $T/a $T/far 2>&1 | wc -c | grep -qx ' *0'"
run_case 0 "tolcmp -s $T/a $T/far; test \$? = 1"

# The tolerance: |a-b| <= abs + rel*max(|a|,|b|).
printf '100\n1.5\n' >$T/x
printf '100\n1.5001\n' >$T/y
run_case 1 "tolcmp $T/x $T/y"
run_case 0 "tolcmp -r 1e-4 $T/x $T/y"           # 1e-4 <= 1.5001e-4
run_case 1 "tolcmp -r 6e-5 $T/x $T/y"           # 1e-4 > 0.9e-4
run_case 0 "tolcmp -a 1e-4 -r 0 $T/x $T/y"      # boundary is inclusive, up to rounding
run_case 1 "tolcmp -a 9e-5 -r 0 $T/x $T/y"
# Integers are exact whatever the tolerance; an integer against a real is not.
printf '100\n' >$T/i1
printf '101\n' >$T/i2
printf '100.0000001\n' >$T/i3
run_case 1 "tolcmp -a 10 $T/i1 $T/i2"
run_case 0 "tolcmp $T/i1 $T/i3"
printf '007 +5 -0\n' >$T/i4
printf '7 5 0\n' >$T/i5
run_case 0 "tolcmp $T/i4 $T/i5"
# nan matches nan only; infinities match themselves.
printf 'nan inf -inf 1e308\n' >$T/n1
printf 'NaN inf -inf 1e308\n' >$T/n2
printf 'nan inf inf 1e308\n' >$T/n3
printf '1 inf -inf 1e308\n' >$T/n4
run_case 0 "tolcmp $T/n1 $T/n2"
run_case 1 "tolcmp $T/n1 $T/n3" "" "tolcmp: $T/n1:1: \"-inf\" vs \"inf\" (difference inf)"
run_case 1 "tolcmp $T/n1 $T/n4" "" "tolcmp: $T/n1:1: \"nan\" vs \"1\""
# Empty files and blank lines.
: >$T/e1
: >$T/e2
run_case 0 "tolcmp $T/e1 $T/e2"
printf '\n  \n' >$T/b1
printf '\t\n\n' >$T/b2
run_case 0 "tolcmp $T/b1 $T/b2"
run_case 1 "tolcmp $T/e1 $T/b1"
# stdin as either file.
run_case 0 "tolcmp - $T/close <$T/a"
run_case 0 "tolcmp $T/a - <$T/close"

# Usage and I/O errors: exit 2.
run_case 2 "tolcmp $T/a $T/nonexistent" "" "tolcmp: $T/nonexistent: "
run_case 2 "tolcmp $T/a" "" "tolcmp: expected two files"
run_case 2 "tolcmp - - </dev/null" "" "tolcmp: only one file can be stdin"
run_case 2 "tolcmp -a x $T/a $T/a" "" "tolcmp: -a: \"x\" is not a number"
run_case 2 "tolcmp -r -1 $T/a $T/a" "" "tolcmp: -r: -1 must be in"
run_case 2 "tolcmp -q $T/a $T/a" "" "tolcmp: -q: unknown option"
run_case 2 "tolcmp $T/a -a" "" "tolcmp: -a: option requires an argument"
run_case 0 "tolcmp $T/a /etc 2>/dev/null; test \$? = 2"
run_case 0 "tolcmp --help | grep -q '^usage: tolcmp \[-s\] \[-a abs\] \[-r rel\] file1 file2$'"
run_case 0 "tolcmp --version | grep -q '^tolcmp (facet) '"

# Not text: a NUL byte, or a line past 16 MB (/dev/zero was read until
# memory ran out at 2 GB): exit 2 within a 200 MB address space.
printf '1 2\n3\0 4\n' >$T/nul
run_case 2 "tolcmp $T/nul $T/nul" "" "tolcmp: $T/nul:2: NUL byte: not a text file"
lim=
[ -z "${FCT_SANITIZE:-}" ] && lim="ulimit -v 204800;"
run_case 2 "$lim timeout 20 tolcmp /dev/zero $T/a" "" "tolcmp: /dev/zero:1: line longer than 16777216 bytes"

# The man page's examples.
run_case 0 "meshinfo tests/data/info_cube.ply >$T/got && tolcmp tests/cmd/expected/meshinfo_cube.txt $T/got"
run_case 0 "meshconv -a tests/data/info_points.ply >$T/points.ply && tolcmp tests/data/info_points.ply $T/points.ply"
printf '1e-3 2\n' >$T/ex1
printf '0.001 2.0\n' >$T/ex2
run_case 0 "tolcmp -a 0 -r 0 $T/ex1 $T/ex2"
finish

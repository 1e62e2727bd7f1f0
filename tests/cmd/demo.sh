# tools/demo's command line (-h exits 0; usage errors exit 2 in one line)
# and its stages' status: a stage that fails inside what used to be a pipe
# (meshinfo | awk) stops the demo with the stage's own one line (issue 24,
# item 9).  The whole demo runs in `make demo`, not here.
. tests/lib.sh

run_case 0 "sh tools/demo -h | grep -q '^usage: demo '"
run_case 0 "sh tools/demo --help | grep -q -- '--gallery dir'"
run_case 0 "sh tools/demo --version | grep -q '^demo (facet) '"
run_case 2 "sh tools/demo --bogus" "" "demo: --bogus: unknown option"
run_case 2 "sh tools/demo --bogus=1" "" "demo: --bogus: unknown option"
run_case 2 "sh tools/demo --gallery" "" "demo: --gallery: option requires an argument"
run_case 2 "sh tools/demo out" "" "demo: out: unexpected operand"
run_case 2 "sh tools/demo -- out" "" "demo: out: unexpected operand"

# A meshinfo that fails: its status was lost in `meshinfo | awk`, and the
# demo went on to print a screenful of failed checks.  Now: its one line,
# exit 1, nothing more.
mkdir -p $TMP/bin
for p in "$FCT_BIN"/*; do ln -s "$p" $TMP/bin/; done
rm $TMP/bin/meshinfo
printf '#!/bin/sh\necho "meshinfo: $1: broken on purpose" >&2\nexit 1\n' >$TMP/bin/meshinfo
chmod +x $TMP/bin/meshinfo
run_case 1 "OUT=$TMP/demo FCT_BIN=$TMP/bin sh tools/demo >/dev/null" "" "meshinfo: 1-mesh.ply: broken on purpose"
check_true "no temporary file left" sh -c "! ls $TMP/demo/*/*.tmp $TMP/demo/*/*.tmp.ply 2>/dev/null"
finish

# sunfuse: the C programs' command line (options after the folder, bundled
# -qv, --opt=value, "--", -o -), one error line and exit 2 on usage errors,
# every stage's status kept (a stage's usage error stays 2, a bad depth file
# gives its one line), names with blanks or a leading '-', and the temporary
# folder removed on failure and on a signal (issue 24, items 9 and j).
. tests/lib.sh

S=$TMP/room
run_case 0 "mkscene -q --views 2 --size 80x60 -K 70,70,39.5,29.5 -o $S >/dev/null"
run_case 0 "sunfuse -q --voxel 0.05 --iterations 2 -o $TMP/ref.ply $S"
check_num "fused faces" "$(meshinfo $TMP/ref.ply | awk '$1 == "faces:" { print $2 }')" ">" 1000
# The same command gives the same bytes (the temporary folder's random name
# was in the provenance line).
run_case 0 "cp $TMP/ref.ply $TMP/again.ply"
run_case 0 "sunfuse -q --voxel 0.05 --iterations 2 -o $TMP/ref.ply $S && cmp $TMP/ref.ply $TMP/again.ply"
# Options after the folder ("0.05: not a folder" before), --opt=value,
# bundled flags, -o - (standard output): the same model (the provenance
# line names the options as given).
body() { meshconv -a "$1" | grep -v '^comment facet tsdfuse '; }
body $TMP/ref.ply >$TMP/ref.txt
same() { body "$1" | cmp -s - $TMP/ref.txt; }
run_case 0 "sunfuse -o $TMP/a.ply $S --voxel 0.05 --iterations=2 -q"
check_true "options after the folder" same $TMP/a.ply
run_case 0 "sunfuse --voxel=0.05 -qv --iterations 2 -o- $S 2>/dev/null >$TMP/b.ply"
check_true "--opt=value, -qv, -o-" same $TMP/b.ply
run_case 0 "sunfuse -qo $TMP/c.ply --voxel 0.05 --iterations 2 $S"
check_true "-qo FILE" same $TMP/c.ply
# A folder with a blank ($views was unquoted) and one named like an option.
cp -R $S "$TMP/my room"
run_case 0 "sunfuse -q --voxel 0.05 --iterations 2 -o $TMP/d.ply '$TMP/my room'"
check_true "a folder with a blank" same $TMP/d.ply
mkdir -p $TMP/d && cp -R $S $TMP/d/-v
run_case 0 "cd $TMP/d && sunfuse -q --voxel 0.05 --iterations 2 -o ../e.ply -- -v"
check_true "a folder named -v, after --" same $TMP/e.ply
# --keep keeps each smoothed view.
run_case 0 "sunfuse -q --voxel 0.05 --keep $TMP/kept -o $TMP/f.ply $S && test -s $TMP/kept/view00.ply && test -s $TMP/kept/view01.ply"

# Usage errors: exit 2, one line.
run_case 2 "sunfuse -o x.ply" "" "sunfuse: a folder of views is needed"
run_case 2 "sunfuse -o x.ply $S $S" "" "sunfuse: too many operands"
run_case 2 "sunfuse --bogus $S" "" "sunfuse: --bogus: unknown option"
run_case 2 "sunfuse -qx $S" "" "sunfuse: -x: unknown option"
run_case 2 "sunfuse $S --voxel" "" "sunfuse: --voxel: option requires an argument"
run_case 2 "sunfuse --carve=yes $S" "" "sunfuse: --carve: unknown option, or it takes no argument"
run_case 0 "sunfuse -h | grep -q '^usage: sunfuse '"
# A stage's usage error stays exit 2 (it was 1), with the stage's one line.
run_case 2 "sunfuse --voxel abc -o $TMP/x.ply $S" "" "tsdfuse: --voxel: \"abc\" is not a number"
run_case 2 "sunfuse --iterations x -o $TMP/x.ply $S" "" "areaflow: --iterations: "
# Bad data: one line, exit 1, no temporary folder left.
mkdir -p $TMP/tmpd
run_case 1 "sunfuse -o $TMP/x.ply $TMP/nothere" "" "sunfuse: $TMP/nothere: not a folder"
cp -R $S $TMP/bad && printf 'junk' >$TMP/bad/view01.depth.pfm
run_case 1 "TMPDIR=$TMP/tmpd sunfuse -o $TMP/x.ply $TMP/bad" "" "dm2mesh: $TMP/bad/view01.depth.pfm: "
check_true "no temporary folder left after a failed stage" sh -c "[ -z \"\$(ls -A $TMP/tmpd)\" ]"
check_true "no model written" test ! -e $TMP/x.ply
run_case 0 "cd $TMP && TMPDIR=tmpd sunfuse -q --voxel 0.05 -o x.ply room"
check_true "a relative TMPDIR: no temporary folder left" sh -c "[ -z \"\$(ls -A $TMP/tmpd)\" ]"
rm -f $TMP/x.ply
rm $TMP/bad/view01.pose
run_case 1 "sunfuse -o $TMP/x.ply $TMP/bad" "" "sunfuse: $TMP/bad/view01.pose: missing"
run_case 1 "sunfuse -o $TMP/x.ply $TMP/tmpd" "" "sunfuse: $TMP/tmpd: no viewNN.camera files"
nl="$TMP/new
line"
run_case 1 "sunfuse '$nl'" "" "sunfuse: $TMP/new\\nline: not a folder"

# SIGTERM in the middle of a stage: the stage is stopped, the temporary
# folder removed, exit 143.
B=$TMP/big
run_case 0 "mkscene -q --views 4 --size 640x480 -o $B >/dev/null"
TMPDIR=$TMP/tmpd sunfuse -q --voxel 0.02 -o $TMP/big.ply $B 2>/dev/null &
pid=$!
i=0
while [ $i -lt 400 ] && ! ls $TMP/tmpd/sunfuse.*/dense.ply >/dev/null 2>&1; do
	sleep 0.05
	i=$((i + 1))
done
kill -TERM $pid
wait $pid
st=$?
check_num "SIGTERM: exit 143" "$st" == 143
check_true "SIGTERM: the temporary folder is gone" sh -c "[ -z \"\$(ls -A $TMP/tmpd)\" ]"
check_true "SIGTERM: no model" test ! -e $TMP/big.ply
finish

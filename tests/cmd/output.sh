# Outputs at the edges: a closed pipe with SIGPIPE ignored ends a program
# quietly (it printed an uninitialised buffer or an empty "prog: " line),
# a program killed while writing -o FILE leaves no hidden temporary file
# (.FILE.XXXXXX), and -o takes a legal 252-byte name (the temporary name
# added 8 bytes: "File name too long").
. tests/lib.sh
D=tests/data

# quiet_on_closed_pipe "command": run with SIGPIPE ignored by the parent
# and stdout a pipe whose reader has gone; the command must die of SIGPIPE
# (status 141) and print nothing.
quiet_on_closed_pipe() {
	sh -c "trap '' PIPE; { $1 2>\"$TMP/perr\"; echo \$? >\"$TMP/pst\"; } | head -c 0"
	st=$(cat "$TMP/pst")
	if [ "$st" = 141 ] && [ ! -s "$TMP/perr" ]; then ok
	else not_ok "$1 into a closed pipe: status $st, stderr \"$(head -c 200 "$TMP/perr")\""; fi
}
dm2mesh -K tum samples/tum/TUM_depth.png >"$TMP/desk.ply"
quiet_on_closed_pipe "dm2mesh -K tum samples/tum/TUM_depth.png"
quiet_on_closed_pipe "segplanes $TMP/desk.ply"
quiet_on_closed_pipe "areaflow --iterations 1 $TMP/desk.ply"
quiet_on_closed_pipe "meshconv -a $TMP/desk.ply"
quiet_on_closed_pipe "meshinfo $TMP/desk.ply $TMP/desk.ply $TMP/desk.ply"

# A file size limit stops meshconv in the middle of its output (SIGXFSZ):
# neither the output nor its temporary file is left.
mkdir "$TMP/k"
run_case 153 "ulimit -f 100; meshconv -a -o $TMP/k/out.ply $TMP/desk.ply"
check_true "SIGXFSZ: nothing left in the folder" test -z "$(ls -A "$TMP/k")"

# SIGTERM and SIGHUP while the temporary file is being written (polled for:
# a 27 MB ascii PLY takes a few tenths of a second to write).  SIGINT is
# the unit test's (test_output.c): a background job here ignores it.
for sig in TERM HUP; do
	meshconv -a -o "$TMP/k/out.ply" "$TMP/desk.ply" &
	pid=$!
	seen=0
	for i in $(seq 2000); do
		if ls -A "$TMP/k" | grep -q '^\.out\.ply\.'; then
			kill -s $sig $pid
			seen=1
			break
		fi
		kill -0 $pid 2>/dev/null || break
	done
	{ wait $pid; } 2>/dev/null
	st=$?
	if [ $seen = 1 ]; then
		check_true "SIG$sig while writing: status $st" test $st -gt 128
		check_true "SIG$sig: nothing left in the folder ($(ls -A "$TMP/k"))" test -z "$(ls -A "$TMP/k")"
	else
		echo "output.sh: SIG$sig: the write ended before it was seen, not tested" >&2
	fi
	rm -f "$TMP/k/out.ply"
done

# TextureFile paths are kept as given on the pipes, and written relative to
# the output's folder, absolute ones too (PLY comment, OBJ comment and
# map_Kd): a model moved with its image, opened from another folder, is
# still textured (an absolute path broke once the folder moved).
mkdir -p "$TMP/m/a"
cp samples/tum/TUM_color.png "$TMP/m/a/rgb.png"
abs=$(cd "$TMP/m/a" && pwd)/rgb.png
run_case 0 "dm2mesh -K tum --step 8 --image $abs -o $TMP/m/a/desk.ply samples/tum/TUM_depth.png"
check_true "PLY: TextureFile relative" grep -a -q "^comment TextureFile rgb.png\$" "$TMP/m/a/desk.ply"
run_case 0 "dm2mesh -K tum --step 8 --image $abs samples/tum/TUM_depth.png | tee $TMP/m/pipe.ply | meshconv -o $TMP/m/a/desk.obj"
check_true "on the pipe: TextureFile as given" grep -a -q "^comment TextureFile $abs\$" "$TMP/m/pipe.ply"
check_true "OBJ: map_Kd relative" grep -q "^map_Kd rgb.png\$" "$TMP/m/a/desk.mtl"
check_true "OBJ: TextureFile comment relative" grep -q "^# comment TextureFile rgb.png\$" "$TMP/m/a/desk.obj"
run_case 0 "meshconv -o $TMP/m/up.ply $TMP/m/a/desk.obj"
check_true "written one folder up: a/rgb.png" grep -a -q "^comment TextureFile a/rgb.png\$" "$TMP/m/up.ply"
mv "$TMP/m/a" "$TMP/m/b"
for f in desk.ply desk.obj; do
	run_case 0 "cd / && meshshot -v -o $TMP/m/shot.png $TMP/m/b/$f"
	check_true "moved $f: drawn textured, no warning" sh -c "grep -q 'mode=texture' $TMP/err && ! grep -q warning $TMP/err"
done

# Names of 252 and 255 bytes, a PLY and an OBJ with its .mtl.
long=$(printf 'n%.0s' $(seq 248))
run_case 0 "meshconv -o $TMP/k/$long.ply $D/info_cube.ply"
run_case 0 "meshinfo $TMP/k/$long.ply"
long=$(printf 'm%.0s' $(seq 251))
run_case 0 "meshconv -o $TMP/k/$long.obj $D/shot_cube.ply"
check_true "a 255-byte OBJ name and its .mtl" test -s "$TMP/k/$long.obj" -a -s "$TMP/k/$long.mtl"
check_true "no temporary file left" test -z "$(ls -A "$TMP/k" | grep '^\.')"
run_case 1 "meshconv -o $TMP/k/x$long.ply $D/info_cube.ply" "" "meshconv: $TMP/k/x$long.ply: File name too long"
finish

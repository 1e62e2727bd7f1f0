# The PLY forms facet writes, read by the readers users have: Open3D,
# pymeshlab (MeshLab), trimesh and Blender (bpy), each when its Python module is
# installed (skipped with a message otherwise): binary little- and
# big-endian and ascii, with s t and TextureFile, with the face property
# patch and the plane element (segplanes), the edge element (simpchain),
# the planar model (planedecim),
# per-corner texcoord over several views (cyl2planar), an OBJ with its
# .mtl, planarize's models (PLY with s t, OBJ, a panorama's per-corner
# texcoord, and the atlas baked from a mesh's vertex colours, PLY and OBJ),
# roommodel's textured OBJ, tsdfuse's fused mesh with each
# vertex's sigma, and tsdfuse naming 30 views, whose provenance line Open3D's reader
# aborted on at 2359 bytes ("RPly: Line too long").  The numbers each reader
# gets are checked against facet's own ascii output (tests/cmd/interop.py).
. tests/lib.sh
PY=${PYTHON:-python3}

mkdir -p "$TMP/io"
cp samples/tum/TUM_color.png "$TMP/io/rgb.png"
cd "$TMP/io" || exit 1
S=$OLDPWD/samples/tum
run_case 0 "dm2mesh -K tum --step 8 --image rgb.png -o desk.ply $S/TUM_depth.png"
run_case 0 "dm2mesh -a -K tum --step 8 --image rgb.png -o desk_a.ply $S/TUM_depth.png"
run_case 0 "meshconv -f binary_big_endian -o desk_be.ply desk.ply"
run_case 0 "segplanes -o planes.ply desk.ply"
run_case 0 "simpchain -o chains.ply planes.ply"
run_case 0 "planedecim -o model.ply planes.ply"
run_case 0 "meshconv -o model.obj model.ply"
run_case 0 "planarize -K tum --step 2 -o plan.ply $S/TUM_depth.png rgb.png"
run_case 0 "planarize -K tum --step 2 -o plan_obj.obj $S/TUM_depth.png rgb.png"
mkscene -q --views 2 --size 80x60 --fx 60 --panorama 1024x256 -o room
for i in 00 01; do
	dm2mesh -q --camera room/view$i.camera --pose room/view$i.pose -o room/v$i.ply room/view$i.depth.pfm
done
mkdir views
set --
for k in $(seq 10 39); do
	ln -s ../room/v0$((k % 2)).ply views/fragment_of_the_room_$k.ply
	set -- "$@" views/fragment_of_the_room_$k.ply
done
run_case 0 "tsdfuse --voxel 0.1 -o fused.ply $*"
check_true "30 views named in the provenance, abbreviated" \
	grep -a -q "^comment facet tsdfuse --voxel 0.1 -o fused.ply views/fragment_of_the_room_10.ply .* (2[0-9] more) views/fragment_of_the_room_39.ply\$" fused.ply
# Depth images under a sensor's noise model: the fused mesh carries each
# vertex's sigma.
run_case 0 "tsdfuse --voxel 0.05 --noise kinect --camera room/view00.camera --poses room/view00.pose --poses room/view01.pose -o fused_sigma.ply room/view00.depth.pfm room/view01.depth.pfm"
check_true "fused_sigma.ply: has sigma" grep -a -q '^property float sigma$' fused_sigma.ply
dm2mesh -q --step 8 --cylindrical ,,0 --pose room/pano.pose --image room/pano.color.png -o dense.ply room/pano.depth.pfm
mkdir c
run_case 0 "cyl2planar --mesh dense.ply -o c/room.ply"
run_case 0 "planarize --step 4 --cylindrical ,,0 --pose room/pano.pose -o c/plan.ply room/pano.depth.pfm room/pano.color.png"
awk -f "$OLDPWD/tests/data/colour_wall.awk" >wall.ply
run_case 0 "planarize -o bake.ply wall.ply"
run_case 0 "planarize -o bake_obj.obj wall.ply"
run_case 0 "roommodel -q --voxel 0.05 --camera room/view00.camera --poses room/view00.pose --poses room/view01.pose --image room/view00.color.png --image room/view01.color.png -o room_model.obj room/view00.depth.pfm room/view01.depth.pfm"

# Every header line of every file: at most 255 bytes.
for f in desk.ply desk_a.ply desk_be.ply planes.ply chains.ply model.ply fused.ply fused_sigma.ply c/room.ply plan.ply c/plan.ply \
	bake.ply; do
	check_num "$f: longest header line" "$(sed -n '1,/^end_header/p' "$f" | LC_ALL=C awk '{ n = length($0) > n ? length($0) : n } END { print n }')" "<=" 255
done

if ! command -v "$PY" >/dev/null 2>&1 || ! "$PY" -c 'import numpy' 2>/dev/null; then
	echo "interop.sh: $PY with numpy not found, the readers are not tried" >&2
	cd "$OLDPWD" || exit 1
	finish
	exit
fi
specs=
for f in desk.ply desk_a.ply desk_be.ply planes.ply chains.ply model.ply fused.ply fused_sigma.ply c/room.ply model.obj \
	plan.ply c/plan.ply plan_obj.obj room_model.obj bake.ply bake_obj.obj; do
	ref=${f%.*}.ref.ply
	case $f in model.obj) ref=model.ref.ply ;; esac
	[ -f "$ref" ] || meshconv -a -o "$ref" "$f"
	case $f in
	chains.ply) kind=wire ;;
	fused.ply | fused_sigma.ply) kind=mesh ;;
	c/room.ply | c/plan.ply | bake.ply) kind=corner ;;
	*.obj) kind=obj ;;
	*) kind=st ;;
	esac
	specs="$specs $f:$ref:$kind"
done
for mod in open3d pymeshlab trimesh bpy; do
	if ! "$PY" -c "import $mod" 2>/dev/null; then
		echo "interop.sh: Python module $mod not installed, skipped (pip install $mod)" >&2
		continue
	fi
	"$PY" "$OLDPWD/tests/cmd/interop.py" $mod $specs >"$TMP/$mod.out" 2>"$TMP/$mod.err"
	st=$?
	grep '^SKIP' "$TMP/$mod.out" | sed 's/^/interop.sh: /' >&2
	while IFS= read -r line; do
		case $line in
		PASS*) ok ;;
		FAIL*) not_ok "$line" ;;
		esac
	done <"$TMP/$mod.out"
	check_true "$mod: the reader ran to the end (status $st): $(tail -n 2 "$TMP/$mod.err")" test $st = 0
	check_true "$mod: checked something" grep -q '^PASS' "$TMP/$mod.out"
done
cd "$OLDPWD" || exit 1
finish

# planarize on a mesh that carries its colour as vertex red green blue and
# no image (issue 23 item 6): the model gets an atlas baked from the dense
# mesh's colours.  A synthetic wall (a checkerboard of 0.2 m squares) and
# floor (two red lines 6 cm wide) at 2 cm, seen by the camera in its
# header: the model (4 faces) rendered from that camera matches the dense
# mesh's own rendering at over 33 dB (35.85 measured), where the model's
# vertex colours alone (--texel 0, as before) give under 12 (8.82).  The
# files (PLY with per-corner texcoord and TextureFile, OBJ with MTL),
# texture paths relative to the model's folder, the same bytes twice, a
# model on standard output left with its vertex colours, segplanes |
# planedecim -o baking the same model and atlas, the option's grammar.
. tests/lib.sh

field() { sed -n "s/^planarize: $1=//p" "$TMP/err"; }
judged() { awk '$1 == "all" { print $'"$1"' }' "$TMP/out"; }

mkdir -p "$TMP/cb/out"
D=$TMP/cb/dense.ply
awk -f tests/data/colour_wall.awk >"$D"
printf '1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n' >"$TMP/cb/id.pose"
J="viewjudge -K 240,240,159.5,119.5 --poses $TMP/cb/id.pose"
run_case 0 "meshshot -q -m color -o $TMP/cb/photo.png $D"

run_case 0 "planarize -v -o $TMP/cb/out/model.ply $D"
check_num "model faces" "$(sed -n 's/^planarize: planedecim *[0-9]* vertices *\([0-9]*\) faces.*/\1/p' "$TMP/err")" "<=" 8
check_num "bake: charts (one per plane)" "$(field 'bake: charts')" == 2
check_num "bake: charts in their plane's frame" "$(field 'bake: charts_rectified')" == 2
check_num "bake: texel, half the mean edge (0.0113807 m)" "$(field 'bake: texel')" == 0.0113807118
check_true "model.ply names its atlas beside it" grep -a -q '^comment TextureFile model_atlas0.png$' "$TMP/cb/out/model.ply"
check_true "model.ply: per-corner texcoord" grep -a -q '^property list uchar float texcoord$' "$TMP/cb/out/model.ply"
check_true "the atlas is written" test -s "$TMP/cb/out/model_atlas0.png"
run_case 0 "$J $TMP/cb/out/model.ply $TMP/cb/photo.png"
check_num "baked model: PSNR against the dense mesh's rendering" "$(judged 3)" ">" 33
check_num "baked model: coverage" "$(judged 2)" ">" 0.78
run_case 0 "planarize --texel 0 -o $TMP/cb/vc.ply $D"
check_true "--texel 0: no atlas" test ! -e "$TMP/cb/vc_atlas0.png"
run_case 0 "$J $TMP/cb/vc.ply $TMP/cb/photo.png"
check_num "vertex-coloured model: PSNR (the pattern lost)" "$(judged 3)" "<" 12
# A coarser texel given: fewer texels, the pattern still there.
run_case 0 "planarize -v --texel 0.03 -o $TMP/cb/coarse.ply $D"
check_num "--texel 0.03: reported" "$(field 'bake: texel')" == 0.03
run_case 0 "$J $TMP/cb/coarse.ply $TMP/cb/photo.png"
check_num "--texel 0.03: PSNR" "$(judged 3)" ">" 20

# The same bytes twice; the OBJ with its MTL, paths relative to its folder.
mkdir "$TMP/cb/a" "$TMP/cb/b"
run_case 0 "cd $TMP/cb/a && planarize -o model.ply ../dense.ply && cd ../b && planarize -o model.ply ../dense.ply"
check_true "the same model twice" cmp -s "$TMP/cb/a/model.ply" "$TMP/cb/b/model.ply"
check_true "the same atlas twice" cmp -s "$TMP/cb/a/model_atlas0.png" "$TMP/cb/b/model_atlas0.png"
check_true "the same atlas as in out/" cmp -s "$TMP/cb/a/model_atlas0.png" "$TMP/cb/out/model_atlas0.png"
run_case 0 "planarize -o $TMP/cb/out/model.obj $D"
check_true "model.mtl names the atlas" grep -q '^map_Kd model_atlas0.png$' "$TMP/cb/out/model.mtl"
check_true "model.obj: texture coordinates" grep -q '^vt ' "$TMP/cb/out/model.obj"
run_case 0 "$J $TMP/cb/out/model.obj $TMP/cb/photo.png"
check_num "model.obj: PSNR" "$(judged 3)" ">" 33
# On standard output there is no folder for an atlas: vertex colours only.
check_num "on standard output: TextureFile lines" "$(planarize "$D" | meshconv -a - | awk '/^comment TextureFile/ { n++ } END { print n + 0 }')" == 0
check_num "on standard output: vertex colours" "$(planarize "$D" | meshconv -a - | grep -c '^property uchar red$')" == 1

# The stages on a pipe bake alike: segplanes | planedecim -o.
run_case 0 "segplanes $D | planedecim -v -o $TMP/cb/a/piped.ply"
check_true "segplanes | planedecim: planarize's atlas" cmp -s "$TMP/cb/a/piped_atlas0.png" "$TMP/cb/a/model_atlas0.png"
check_true "segplanes | planedecim: planarize's model" test "$(meshconv -a "$TMP/cb/a/piped.ply" | grep -v '^comment facet ' | sed 's/piped_atlas/model_atlas/' | cksum)" = "$(meshconv -a "$TMP/cb/a/model.ply" | grep -v '^comment facet ' | cksum)"
check_num "planedecim: bake: charts" "$(sed -n 's/^planedecim: bake: charts=//p' "$TMP/err")" == 2

run_case 2 "planedecim --texel x $D" "" "planedecim: --texel: "
run_case 2 "planarize --texel -1 $D" "" "planarize: --texel: "
run_case 2 "planarize --texel x $D" "" "planarize: --texel: "
run_case 0 "planarize --help | grep -q -- '--texel size'"

finish

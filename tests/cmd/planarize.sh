# planarize: the planar pipeline in one process (dm2mesh, segplanes,
# planedecim, texture), judged against the exact scene on mkscene's room
# with Gaussian and with structured (Kinect) noise, beside the dense mesh
# and a quadric decimation (qemdecim) to the same face count; the real TUM
# and 7-Scenes frames; a valid mesh (no non-manifold edge, degenerate or
# duplicate face); dm2mesh's camera options (Middlebury's calib.txt,
# --doffs, the implausible-depth warning, a georeferenced pose kept as
# double); the same bytes twice; the stages equal to the programs on a
# pipe; mesh inputs with and without a camera; --keep; the C programs'
# grammar and their error conventions.
. tests/lib.sh

figure() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }
field() { sed -n "s/^planarize: $1=//p" "$2"; }
info() { meshinfo "$2" | awk -v k="$1:" '$1 == k { print $2 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { print (b > 0 ? a / b : 0) }'; }
# valid NAME FILE: no non-manifold edge, degenerate or duplicate face
valid() {
	check_num "$1: non-manifold edges" "$(info non_manifold_edges "$2")" == 0
	check_num "$1: degenerate faces" "$(info degenerate_faces "$2")" == 0
	check_num "$1: duplicate faces" "$(info duplicate_faces "$2")" == 0
	# (a vertex torn where planes meet once left its original unused, which
	# Open3D keeps and trimesh and pymeshlab drop: 39 on the TUM desk)
	check_num "$1: vertices no face uses" "$(info isolated_vertices "$2")" == 0
}
# bare FILE: the mesh as ascii without provenance lines (which name the
# command line), for comparing what two runs made
bare() { meshconv -a "$1" | grep -v '^comment facet '; }

# room NAME NOISE: mkscene's furnished room (640x480) with that noise,
# planarize with the view's noise model, qemdecim of the dense mesh to the
# model's face count, and each one's distances to the TRUE surface
# (meshdist -p -s from points on it to scene.ply) in $R/{dense,model,qem}.
room() {
	R=$TMP/$1
	mkscene -q --noise "$2" -o "$R" >/dev/null
	run_case 0 "planarize -v --camera $R/view00.camera --pose $R/view00.pose --noise $R/view00.noise --keep $R/k -o $R/model.ply $R/view00.depth.pfm $R/view00.color.png 2>$R/err"
	run_case 0 "qemdecim -c -n $(info faces "$R/model.ply") -o $R/qem.ply $R/k/1-mesh.ply"
	meshdist -p -s 200000 "$R/k/1-mesh.ply" "$R/scene.ply" >"$R/dense"
	meshdist -p -s 200000 "$R/model.ply" "$R/scene.ply" >"$R/model"
	meshdist -p -s 200000 "$R/qem.ply" "$R/scene.ply" >"$R/qem"
	valid "$1" "$R/model.ply"
}

# Gaussian noise along the rays, sigma 2 mm (measured at planar 277adc3:
# 583x, 1045 faces; to the truth, mean 0.38 mm against 0.75 for the dense
# mesh and 0.52 for QEM; the model's median point 0.016 mm off, the dense
# mesh's 0.55).
room gauss gaussian:0.002
R=$TMP/gauss
check_num "gauss: reduction 500x" "$(field reduction "$R/err")" ">=" 500
check_num "gauss: closer to the truth than the dense mesh (mean, 0.7)" \
	"$(ratio "$(figure mean "$R/model")" "$(figure mean "$R/dense")")" "<" 0.7
check_num "gauss: closer to the truth than QEM at the same face count (mean, 0.85)" \
	"$(ratio "$(figure mean "$R/model")" "$(figure mean "$R/qem")")" "<" 0.85
check_num "gauss: the model's median point on the truth (dense p50 / 10)" \
	"$(figure p50 "$R/model")" "<" "$(awk -v d="$(figure p50 "$R/dense")" 'BEGIN { print d / 10 }')"
# Table 1 in process equals meshdist on the kept stages.
run_case 0 "meshdist $R/k/1-mesh.ply $R/k/3-model.ply > $R/table1"
# (The files hold the model's coordinates as float: 1e-8 apart.)
check_num "gauss: E_mean is meshdist's" "$(awk -v a="$(field E_mean "$R/err")" -v b="$(figure mean "$R/table1")" 'BEGIN { d = a - b; print (d < 0 ? -d : d) }')" "<" 1e-7
check_num "gauss: E_max is meshdist's" "$(awk -v a="$(field E_max "$R/err")" -v b="$(figure max "$R/table1")" 'BEGIN { d = a - b; print (d < 0 ? -d : d) }')" "<" 1e-7

# Structured-light noise as ICL-NUIM simulates it (disparity noise, 1/8-px
# steps, jittered sampling; measured at planar 277adc3: 308x, 1974 faces;
# mean distance to the truth 3.1 mm against 16.1 for the dense mesh and 4.9
# for QEM, p95 15.9 mm against 50 and 15.8).
room kinect kinect
R=$TMP/kinect
check_num "kinect: reduction 300x" "$(field reduction "$R/err")" ">=" 300
check_num "kinect: closer to the truth than the dense mesh (mean, half)" \
	"$(ratio "$(figure mean "$R/model")" "$(figure mean "$R/dense")")" "<" 0.5
check_num "kinect: closer to the truth than QEM at the same face count (mean)" \
	"$(ratio "$(figure mean "$R/model")" "$(figure mean "$R/qem")")" "<" 0.9
check_num "kinect: p95 below the dense mesh's" "$(figure p95 "$R/model")" "<" "$(figure p95 "$R/dense")"
check_true "kinect: each stage's line" grep -q '^planarize: planedecim  *[0-9]* vertices  *[0-9]* faces  *[0-9.]* s$' "$R/err"
check_true "kinect: stage figures" grep -q '^planarize: segplanes: patches=[0-9]*$' "$R/err"
check_true "kinect: --keep files" test "$(ls "$R/k" | tr '\n' ' ')" = "1-mesh.ply 2-patches.ply 3-model.ply "

# Missing pixels, as sensors drop them (speckle, dark or shiny spots): 5%
# of the room's pixels at random, 320x240.  Each leaves a small hole in a
# plane, which planedecim fills; half of them touch another hole at a
# corner, and noise along the rays folds such a small loop in the plane
# unless it is filled after the projection onto the plane.  Measured when
# that came in: 121x, 1.9 mm from the truth, dense mesh 16 (the frame
# without missing pixels 297x, 1.7 mm); 33x when those holes stayed open.
M=$TMP/missing
mkscene -q --size 320x240 --fx 262.5 --noise kinect --missing 0.05 -o "$M" >/dev/null
run_case 0 "planarize -v --camera $M/view00.camera --pose $M/view00.pose --noise $M/view00.noise --keep $M/k -o $M/model.ply $M/view00.depth.pfm 2>$M/err"
check_num "5% missing pixels: reduction 100x" "$(field reduction "$M/err")" ">=" 100
check_num "5% missing pixels: holes filled" "$(sed -n 's/^planarize: planedecim: holes_filled=//p' "$M/err")" ">" 2000
meshdist -p -s 200000 "$M/k/1-mesh.ply" "$M/scene.ply" >"$M/dense"
meshdist -p -s 200000 "$M/model.ply" "$M/scene.ply" >"$M/model"
check_num "5% missing pixels: closer to the truth than the dense mesh (mean, a quarter)" \
	"$(ratio "$(figure mean "$M/model")" "$(figure mean "$M/dense")")" "<" 0.25
valid "5% missing pixels" "$M/model.ply"

# The real TUM frame, defaults: an OBJ with its material library naming the
# photo relative to the model's folder (measured with planedecim's -e 1.5
# default: 53x, E_mean 8.6 mm, E_max 220 mm; QEM at the same count is
# closer to the dense mesh).  Issue 23 asks 50x: 78x at d60fa92, 48x once
# segplanes kept no face farther than 3 sigma from its plane (more of the
# clutter is free-form surface), 53x with -e 1.5.
S=samples/tum
mkdir -p "$TMP/tum/models"
run_case 0 "planarize -v -K tum --keep $TMP/tum/k -o $TMP/tum/models/desk.obj $S/TUM_depth.png $S/TUM_color.png 2>$TMP/tum/err"
check_num "TUM: reduction 50x (issue 23)" "$(field reduction "$TMP/tum/err")" ">=" 50
check_num "TUM: E_mean below 11 mm" "$(field E_mean "$TMP/tum/err")" "<" 0.011
check_num "TUM: E_max below 0.3 m" "$(field E_max "$TMP/tum/err")" "<" 0.3
valid TUM "$TMP/tum/models/desk.obj"
map=$(awk '$1 == "map_Kd" { print $2 }' "$TMP/tum/models/desk.mtl")
check_true "TUM: map_Kd relative ($map)" test "${map#/}" = "$map"
check_true "TUM: map_Kd names the photo from the model's folder" cmp -s "$TMP/tum/models/$map" "$S/TUM_color.png"
# Stage 1 is dm2mesh's mesh, bytes and all (but the provenance).
run_case 0 "dm2mesh -K tum --image $S/TUM_color.png -o $TMP/tum/k/dm2mesh.ply $S/TUM_depth.png"
check_true "TUM: 1-mesh.ply is dm2mesh's" test "$(bare "$TMP/tum/k/1-mesh.ply" | cksum)" = "$(bare "$TMP/tum/k/dm2mesh.ply" | cksum)"

# The 7-Scenes kitchen, frame 000000 (samples/7scenes): 90x, 5947 faces,
# E_mean 4.8 mm, E_max 115 mm measured at planar 277adc3 (102x and 115 mm
# at d60fa92, 91 mm before it).  Issue 23 asks 50x and a max under 100 mm:
# 116 mm until a vertex's move along its ray onto its plane was bounded
# (max_move sigma), 92 mm since.
K=samples/7scenes
run_case 0 "planarize -v -K 7scenes --pose $K/frame-000000.pose.txt -o $TMP/kitchen.obj $K/frame-000000.depth.png $K/frame-000000.color.jpg 2>$TMP/kitchen.err"
check_num "7-Scenes: reduction 80x" "$(field reduction "$TMP/kitchen.err")" ">=" 80
check_num "7-Scenes: E_mean below 7 mm" "$(field E_mean "$TMP/kitchen.err")" "<" 0.007
check_num "7-Scenes: E_max below 100 mm (issue 23)" "$(field E_max "$TMP/kitchen.err")" "<" 0.1
valid 7-Scenes "$TMP/kitchen.obj"

# dm2mesh's camera options are planarize's.  Middlebury's calib.txt as
# --camera: the disparities of 20 px with its doffs 5 are 0.1 * 100 / 25 =
# 0.4 m, as dm2mesh makes them (tests/cmd/dm2mesh.sh).
D=tests/data
run_case 0 "planarize --camera $D/dm_middlebury_calib.txt --keep $TMP/mb -o $TMP/mb.ply $D/dm_disp.pfm"
run_case 0 "dm2mesh --camera $D/dm_middlebury_calib.txt -o $TMP/mb/dm2mesh.ply $D/dm_disp.pfm"
check_true "calib.txt: 1-mesh.ply is dm2mesh's" test "$(bare "$TMP/mb/1-mesh.ply" | cksum)" = "$(bare "$TMP/mb/dm2mesh.ply" | cksum)"
check_true "calib.txt: every depth 0.4" test "$(bare "$TMP/mb/1-mesh.ply" | awk '/^end_header/ { h = 1; next } h && NF == 5 { print $3 }' | sort -u)" = 0.4
run_case 0 "planarize --camera $D/dm_middlebury_calib.txt --doffs 0 --keep $TMP/mb0 -o $TMP/mb0.ply $D/dm_disp.pfm"
check_true "calib.txt, --doffs 0: every depth 0.5" test "$(bare "$TMP/mb0/1-mesh.ply" | awk '/^end_header/ { h = 1; next } h && NF == 5 { print $3 }' | sort -u)" = 0.5
run_case 2 "planarize -K 100,100,3.5,2.5 --doffs 5 $D/dm_disp.pfm" "" "planarize: --doffs is for disparities and needs --baseline"
run_case 2 "planarize -K $D/dm_middlebury_calib.txt $D/dm_disp.pfm" "" "planarize: -K: \"$D/dm_middlebury_calib.txt\" is a file: give an intrinsics file with --camera"
# The TUM desk with fr3's K typed as numbers (depth read as millimetres, not
# TUM's 1/5000 m): dm2mesh's warning, and the model is made all the same.
run_case 0 "planarize --step 8 -K 535.4,539.2,320.1,247.6 -o $TMP/tum12.ply $S/TUM_depth.png 2>$TMP/tum12.err"
check_true "implausible depth: dm2mesh's warning" grep -q "^planarize: warning: $S/TUM_depth.png: median depth 12.1 m: implausible" "$TMP/tum12.err"
# A georeferenced pose (the room 500 km east, 4000 km north): positions
# kept as double, and the model is the programs' on a pipe.
G=$TMP/geo
mkscene -q --views 1 --size 160x120 --fx 131.25 --noise kinect-gauss:0.0015 -o "$G" >/dev/null
awk 'NR == 1 { $4 += 500000 } NR == 2 { $4 += 4000000 } { print }' "$G/view00.pose" >"$G/far.pose"
run_case 0 "planarize -v --camera $G/view00.camera --pose $G/far.pose --keep $G/k -o $G/model.ply $G/view00.depth.pfm 2>$G/err"
check_num "georeferenced: double positions reported" "$(sed -n 's/^planarize: dm2mesh: double_xyz=//p' "$G/err")" == 1
check_true "georeferenced: x is double in the model" sh -c "meshinfo $G/model.ply | grep -q '^property: vertex double x'"
gf=$(info faces "$G/k/1-mesh.ply")
run_case 0 "dm2mesh --camera $G/view00.camera --pose $G/far.pose $G/view00.depth.pfm | segplanes --min-faces $((gf / 600)) | planedecim -o $G/pipe.ply"
check_true "georeferenced: the programs' model" test "$(bare "$G/pipe.ply" | cksum)" = "$(bare "$G/model.ply" | cksum)"

# A small room (320x240, Kinect noise) for what follows.
V=$TMP/small
mkscene -q --size 320x240 --fx 262.5 --noise kinect -o "$V" >/dev/null
C="--camera $V/view00.camera --pose $V/view00.pose --noise $V/view00.noise"
run_case 0 "planarize $C --keep $V/k -o $V/a.ply $V/view00.depth.pfm $V/view00.color.png"
cp "$V/a.ply" "$V/a1.ply"
run_case 0 "planarize $C --keep $V/k -o $V/a.ply $V/view00.depth.pfm $V/view00.color.png"
check_true "the same bytes twice" cmp -s "$V/a.ply" "$V/a1.ply"
# The stages are the programs: the kept dense mesh through segplanes (with
# planarize's --min-faces: one in 600 faces) and planedecim is the model.
mf=$(info faces "$V/k/1-mesh.ply")
run_case 0 "segplanes --min-faces $((mf / 600)) $V/k/1-mesh.ply | planedecim -o $V/pipe.ply"
check_true "segplanes | planedecim gives planarize's model" test "$(bare "$V/pipe.ply" | cksum)" = "$(bare "$V/k/3-model.ply" | cksum)"
check_true "2-patches.ply is segplanes'" test "$(segplanes --min-faces $((mf / 600)) "$V/k/1-mesh.ply" | bare - | cksum)" = "$(bare "$V/k/2-patches.ply" | cksum)"

# Grammar: options after operands, bundled flags, --opt=value, '--', '-'.
run_case 0 "planarize $V/view00.depth.pfm $V/view00.color.png $C -o $V/c.ply"
check_true "options after the operands" test "$(bare "$V/c.ply" | cksum)" = "$(bare "$V/a.ply" | cksum)"
run_case 0 "planarize -av --camera=$V/view00.camera --pose=$V/view00.pose --noise=$V/view00.noise --min-faces=$((mf / 600)) -o $V/d.ply $V/view00.depth.pfm $V/view00.color.png 2>$V/d.err"
check_true "-av: ascii" grep -q '^format ascii 1.0' "$V/d.ply"
check_true "-av: figures" grep -q '^planarize: reduction=' "$V/d.err"
check_true "--opt=value" test "$(bare "$V/d.ply" | cksum)" = "$(bare "$V/a.ply" | cksum)"
cp "$V/view00.depth.pfm" "$TMP/-d.pfm"
run_case 0 "cd $TMP && planarize $C --image small/view00.color.png -o e.ply -- -d.pfm"
check_true "-- then a depth image named -d.pfm" test "$(bare "$TMP/e.ply" | cksum)" = "$(bare "$V/a.ply" | cksum)"
run_case 0 "planarize $C --image $V/view00.color.png - < $V/view00.depth.pfm > $V/f.ply"
check_true "depth on standard input, model on standard output" test "$(bare "$V/f.ply" | cksum)" = "$(bare "$V/a.ply" | cksum)"
run_case 0 "planarize -o $V/g.ply < $V/k/1-mesh.ply"
check_num "a mesh on standard input" "$(info faces "$V/g.ply")" == "$(info faces "$V/a.ply")"

# Any mesh in.  With a camera (the kept dense mesh): the depth image's model.
run_case 0 "planarize -o $V/m1.ply $V/k/1-mesh.ply"
check_true "a mesh with a camera: the model of its depth image" test "$(bare "$V/m1.ply" | cksum)" = "$(bare "$V/a.ply" | cksum)"
# Without a camera (its camera and pose comments taken away; sigma kept):
# measured 197x, 4.1 mm from the truth against the dense mesh's 15.8 (204x
# before the small holes of the free-form surface were filled: seven
# missing pixels' holes, 29 faces more in a model of 760).
meshconv -a "$V/k/1-mesh.ply" | grep -v -e '^comment camera ' -e '^comment pose ' >"$V/nocam.ply"
run_case 0 "planarize -v -o $V/m2.ply $V/nocam.ply 2>$V/m2.err"
check_num "no camera: reduction 190x" "$(field reduction "$V/m2.err")" ">=" 190
valid "no camera" "$V/m2.ply"
run_case 0 "meshdist -s 100000 $V/m2.ply $V/scene.ply > $V/m2.dist"
run_case 0 "meshdist -s 100000 $V/k/1-mesh.ply $V/scene.ply > $V/dense.dist"
check_num "no camera: closer to the truth than the dense mesh (half)" \
	"$(ratio "$(figure mean "$V/m2.dist")" "$(figure mean "$V/dense.dist")")" "<" 0.5
# --noise for a mesh.  With a camera: sigma again from the model at each
# vertex's depth, as dm2mesh gave it (the kept mesh's model; measured the
# same faces, 6e-8 m apart at most: the positions are the file's floats).
run_case 0 "planarize --noise $V/view00.noise -o $V/m3.ply $V/k/1-mesh.ply"
check_num "--noise on a mesh with a camera: the depth image's faces" "$(info faces "$V/m3.ply")" == "$(info faces "$V/a.ply")"
run_case 0 "meshdist -H $V/m3.ply $V/a.ply"
check_num "... and the same surface (1e-6 m)" "$(awk '$1 == "hausdorff" { print $2 }' "$TMP/out")" "<" 1e-6
check_true "--noise on a mesh: its model in the header" grep -aq "^comment noise kinect" "$V/m3.ply"
# Without a camera: one figure.  Another tool's fused wall: a 2 m square
# bent by 2 mm (sin x sin y over a full period, what a fusion's registration
# leaves; zero on average) under 0.2 mm of noise, no camera, no sigma.  Its
# own residuals say 0.2 mm, and the bend is cut into planes (measured 13
# patches, 106x, 0.82 mm from the flat truth, which the mesh itself is);
# told its noise is 1 mm it is one plane (2 faces, 0.00 mm).  qemdecim to
# 2 faces: 0.91 mm.
W=$TMP/wall
mkdir -p "$W"
awk 'BEGIN {
	srand(1); n = 101; pi = 3.14159265358979
	print "ply\nformat ascii 1.0\nelement vertex " n * n
	print "property float x\nproperty float y\nproperty float z"
	print "element face " 2 * (n - 1) * (n - 1) "\nproperty list uchar int vertex_indices\nend_header"
	for (j = 0; j < n; j++)
		for (i = 0; i < n; i++) {
			x = 2 * i / (n - 1); y = 2 * j / (n - 1)
			printf "%.6f %.6f %.6f\n", x, y, 0.002 * sin(pi * x) * sin(pi * y) + 0.0004 * (rand() + rand() + rand() - 1.5)
		}
	for (j = 0; j < n - 1; j++)
		for (i = 0; i < n - 1; i++) {
			a = j * n + i
			printf "3 %d %d %d\n3 %d %d %d\n", a, a + 1, a + n + 1, a, a + n + 1, a + n
		}
}' >"$W/wall.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n-1 -1 0\n3 -1 0\n3 3 0\n-1 3 0\n3 0 1 2\n3 0 2 3\n' >"$W/truth.ply"
run_case 0 "planarize -v -o $W/est.ply $W/wall.ply 2>$W/est.err"
run_case 0 "planarize -v --noise poly:0.001,0,0 -o $W/told.ply $W/wall.ply 2>$W/told.err"
check_num "a bent wall, its noise estimated: more than one patch" "$(field "segplanes: patches" "$W/est.err")" ">" 1
check_num "... told 1 mm: one patch" "$(field "segplanes: patches" "$W/told.err")" == 1
check_num "... told 1 mm: sigma 1 mm" "$(field "segplanes: noise" "$W/told.err")" "==" 0.00100000005
meshdist -s 100000 "$W/est.ply" "$W/truth.ply" >"$W/est.dist"
meshdist -s 100000 "$W/told.ply" "$W/truth.ply" >"$W/told.dist"
meshdist -s 100000 "$W/wall.ply" "$W/truth.ply" >"$W/wall.dist"
check_num "... told: within 0.1 mm of the flat truth (mean)" "$(figure mean "$W/told.dist")" "<" 0.0001
check_num "... estimated: no closer than the mesh itself (half)" \
	"$(ratio "$(figure mean "$W/est.dist")" "$(figure mean "$W/wall.dist")")" ">" 0.5
check_num "... told: 1000x fewer faces" "$(field reduction "$W/told.err")" ">=" 1000
# The same wall as a triangle soup (every face its own three corners, as an
# STL file converted writes it): no two faces shared an edge, no face merged
# with another, and the debris step kept the largest piece, one triangle
# (reduction 20000).  Its copies of a position are one vertex again:
# 60000 - 10201 merged, the same model as the wall's.
awk '/^end_header/ { hdr = 0; body = 1; print "element vertex 60000"; print "property float x\nproperty float y\nproperty float z"
		print "element face 20000\nproperty list uchar int vertex_indices\nend_header"; next }
	NR <= 2 { print; next } body && n < 10201 { p[n++] = $0; next }
	body { f[nf++] = $0 }
	END { for (i = 0; i < nf; i++) { split(f[i], c, " "); for (k = 2; k <= 4; k++) print p[c[k]] }
		for (i = 0; i < nf; i++) printf "3 %d %d %d\n", 3 * i, 3 * i + 1, 3 * i + 2 }' "$W/wall.ply" >"$W/soup.ply"
check_num "a triangle soup: 3 corners a face" "$(info vertices "$W/soup.ply")" == 60000
run_case 0 "planarize -v --noise poly:0.001,0,0 -o $W/soup.model.ply $W/soup.ply 2>$W/soup.err"
check_num "... its copies welded" "$(field "segplanes: welded_vertices" "$W/soup.err")" == 49799
# E_*: each position once, as the wall's own vertices give them (a copy
# per corner weighed the border's positions less and the inner ones more).
meshdist "$W/wall.ply" "$W/soup.model.ply" >"$W/soup.e.dist"
e_ratio=$(ratio "$(field E_mean "$W/soup.err")" "$(figure mean "$W/soup.e.dist")")
check_num "... E_mean: the soup's positions each once (above)" "$e_ratio" ">" 0.999999
check_num "... E_mean: the soup's positions each once (below)" "$e_ratio" "<" 1.000001
# segplanes keeps the faces, in their order (labels map back onto the
# soup's faces); the vertices are the wall's 10201.
run_case 0 "segplanes -o $W/soup.seg.ply $W/soup.ply"
check_num "... segplanes: the soup's faces" "$(info faces "$W/soup.seg.ply")" == 20000
check_num "... segplanes: one vertex a position" "$(info vertices "$W/soup.seg.ply")" == 10201
check_num "... one patch, as the wall" "$(field "segplanes: patches" "$W/soup.err")" == 1
check_num "... the wall's faces" "$(info faces "$W/soup.model.ply")" == "$(info faces "$W/told.ply")"
meshdist -s 100000 "$W/soup.model.ply" "$W/truth.ply" >"$W/soup.dist"
check_num "... within 0.1 mm of the flat truth (mean)" "$(figure mean "$W/soup.dist")" "<" 0.0001
run_case 2 "planarize --noise kinect -o $W/k.ply $W/wall.ply" "" "planarize: --noise: $W/wall.ply: the noise model \"kinect 585 0.075 0.051 0.125\" grows with depth, and the mesh has no camera"
run_case 2 "planarize -K tum -o $W/k.ply $W/wall.ply" "" "planarize: -K: for depth images, and $W/wall.ply is a mesh"
# A fused scan (tsdfuse --carve of four views: watertight, 145 pieces, no
# camera) stays watertight; its floating debris (pieces of fewer than 64
# faces, --min-piece) is dropped, every other piece stays; with
# --min-piece 0, as many pieces as the fusion.
mkscene -q --views 4 --size 160x120 --fx 131.25 --noise kinect -o "$TMP/fv" >/dev/null
for i in 0 1 2 3; do
	dm2mesh -q --camera "$TMP/fv/view0$i.camera" --pose "$TMP/fv/view0$i.pose" \
		--noise "$TMP/fv/view0$i.noise" -o "$TMP/fv/v$i.ply" "$TMP/fv/view0$i.depth.pfm"
done
run_case 0 "tsdfuse -q --carve --voxel 0.04 -o $TMP/fv/fused.ply $TMP/fv/v0.ply $TMP/fv/v1.ply $TMP/fv/v2.ply $TMP/fv/v3.ply"
run_case 0 "planarize -v -o $TMP/fv/model.ply $TMP/fv/fused.ply 2>$TMP/fv/err"
check_num "fused: reduction 80x" "$(field reduction "$TMP/fv/err")" ">=" 80
check_num "fused: watertight in" "$(info border_edges "$TMP/fv/fused.ply")" == 0
check_num "fused: watertight out" "$(info border_edges "$TMP/fv/model.ply")" == 0
check_num "fused: free-form faces" "$(field "planedecim: free_faces" "$TMP/fv/err")" ">" 0
check_num "fused: none on a border (-v border_free_faces)" "$(field "planedecim: border_free_faces" "$TMP/fv/err")" == 0
check_num "fused: debris dropped" "$(field "planedecim: debris_pieces" "$TMP/fv/err")" ">" 0
check_num "fused: the other pieces kept" "$(info components "$TMP/fv/model.ply")" == \
	"$(($(info components "$TMP/fv/fused.ply") - $(field "planedecim: debris_pieces" "$TMP/fv/err")))"
run_case 0 "planarize -v --min-piece 0 -o $TMP/fv/all.ply $TMP/fv/fused.ply 2>$TMP/fv/all.err"
check_num "--min-piece 0: as many pieces" "$(info components "$TMP/fv/all.ply")" == "$(info components "$TMP/fv/fused.ply")"
check_num "--min-piece 0: watertight out" "$(info border_edges "$TMP/fv/all.ply")" == 0
check_num "--min-piece 0: nothing dropped" "$(field "planedecim: debris_faces" "$TMP/fv/all.err")" == 0
valid fused "$TMP/fv/model.ply"
# An OBJ with a texture (planarize's own) keeps it; an image given replaces it.
run_case 0 "planarize $C -o $V/h.obj $V/view00.depth.pfm $V/view00.color.png"
run_case 0 "planarize -o $V/i.obj $V/h.obj"
check_true "an OBJ's texture kept" grep -q '^map_Kd view00.color.png$' "$V/i.mtl"
run_case 0 "planarize -o $V/j.obj $V/h.obj $V/view00.patch.png"
check_true "an image given replaces it" grep -q '^map_Kd view00.patch.png$' "$V/j.mtl"
check_true "the exact scene (no camera, no sigma)" planarize -q -o "$V/scene-model.ply" "$V/scene.ply"
valid "the exact scene" "$V/scene-model.ply"

# A panorama: textured through planar views written beside the model.
P=$TMP/pano
mkscene -q --views 0 --panorama 1024x256 -o "$P" >/dev/null
run_case 0 "planarize -q --cylindrical ,,0 --pose $P/pano.pose -o $P/room.obj $P/pano.depth.pfm $P/pano.color.png"
check_true "panorama: one material per view used" test "$(grep -c '^map_Kd room.view0[0-7].png$' "$P/room.mtl")" -ge 6
check_true "panorama: the views beside the model" test -f "$P/room.view00.png"
valid panorama "$P/room.obj"
run_case 2 "planarize --cylindrical ,,0 $P/pano.depth.pfm $P/pano.color.png" "" "planarize: -o model is needed"

# Errors: one line; a failing stage by name; usage errors exit 2.
head -c 3000 samples/tum/TUM_depth.png >"$TMP/cut.png"
run_case 1 "planarize -K tum -o $TMP/x.ply $TMP/cut.png" "" "planarize: $TMP/cut.png: "
printf 'not a depth image\n' >"$TMP/text.png"
run_case 1 "planarize -o $TMP/x.ply $TMP/text.png" "" "planarize: $TMP/text.png: neither a depth image (PNG, PGM, JPEG or PFM) nor a mesh (PLY or OBJ)"
run_case 1 "planarize -K tum -o $TMP/x.ply $TMP/nonexistent.png" "" "planarize: $TMP/nonexistent.png: "
run_case 1 "planarize -K tum -o $TMP/x.ply $V/view00.depth.pfm" "" "planarize: dm2mesh: $V/view00.depth.pfm: the camera is 640x480 but the depth image is 320x240"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' >"$TMP/cloud.ply"
run_case 1 "planarize -o $TMP/x.ply $TMP/cloud.ply" "" "planarize: segplanes: $TMP/cloud.ply: no faces to segment (a point cloud"
run_case 1 "planarize $C -o $TMP/x.ply $V/view00.depth.pfm $TMP/nonexistent.png" "" "planarize: $TMP/nonexistent.png: "
run_case 1 "planarize $C --keep $V/view00.camera -o $TMP/x.ply $V/view00.depth.pfm" "" "planarize: --keep: $V/view00.camera: exists and is not a folder"
run_case 1 "planarize $C -o $TMP/no/such/x.ply $V/view00.depth.pfm" "" "planarize: $TMP/no/such/x.ply: "
run_case 1 "planarize -o $TMP/x.ply < /dev/null" "" "planarize: <stdin>: neither a depth image"
run_case 2 "planarize --bogus $V/view00.depth.pfm" "" "planarize: --bogus: unknown option"
run_case 2 "planarize -x $V/view00.depth.pfm" "" "planarize: -x: unknown option"
run_case 2 "planarize $V/view00.depth.pfm -j" "" "planarize: -j: option requires an argument"
run_case 2 "planarize -o $TMP/x.ply $V/view00.depth.pfm" "" "planarize: no camera: give -K, --camera or --cylindrical"
run_case 2 "planarize -K tum -o $TMP/x.ply $V/k/1-mesh.ply" "" "planarize: -K: for depth images, and $V/k/1-mesh.ply is a mesh"
run_case 2 "planarize -c 2 -n 5 $V/view00.depth.pfm" "" "planarize: -c and -n exclude each other"
run_case 2 "planarize -K tum a b c" "" "planarize: too many operands"
run_case 2 "planarize -K tum --image a.png b.png c.png" "" "planarize: the image is given twice"
run_case 2 "planarize -K tum b.png -" "" "planarize: the image cannot be standard input"
run_case 2 "planarize --fov 180 b.png" "" "planarize: --fov: "
run_case 2 "planarize --min-faces=x b.png" "" "planarize: --min-faces: "
run_case 0 "planarize --version | grep -q '^planarize (facet) '"

# The man page's examples run as written, from a folder with samples/.
awk '/^\.Sh EXAMPLES/ { f = 1; next } /^\.Sh / { f = 0 } !f { next }
	/^\.Bd -literal/ { b = 1; next } /^\.Ed/ { b = 0; next }
	/^\.Dl / { sub(/^\.Dl /, ""); print; next } b { print }' man/man1/planarize.1 |
	sed 's/\\e$/\\/' | awk '{ line = line $0 } /\\$/ { sub(/\\$/, "", line); next } { print line; line = "" }' >"$TMP/examples"
check_num "examples in planarize.1" "$(grep -c '^planarize ' "$TMP/examples")" == 4
mkdir "$TMP/ex"
ln -s "$(pwd)/samples" "$TMP/ex/samples"
ln -s "$(pwd)/tests" "$TMP/ex/tests"
while IFS= read -r ex; do
	run_case 0 "cd $TMP/ex && $ex >/dev/null 2>&1"
done <"$TMP/examples"
run_case 0 "planarize --help | head -n 1 | grep -q '^usage: planarize '"

finish

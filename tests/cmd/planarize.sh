# planarize: the whole planar pipeline (Kang et al. sec. 2-6) on a furnished
# synthetic room with Kinect-class noise, judged against the exact scene:
# the paper's Table 1 figures, the reduction, completeness, denoising, a
# valid mesh; then real Kinect frames.
. tests/lib.sh

figure() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }
info() { meshinfo "$2" | awk -v k="$1:" '$1 == k { print $2 }'; }

S=$TMP/room K=$TMP/stages
run_case 0 "mkscene --noise kinect-gauss:0.0012 -o $S"
run_case 0 "planarize -v --camera $S/view00.camera --pose $S/view00.pose --keep $K -o $TMP/room.obj $S/view00.depth.pfm $S/view00.color.png 2> $TMP/room.err"
run_case 0 "test -s $TMP/room.obj && test -s $TMP/room.mtl && grep -q '^map_Kd ' $TMP/room.mtl"
in=$(info faces $K/1-mesh.ply) out=$(info faces $K/5-model.ply)
# Twenty-odd visible planes need a few hundred faces, not the 600,000 of
# the dense mesh: the issue asks for 500 times fewer (measured: 585x, 1041
# faces).
check_num "reduction 500x ($in -> $out faces)" "$(awk -v a="$in" -v b="$out" 'BEGIN { print (b > 0 ? a / b : 0) }')" ">=" 500
# Completeness: the true visible surface (the noiseless depth meshed) lies
# within 5 mm of the model on average.
run_case 0 "dm2mesh --camera $S/view00.camera --pose $S/view00.pose -o $TMP/truth.ply $S/view00.truth.pfm"
run_case 0 "meshdist $TMP/truth.ply $K/5-model.ply > $TMP/complete.dist"
check_num "completeness: mean distance of the true surface to the model" "$(figure mean $TMP/complete.dist)" "<" 0.005
# Denoising (sec. 5): points on the model are closer to the true surface
# than points on the noisy input mesh.
run_case 0 "meshdist -s 200000 $K/5-model.ply $S/scene.ply > $TMP/model.dist"
run_case 0 "meshdist -s 200000 $K/1-mesh.ply $S/scene.ply > $TMP/noisy.dist"
check_num "the model is closer to the truth than the noisy mesh" "$(figure mean $TMP/model.dist)" "<" "$(figure mean $TMP/noisy.dist)"
# Table 1: the dense mesh's vertices to the model.
run_case 0 "meshdist $K/1-mesh.ply $K/5-model.ply > $TMP/table1.dist"
check_num "E_avg below 2 cm" "$(figure mean $TMP/table1.dist)" "<" 0.02
run_case 0 "grep -q '^planarize: reduction=' $TMP/room.err && grep -q '^planarize: E_mean=' $TMP/room.err"
# A valid mesh: no non-manifold edge, no degenerate face, every face wound
# like its patch's plane normal (which agrees with the input's faces).
check_num "no non-manifold edges" "$(info non_manifold_edges $K/5-model.ply)" == 0
check_num "no degenerate faces" "$(info degenerate_faces $K/5-model.ply)" == 0
# No face wound against its plane.  A few faces of the model are slivers of
# three vertices on one crease line (area about 1e-8 of a face's mean, the
# float positions' rounding): their orientation is noise, and they are
# counted apart; every other face must agree with its plane.
meshconv -a $K/5-model.ply | awk '
	/^element vertex/ { nv = $3 } /^element face/ { nf = $3 } /^element plane/ { np = $3 }
	/^end_header/ { s = 1; v = 0; f = 0; p = 0; next } s == 0 { next }
	v < nv { x[v] = $1; y[v] = $2; z[v] = $3; v++; next }
	f < nf { a = $2; b = $3; c = $4; pat[f] = $5
		ux = x[b] - x[a]; uy = y[b] - y[a]; uz = z[b] - z[a]; wx = x[c] - x[a]; wy = y[c] - y[a]; wz = z[c] - z[a]
		fx[f] = uy * wz - uz * wy; fy[f] = uz * wx - ux * wz; fz[f] = ux * wy - uy * wx; f++; next }
	p < np { px[p] = $1; py[p] = $2; pz[p] = $3; p++ }
	END { all = 0; for (i = 0; i < nf; i++) { ar[i] = sqrt(fx[i] ^ 2 + fy[i] ^ 2 + fz[i] ^ 2); all += ar[i] }
		bad = 0; slivers = 0; badarea = 0
		for (i = 0; i < nf; i++) {
			if (pat[i] < 0 || fx[i] * px[pat[i]] + fy[i] * py[pat[i]] + fz[i] * pz[pat[i]] > 0) continue
			if (ar[i] < 1e-6 * all / nf) slivers++; else bad++
			badarea += ar[i] }
		print bad, slivers, (all > 0 ? badarea / all : 1) }' > $TMP/flips
check_num "faces against their plane (slivers apart)" "$(awk '{ print $1 }' $TMP/flips)" == 0
check_num "area of the flipped slivers" "$(awk '{ print $3 }' $TMP/flips)" "<" 1e-6
# The wireframe's vertices all reached their planes (torn at occlusions).
check_num "projverts: vertices off their planes" "$(sed -n 's/^projverts: rejected=//p' $K/projverts.err)" == 0
check_num "projverts: torn at occlusions" "$(sed -n 's/^projverts: torn=//p' $K/projverts.err)" ">" 0

# Section 8, Fig. 8: the depth map read with a focal length 0.8 times the
# true one stretches depth by 1.25 against the lateral axes; --depth-scale-fix
# finds the scale that makes the walls orthogonal again.
run_case 0 "planarize -v --depth-scale-fix -K 420,420,319.5,239.5 --pose $S/view00.pose -o $TMP/scaled.ply $S/view00.depth.pfm $S/view00.color.png 2> $TMP/scaled.err"
scale=$(sed -n 's/^projverts: depth_scale=//p' $TMP/scaled.err)
check_num "depth scale found (true 1.25) within 1%" "$(awk -v s="$scale" 'BEGIN { d = s / 1.25 - 1; print (d < 0 ? -d : d) }')" "<" 0.01

# Real Kinect frames: the pipeline runs with its defaults and simplifies.
run_case 0 "planarize -v -K tum --keep $TMP/tum -o $TMP/tum.ply samples/tum/TUM_depth.png samples/tum/TUM_color.png 2> $TMP/tum.err"
check_num "TUM frame: 50x fewer faces" "$(awk -v a="$(info faces $TMP/tum/1-mesh.ply)" -v b="$(info faces $TMP/tum.ply)" 'BEGIN { print (b > 0 ? a / b : 0) }')" ">=" 50
run_case 0 "grep -a -q '^comment TextureFile ' $TMP/tum.ply"
F=../shared/data/7scenes_redkitchen/frames
if [ -d "$F" ]; then
	run_case 0 "planarize -K 7scenes --pose $F/frame-000000.pose.txt --keep $TMP/k -o $TMP/kitchen.obj $F/frame-000000.depth.png $F/frame-000000.color.jpg"
	run_case 0 "meshdist $TMP/k/1-mesh.ply $TMP/k/5-model.ply > $TMP/k.dist"
	check_num "7-Scenes frame: E_avg below 3 cm" "$(figure mean $TMP/k.dist)" "<" 0.03
fi

# Bad or odd input along the whole pipeline (issue: empty meshes, a single
# face, all faces coplanar, no image coordinates, point clouds, unlabelled
# faces): a clear message or a sensible result.
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n' > $TMP/empty.ply
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > $TMP/one.ply
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' > $TMP/cloud.ply
run_case 1 "segplanes -o $TMP/e1.ply $TMP/empty.ply" "" "segplanes: $TMP/empty.ply: no faces to segment (an empty mesh)"
run_case 1 "segplanes -o $TMP/c1.ply $TMP/cloud.ply" "" "segplanes: $TMP/cloud.ply: no faces to segment (a point cloud: mesh it first, e.g. with dm2mesh --points)"
run_case 1 "simpchain -o $TMP/u1.ply $TMP/one.ply" "" "simpchain: $TMP/one.ply: faces have no patch property (label them with segplanes)"
run_case 1 "projverts -o $TMP/u2.ply $TMP/one.ply" "" "projverts: $TMP/one.ply: no plane element (the planes of segplanes)"
run_case 1 "tripatch -o $TMP/u3.ply $TMP/one.ply" "" "tripatch: $TMP/one.ply: no edge element (tripatch reads simpchain's wireframe)"
# One face without image coordinates: the whole chain gives it back.
run_case 0 "segplanes $TMP/one.ply | simpchain | projverts | tripatch -o $TMP/one-out.ply"
check_num "a single face through the pipeline" "$(info faces $TMP/one-out.ply)" == 1
# A whole view of one plane: two triangles.
run_case 0 "mkscene --scene plane -o $TMP/plane"
run_case 0 "planarize --camera $TMP/plane/view00.camera -o $TMP/plane.ply $TMP/plane/view00.depth.pfm $TMP/plane/view00.color.png"
check_num "a view of one plane: two triangles" "$(info faces $TMP/plane.ply)" == 2

# Usage.
run_case 2 "planarize -K tum samples/tum/TUM_depth.png" "" "planarize: a depth image and an image are needed"
run_case 2 "planarize -K tum samples/tum/TUM_depth.png samples/tum/TUM_color.png" "" "planarize: -o model is needed"
run_case 2 "planarize --bogus -o x.ply a b" "" "planarize: --bogus: unknown option"
run_case 1 "planarize -K tum -o $TMP/x.ply nonexistent.png samples/tum/TUM_color.png" "" "planarize: nonexistent.png: cannot read"

finish

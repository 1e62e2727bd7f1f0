# JPEG wherever a program reads an image (each refused it before: "not a
# PNG or PFM image"): dm2mesh --image and meshshot's TextureFile,
# tsdfuse --image, a cyl2planar panorama, a pngsheet picture.  The image is
# the 64x48 piece of the 7-Scenes kitchen (tests/data/jpg_7scenes.jpg:
# channel ranges 163-255, 167-255, 146-255, as imginfo and Pillow give
# them), on the depth of a 64x48 view of mkscene's room.  The decoded
# pixels themselves are checked in tests/unit/test_image.c.
. tests/lib.sh
J=tests/data/jpg_7scenes.jpg
mkscene -q --views 1 --size 64x48 --fx 50 -o "$TMP/r"
R=$TMP/r

# dm2mesh records the JPEG; meshshot draws it from the mesh's camera over a
# blue background: every covered pixel is a texel (blue >= 146).
run_case 0 "dm2mesh --camera $R/view00.camera --image $J -o $TMP/d.ply $R/view00.depth.pfm"
check_true "TextureFile names the JPEG" grep -a -q "^comment TextureFile .*jpg_7scenes.jpg\$" "$TMP/d.ply"
run_case 0 "meshshot -v --view camera --bg 0,0,255 -o $TMP/shot.png $TMP/d.ply"
check_true "drawn textured" grep -q "meshshot: mode=texture" "$TMP/err"
run_case 0 "imginfo $TMP/shot.png"
check_true "covered pixels from the JPEG" grep -q "^channel 2 min 146 max 255 " "$TMP/out"

# tsdfuse colours the fused vertices from the JPEG: each is grey 128 (no
# view sees it) or inside the JPEG's channel ranges; most are seen.
K=$(awk '{ print $5 "," $6 "," $7 "," $8 }' "$R/view00.camera")
run_case 0 "tsdfuse --voxel 0.05 -K $K --poses $R/view00.pose --image $J -o $TMP/f.ply $R/view00.depth.pfm"
meshconv -a -o "$TMP/f.txt" "$TMP/f.ply"
counts=$(awk '/^end_header/ { h = 1; next } h && NF == 9 { n++
	if ($7 == 128 && $8 == 128 && $9 == 128) grey++
	else if ($7 < 163 || $8 < 167 || $9 < 146) out++ } END { print n + 0, grey + 0, out + 0 }' "$TMP/f.txt")
set -- $counts
check_num "fused vertices" "$1" ">" 10000
check_num "vertices coloured outside the JPEG's ranges" "$3" == 0
check_num "vertices no view sees" "$2" "<" "$(($1 / 20))"

# cyl2planar takes it as a panorama (no seam: it is no full circle).
run_case 0 "cyl2planar -v --no-seam-check --count 4 --fov 100 -o $TMP/v $J"
check_true "4 views of 25x72" sh -c "grep -q 'written=4' $TMP/err && grep -q 'view_size=25x72' $TMP/err"
# pngsheet: one 64x48 cell.
run_case 0 "pngsheet -v -o $TMP/sheet.png $J"
check_true "a 64x48 cell" grep -q "pngsheet: cell=64x48" "$TMP/err"
finish

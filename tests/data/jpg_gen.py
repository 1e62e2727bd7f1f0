#!/usr/bin/env python3
"""Write the JPEG fixtures tests/data/jpg_*, their imginfo goldens (.info),
and the bad JPEG inputs tests/bad/img_jpeg_*.

The goldens come from Pillow's decoder (its own libjpeg-turbo build, not the
system library facet links), so the reader is checked against an independent
decode.  jpegtran (Debian's libjpeg-turbo-progs) crops the 7-Scenes frame
without decoding it.  Run from the top folder with the 7-Scenes frame at
/work/shared/data; the outputs are committed, so this runs only when a fixture
is added or changed."""
import io
import struct
import subprocess

import numpy as np
from PIL import Image

D = 'tests/data/'
B = 'tests/bad/'
FRAME = '/work/shared/data/7scenes_redkitchen/frames/frame-000000.color.jpg'


def put(path, data):
    with open(path, 'wb') as f:
        f.write(data)


def info(path, shown=None):
    """imginfo's output for path, from Pillow's decode."""
    im = Image.open(path)
    im.load()
    a = np.asarray(im.convert('L' if im.mode == 'L' else 'RGB')).astype(np.float64)
    if a.ndim == 2:
        a = a[:, :, None]
    h, w, ch = a.shape
    out = ['file %s' % (shown or path), 'format jpeg', 'width %d' % w, 'height %d' % h,
           'channels %d' % ch, 'type u8']
    for c in range(ch):
        v = a[:, :, c]
        out.append('channel %d min %.17g max %.17g mean %.17g zero %d nonfinite 0' %
                   (c, v.min(), v.max(), v.sum() / v.size, int((v == 0).sum())))
    return '\n'.join(out) + '\n'


def jpegtran(args, data):
    return subprocess.run(['jpegtran'] + args, input=data, stdout=subprocess.PIPE,
                          check=True).stdout


def save(im, **kw):
    buf = io.BytesIO()
    im.save(buf, 'JPEG', **kw)
    return buf.getvalue()


def segments(data):
    """(offset, marker, length) of each marker segment before the scan data."""
    out, p = [], 2
    while p < len(data):
        assert data[p] == 0xff
        m = data[p + 1]
        n = struct.unpack('>H', data[p + 2:p + 4])[0]
        out.append((p, m, n))
        if m == 0xda:
            break
        p += 2 + n
    return out


def sof(data):
    return next(p for p, m, n in segments(data) if 0xc0 <= m <= 0xcf and m not in (0xc4, 0xc8, 0xcc))


# --- good fixtures ----------------------------------------------------------
frame = open(FRAME, 'rb').read()
# 64x48 of the kitchen at (320, 240), cut on 16-pixel MCU boundaries, the
# original 4:2:0 coefficients unchanged.
crop = jpegtran(['-crop', '64x48+320+240', '-copy', 'none'], frame)
put(D + 'jpg_7scenes.jpg', crop)
put(D + 'jpg_7scenes_prog.jpg', jpegtran(['-progressive', '-copy', 'none'], crop))
put(D + 'jpg_7scenes_arith.jpg', jpegtran(['-arithmetic', '-copy', 'none'], crop))
put(D + 'jpg_7scenes_restart.jpg', jpegtran(['-restart', '1', '-copy', 'none'], crop))
rgb = Image.open(io.BytesIO(crop)).convert('RGB')
put(D + 'jpg_grey.jpg', save(rgb.convert('L'), quality=90))
# Pillow writes CMYK with an Adobe marker and inverted inks, as Photoshop does.
put(D + 'jpg_cmyk.jpg', save(rgb.convert('CMYK'), quality=95))
# Four 8x8 blocks of flat, known colours, 4:4:4 at quality 100: a flat block
# is its DC coefficient alone, so the decode is the colour within rounding.
tiles = Image.new('RGB', (16, 16))
for i, c in enumerate([(255, 0, 0), (0, 255, 0), (0, 0, 255), (200, 150, 50)]):
    tiles.paste(c, ((i % 2) * 8, (i // 2) * 8, (i % 2) * 8 + 8, (i // 2) * 8 + 8))
put(D + 'jpg_tiles.jpg', save(tiles, quality=100, subsampling=0))

# meshshot's texture atlas (shot_gen.py) as JPEG: 16x16 cells of pure
# colour, quality 100, 4:4:4, so each texel is within a level or two.
put(D + 'shot_atlas.jpg', save(Image.open(D + 'shot_atlas.png').convert('RGB'), quality=100,
                               subsampling=0))

for n in ['7scenes', '7scenes_prog', '7scenes_arith', '7scenes_restart', 'grey', 'cmyk',
          'tiles']:
    put(D + 'jpg_%s.info' % n, info(D + 'jpg_%s.jpg' % n).encode())

# --- bad inputs -------------------------------------------------------------
good = open(D + 'jpg_tiles.jpg', 'rb').read()
at = sof(good)


def with_size(data, w, h):
    p = sof(data) + 5
    return data[:p] + struct.pack('>HH', h, w) + data[p + 4:]


# 626 bytes claiming 60000x60000 (3.6 G pixels), and under 2^31 pixels but
# far more than 626 bytes can code.
put(B + 'img_jpeg_huge.jpg', with_size(good, 60000, 60000))
put(B + 'img_jpeg_lying.jpg', with_size(good, 30000, 30000))
prog = open(D + 'jpg_7scenes_prog.jpg', 'rb').read()
put(B + 'img_jpeg_lying_prog.jpg', with_size(prog, 40000, 40000))
put(B + 'img_jpeg_zero_width.jpg', with_size(good, 0, 16))
put(B + 'img_jpeg_soi.jpg', b'\xff\xd8\xff')
put(B + 'img_jpeg_header_cut.jpg', good[:at + 6])
put(B + 'img_jpeg_truncated.jpg', crop[:len(crop) * 2 // 3])
put(B + 'img_jpeg_prog_truncated.jpg', prog[:len(prog) // 2])
# Entropy data replaced by a run of one byte: libjpeg warns and would fill
# in grey.
scan = segments(crop)[-1]
body = scan[0] + 2 + scan[2]
put(B + 'img_jpeg_corrupt.jpg', crop[:body + 40] + b'\xff\x00' * 200 + crop[-2:])
# 12-bit samples (SOF1, precision 12): not in an 8-bit libjpeg.
p12 = bytearray(good)
p12[at + 1] = 0xc1
p12[at + 4] = 12
put(B + 'img_jpeg_12bit.jpg', bytes(p12))
# Lossless JPEG (SOF3).
p3 = bytearray(good)
p3[at + 1] = 0xc3
put(B + 'img_jpeg_lossless.jpg', bytes(p3))
# Two components: no colour space to read them in.
g = save(Image.new('L', (8, 8), 100))
s = sof(g)
two = g[:s + 2] + struct.pack('>H', 8 + 3 * 2) + g[s + 4:s + 9] + bytes([2, 1, 0x11, 0, 2, 0x11, 0]) + \
    g[s + 2 + 11:]
put(B + 'img_jpeg_two_components.jpg', two)

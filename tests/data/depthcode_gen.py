#!/usr/bin/env python3
"""Cut the depth-code fixtures from the shared data (see samples/README.md).

nyu_depth_crop.pgm: the 160x120 piece at (400, 100) of NYU Depth v2's
NYU_depth.pgm (raw Kinect disparity codes), its samples copied byte for byte,
so little-endian as the original, under a new P5 header.

sun_depth_crop.png: the 160x120 piece at (240, 120) of SUN RGB-D's
SUN_depth.png (millimetres with their bits rotated), its 16-bit samples
unchanged in a PNG written here (one IDAT, filter 0).  The piece holds the
corridor's far end, 919 pixels beyond 8.192 m where the rotation wraps.

Both from isl-org/Open3D at ed30e3b6, examples/test_data/RGBD/other_formats/,
as copied into the shared data.  Run from the top folder:
    python3 tests/data/depthcode_gen.py ../shared/data/rgbd_single_frames_formats
"""
import struct
import sys
import zlib

X_NYU, Y_NYU, X_SUN, Y_SUN, W, H = 400, 100, 240, 120, 160, 120


def png_rows(path):
    """The 16-bit grey rows of a non-interlaced PNG (filters undone)."""
    data = open(path, 'rb').read()
    pos, idat, width = 8, b'', None
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            width, height, depth, colour, _, _, interlace = struct.unpack('>IIBBBBB', body)
            assert depth == 16 and colour == 0 and interlace == 0
        elif kind == b'IDAT':
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), 2 * width, [], bytearray(2 * width)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 2] if i >= 2 else 0
            b, c = prev[i], prev[i - 2] if i >= 2 else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return rows


def write_png16(path, rows, width):
    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
    raw = b''.join(b'\0' + r for r in rows)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, len(rows), 16, 0, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def main(src):
    pgm = open(src + '/NYU_depth.pgm', 'rb').read()
    head = b'P5 640 480 65535\n'
    assert pgm.startswith(head)
    body = pgm[len(head):]
    with open('tests/data/nyu_depth_crop.pgm', 'wb') as f:
        f.write(b'P5\n%d %d\n65535\n' % (W, H))
        for y in range(Y_NYU, Y_NYU + H):
            f.write(body[2 * (y * 640 + X_NYU):2 * (y * 640 + X_NYU + W)])
    rows = png_rows(src + '/SUN_depth.png')
    write_png16('tests/data/sun_depth_crop.png', [r[2 * X_SUN:2 * (X_SUN + W)] for r in rows[Y_SUN:Y_SUN + H]], W)


main(sys.argv[1])

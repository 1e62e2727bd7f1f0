#!/usr/bin/env python3
"""Write the image fixtures tests/data/img_* and bad inputs tests/bad/img_*.

PNGs are built here with zlib alone, not libpng, so the reader is checked
against an independent encoder.  Run from the top folder; the outputs are
committed, so this runs only when a fixture is added or changed."""
import math
import struct
import zlib

def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))

SIG = b'\x89PNG\r\n\x1a\n'

def ihdr(w, h, depth, ctype, interlace=0):
    return chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, depth, ctype, 0, 0, interlace))

def pack_row(samples, depth):
    """Samples of one row (ints) to bytes at the given bit depth."""
    if depth == 8:
        return bytes(samples)
    if depth == 16:
        return b''.join(struct.pack('>H', v) for v in samples)
    out, acc, nbits = bytearray(), 0, 0
    for v in samples:
        acc = (acc << depth) | v
        nbits += depth
        if nbits == 8:
            out.append(acc)
            acc, nbits = 0, 0
    if nbits:
        out.append(acc << (8 - nbits))
    return bytes(out)

ADAM7 = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]

def png(rows, depth, ctype, extra=b'', interlace=0):
    """rows: list of rows, each a flat list of samples (channels interleaved)."""
    h = len(rows)
    spp = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ctype]
    w = len(rows[0]) // spp
    raw = bytearray()
    if not interlace:
        for r in rows:
            raw += b'\0' + pack_row(r, depth)
    else:
        for x0, y0, dx, dy in ADAM7:
            for y in range(y0, h, dy):
                px = [rows[y][x * spp:(x + 1) * spp] for x in range(x0, w, dx)]
                if px:
                    raw += b'\0' + pack_row([v for p in px for v in p], depth)
    return (SIG + ihdr(w, h, depth, ctype, interlace) + extra +
            chunk(b'IDAT', zlib.compress(bytes(raw), 9)) + chunk(b'IEND', b''))

def pfm(rows_top_down, channels, little=True):
    """rows: top row first, each a flat list of floats; stored bottom-up."""
    h = len(rows_top_down)
    w = len(rows_top_down[0]) // channels
    head = b'%s\n%d %d\n%s\n' % (b'PF' if channels == 3 else b'Pf', w, h,
                                  b'-1.0' if little else b'1.0')
    fmt = '<f' if little else '>f'
    body = b''.join(struct.pack(fmt, v) for r in reversed(rows_top_down) for v in r)
    return head + body

def put(path, data):
    with open(path, 'wb') as f:
        f.write(data)

D = 'tests/data/'
B = 'tests/bad/'

# --- good fixtures ----------------------------------------------------------
put(D + 'img_grey8.png', png([[0, 10, 255], [7, 0, 128]], 8, 0))
put(D + 'img_grey16.png', png([[0, 1000, 65535], [258, 0, 4660]], 16, 0))
put(D + 'img_ga8.png', png([[1, 255, 2, 0], [3, 128, 0, 64]], 8, 4))
put(D + 'img_rgb8.png', png([[255, 0, 0, 0, 255, 0], [0, 0, 255, 10, 20, 30]], 8, 2))
put(D + 'img_rgba16.png', png([[1, 2, 3, 65535, 40000, 0, 513, 0]], 16, 6))
put(D + 'img_grey1.png', png([[1, 0, 1, 1, 0, 0, 1, 0, 1]], 1, 0))
put(D + 'img_grey4.png', png([[0, 15, 7], [1, 2, 3]], 4, 0))
# 2-bit palette of 3 colours; the second one half transparent (tRNS).
put(D + 'img_pal2.png', png([[0, 1, 2], [2, 1, 0]], 2, 3,
                            chunk(b'PLTE', bytes([10, 20, 30, 40, 50, 60, 70, 80, 90])) +
                            chunk(b'tRNS', bytes([255, 128]))))
# 5x5 Adam7-interlaced grey: value 10*y + x.
put(D + 'img_adam7.png', png([[10 * y + x for x in range(5)] for y in range(5)], 8, 0,
                             interlace=1))
put(D + 'img_depth.pfm', pfm([[1.5, 0.0, math.nan], [math.inf, 2.25, -1.0]], 1))
put(D + 'img_rgb_be.pfm', pfm([[1, 2, 3, 4, 5, 6], [7, 8, 9, 10, 11, 12]], 3, little=False))
# CR LF line ends and extra blanks, as some writers produce.
put(D + 'img_crlf.pfm', b'Pf\r\n2  1\r\n-1\r\n' + struct.pack('<2f', 0.5, 10.0))

# --- bad inputs -------------------------------------------------------------
good = png([[0, 10, 255], [7, 0, 128]], 8, 0)
idat_at = good.index(b'IDAT') - 4
put(B + 'img_empty.png', b'')
put(B + 'img_text.png', b'hello, this is not an image\n')
put(B + 'img_sig_cut.png', SIG[:5])
put(B + 'img_header_only.png', SIG + ihdr(3, 2, 8, 0))
put(B + 'img_cut_idat.png', good[:idat_at + 12])
crc = bytearray(good)
crc[idat_at - 1] ^= 0xff   # last byte of IHDR's CRC
put(B + 'img_bad_crc.png', bytes(crc))
put(B + 'img_palette16.png', SIG + ihdr(3, 2, 16, 3) + chunk(b'IEND', b''))
put(B + 'img_depth7.png', SIG + ihdr(3, 2, 7, 0) + chunk(b'IEND', b''))
put(B + 'img_zero_width.png', SIG + ihdr(0, 2, 8, 0) + good[idat_at:])
put(B + 'img_zero_height.png', SIG + ihdr(3, 0, 8, 0) + good[idat_at:])
put(B + 'img_huge.png', SIG + ihdr(1000000, 1000000, 8, 0) + good[idat_at:])
# Under 2^31 pixels but 12.8 GB of 16-bit RGBA from a 60-byte file.
put(B + 'img_huge_rgba.png', SIG + ihdr(40000, 40000, 16, 6) + good[idat_at:])
# IDAT that inflates to fewer rows than IHDR declares.
put(B + 'img_short_idat.png', SIG + ihdr(3, 9, 8, 0) + good[idat_at:])
put(B + 'img_bad_zlib.png', SIG + ihdr(3, 2, 8, 0) + chunk(b'IDAT', b'\x78\x9cgarbage') +
    chunk(b'IEND', b''))
put(B + 'img_no_iend.png', good[:good.index(b'IEND') - 4])

floats = struct.pack('<6f', *range(6))
put(B + 'img_neg_size.pfm', b'Pf\n-3 2\n-1\n' + floats)
put(B + 'img_zero_size.pfm', b'Pf\n0 2\n-1\n')
put(B + 'img_lying.pfm', b'Pf\n300 200\n-1\n' + floats)
put(B + 'img_too_long.pfm', b'Pf\n3 2\n-1\n' + floats + b'\0\0\0\0')
put(B + 'img_junk_scale.pfm', b'Pf\n3 2\nabc\n' + floats)
put(B + 'img_zero_scale.pfm', b'Pf\n3 2\n0\n' + floats)
put(B + 'img_nan_scale.pfm', b'Pf\n3 2\nnan\n' + floats)
put(B + 'img_truncated.pfm', b'PF\n3 2\n-1\n' + floats)
put(B + 'img_header_cut.pfm', b'PF\n3 ')
put(B + 'img_huge_side.pfm', b'Pf\n99999999999 1\n-1\n' + floats)
put(B + 'img_too_many_pixels.pfm', b'Pf\n16777216 16777216\n-1\n' + floats)
put(B + 'img_width_junk.pfm', b'Pf\n3x 2\n-1\n' + floats)

# --- big pictures from small files (bounded by the programs' stated limits) --
def blank_1bit(w, h):
    """A w x h 1-bit grey PNG, all black: (w/8 + 1) * h zero bytes deflated."""
    raw = (b'\0' * ((w + 7) // 8 + 1)) * h
    return SIG + ihdr(w, h, 1, 0) + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b'')

# 4000x4000 (16 M pixels, 48 MB as RGB) in 2 KB: 60 of them on one sheet.
# Neither is a fuzz seed (fuzz/run skips big_*): a valid big picture is no
# finding.
put(D + 'big_4000_1bit.png', blank_1bit(4000, 4000))
# 17000x17000 (289 M pixels, 867 MB as RGB) in 35 KB: over pngsheet's 2^28
# and meshshot's 2^26 texture pixels.
put(D + 'big_17000_1bit.png', blank_1bit(17000, 17000))

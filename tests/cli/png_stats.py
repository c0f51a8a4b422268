#!/usr/bin/env python3
"""Statistics of 8-bit RGBA PNGs for the CLI tests (no imaging library: zlib + the PNG filters).

  png_stats.py mean A.png [X0 Y0 X1 Y1]            mean RGB byte value (of the pixel rectangle)
  png_stats.py diff A.png B.png [X0 Y0 X1 Y1]      mean absolute RGB difference (same size images)
  png_stats.py size A.png                          "WIDTH HEIGHT"
Rectangles are half-open pixel ranges, rows from the top; negative values count from the right/bottom.
"""
import struct
import sys
import zlib


def load(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(path + ': not a PNG')
    pos, idat, w, h = 8, b'', 0, 0
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', body[:10])
            if depth != 8 or ctype != 6:
                sys.exit(path + ': expected 8-bit RGBA')
        if kind == b'IDAT':
            idat += body
    raw = zlib.decompress(idat)
    stride = w * 4
    prev = bytearray(stride)
    rows = []
    i = 0
    for _ in range(h):
        f = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - 4] if x >= 4 else 0
            b = prev[x]
            c = prev[x - 4] if x >= 4 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows


def rect(w, h, args):
    if not args:
        return 0, 0, w, h
    x0, y0, x1, y1 = (int(v) for v in args)
    x0, x1 = (v + w if v < 0 else v for v in (x0, x1))
    y0, y1 = (v + h if v < 0 else v for v in (y0, y1))
    return x0, y0, x1, y1


def main():
    cmd = sys.argv[1]
    if cmd == 'mean':
        w, h, rows = load(sys.argv[2])
        x0, y0, x1, y1 = rect(w, h, sys.argv[3:])
        total = sum(rows[y][4 * x + c] for y in range(y0, y1) for x in range(x0, x1) for c in range(3))
        print('%.3f' % (total / ((x1 - x0) * (y1 - y0) * 3)))
    elif cmd == 'size':
        w, h, _ = load(sys.argv[2])
        print('%d %d' % (w, h))
    elif cmd == 'diff':
        wa, ha, ra = load(sys.argv[2])
        wb, hb, rb = load(sys.argv[3])
        if (wa, ha) != (wb, hb):
            sys.exit('sizes differ: %dx%d and %dx%d' % (wa, ha, wb, hb))
        x0, y0, x1, y1 = rect(wa, ha, sys.argv[4:])
        total = sum(abs(ra[y][4 * x + c] - rb[y][4 * x + c]) for y in range(y0, y1) for x in range(x0, x1)
                    for c in range(3))
        print('%.3f' % (total / ((x1 - x0) * (y1 - y0) * 3)))
    else:
        sys.exit(__doc__)


main()

#!/usr/bin/env python3
"""Pixels of the EXRs vplgi writes (scanline, float or half, no/ZIPS/ZIP compression) for the CLI tests,
with no imaging library: the header, zlib, and OpenEXR's predictor and byte interleave undone.

  exr_stats.py same A.exr B.exr   exit 0 when the two images have bit-identical pixels (the header's
                                  capture date and other attributes are ignored), 1 otherwise
  exr_stats.py mean A.exr         mean of R, G, B, and the count of NaN/Inf values
"""
import math
import struct
import sys
import zlib

PIXEL_SIZES = {1: 2, 2: 4}  # HALF, FLOAT (UINT is never written by vplgi)
LINES_PER_CHUNK = {0: 1, 2: 1, 3: 16}  # NONE, ZIPS, ZIP


def read_header(data, path):
    if data[:4] != b'\x76\x2f\x31\x01':
        sys.exit(path + ': not an OpenEXR file')
    version = struct.unpack('<I', data[4:8])[0]
    if version & 0x1e00:  # tiled, long names, deep, multipart
        sys.exit(path + ': only single-part scanline EXRs are read here')
    pos, attributes = 8, {}
    while data[pos] != 0:
        end = data.index(b'\0', pos)
        name = data[pos:end].decode()
        type_end = data.index(b'\0', end + 1)
        size = struct.unpack('<i', data[type_end + 1:type_end + 5])[0]
        attributes[name] = data[type_end + 5:type_end + 5 + size]
        pos = type_end + 5 + size
    return attributes, pos + 1


def channels_of(chlist):
    pos, channels = 0, []
    while chlist[pos] != 0:
        end = chlist.index(b'\0', pos)
        pixel_type = struct.unpack('<i', chlist[end + 1:end + 5])[0]
        channels.append((chlist[pos:end].decode(), pixel_type))
        pos = end + 17  # name, pixel type, pLinear + reserved, x and y sampling
    return channels


def undo_zip(raw, expected):
    data = bytearray(zlib.decompress(raw))
    for i in range(1, len(data)):  # the predictor: each byte was stored as a difference + 128
        data[i] = (data[i - 1] + data[i] - 128) & 0xff
    half = (len(data) + 1) // 2
    out = bytearray(len(data))
    out[0::2], out[1::2] = data[:half], data[half:]
    if len(out) != expected:
        sys.exit('a chunk decompressed to %d bytes, expected %d' % (len(out), expected))
    return bytes(out)


def load(path):
    data = open(path, 'rb').read()
    attributes, pos = read_header(data, path)
    x0, y0, x1, y1 = struct.unpack('<4i', attributes['dataWindow'])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    compression = attributes['compression'][0]
    if compression not in LINES_PER_CHUNK:
        sys.exit('%s: compression %d is not read here' % (path, compression))
    channels = channels_of(attributes['channels'])
    line_bytes = sum(width * PIXEL_SIZES[t] for _, t in channels)
    per_chunk = LINES_PER_CHUNK[compression]
    chunks = (height + per_chunk - 1) // per_chunk
    offsets = struct.unpack('<%dQ' % chunks, data[pos:pos + 8 * chunks])
    planes = {name: [] for name, _ in channels}
    pixels = b''
    for offset in offsets:
        y, size = struct.unpack('<2i', data[offset:offset + 8])
        lines = min(per_chunk, y1 - y + 1)
        raw = data[offset + 8:offset + 8 + size]
        expected = lines * line_bytes
        block = raw if compression == 0 or size == expected else undo_zip(raw, expected)
        pixels += block
        at = 0
        for _ in range(lines):
            for name, pixel_type in channels:  # per line, channel after channel (sorted by name)
                n = width * PIXEL_SIZES[pixel_type]
                fmt = '<%d%s' % (width, 'e' if pixel_type == 1 else 'f')
                planes[name].extend(struct.unpack(fmt, block[at:at + n]))
                at += n
    return width, height, planes, (channels, pixels)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == 'same':
        a, b = load(sys.argv[2]), load(sys.argv[3])
        sys.exit(0 if a[:2] == b[:2] and a[3] == b[3] else 1)  # the decoded bytes, NaN payloads too
    if len(sys.argv) == 3 and sys.argv[1] == 'mean':
        width, height, planes, _ = load(sys.argv[2])
        values = [v for k in 'RGB' for v in planes[k]]
        bad = sum(1 for v in values if not math.isfinite(v))
        finite = [v for v in values if math.isfinite(v)]
        print('%.6g %d' % (sum(finite) / max(1, len(finite)), bad))
        return
    sys.exit(__doc__)


main()

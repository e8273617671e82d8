#!/usr/bin/env python3
"""check_png.py FILE...: exits 1 unless every FILE is a complete PNG (signature, every chunk's CRC,
IEND last, and image data that inflates to exactly the rows its header declares). A half-written
file fails one of these."""
import struct
import sys
import zlib


def check(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return "no PNG signature"
    pos, idat, header, last = 8, b"", None, None
    while pos < len(data):
        if pos + 12 > len(data):
            return "a chunk is cut off at byte %d" % pos
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length or pos + 12 + length > len(data):
            return "chunk %r is cut off" % kind
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            return "chunk %r fails its CRC" % kind
        if kind == b"IHDR":
            header = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        last = kind
        pos += 12 + length
    if last != b"IEND":
        return "no IEND chunk at the end"
    if header is None:
        return "no IHDR chunk"
    width, height, depth, colour = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour, 1)
    expected = height * (1 + width * channels * depth // 8)
    try:
        pixels = zlib.decompress(idat)
    except zlib.error as e:
        return "image data does not inflate: %s" % e
    if len(pixels) != expected:
        return "image data holds %d bytes, expected %d" % (len(pixels), expected)
    return None


def main():
    bad = 0
    for path in sys.argv[1:]:
        why = check(path)
        if why:
            print("check_png: %s: %s" % (path, why))
            bad += 1
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()

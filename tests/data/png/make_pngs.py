#!/usr/bin/env python3
"""Writes the PNG files of tests/image_test.cpp's PngFilesDecodeAsOpenImageIODecodesThem: one per
kind of file libpng expands (palette, gray, alpha, 1/4/8/16 bits, tRNS, Adam7 interlacing), with
the standard library's zlib alone, so that what they hold is written here, not by a decoder."""
import struct, zlib, pathlib

def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))

def pack_row(samples, bits):
    if bits >= 8:
        fmt = '>' + ('B' if bits == 8 else 'H') * len(samples)
        return struct.pack(fmt, *samples)
    out, acc, n = bytearray(), 0, 0
    for s in samples:
        acc = (acc << bits) | s
        n += bits
        if n == 8:
            out.append(acc); acc, n = 0, 0
    if n:
        out.append(acc << (8 - n))
    return bytes(out)

ADAM7 = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]

def png(path, width, height, bits, color_type, pixel, extra=b'', interlace=False):
    """pixel(x, y) -> tuple of the samples of one pixel."""
    raw = bytearray()
    passes = ADAM7 if interlace else [(0, 0, 1, 1)]
    for x0, y0, dx, dy in passes:
        for y in range(y0, height, dy):
            xs = range(x0, width, dx)
            if not xs:
                continue
            raw.append(0)  # filter type None
            raw += pack_row([s for x in xs for s in pixel(x, y)], bits)
    ihdr = struct.pack('>IIBBBBB', width, height, bits, color_type, 0, 0, 1 if interlace else 0)
    data = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + extra + chunk(b'IDAT', zlib.compress(bytes(raw))) + chunk(b'IEND', b'')
    pathlib.Path(path).write_bytes(data)

here = pathlib.Path(__file__).parent
png(here / 'rgb8.png', 3, 2, 8, 2, lambda x, y: (40 * x, 100 + 50 * y, 255 - 30 * x))
png(here / 'rgba16.png', 2, 2, 16, 6, lambda x, y: (1000 * x + 7, 65535 - 900 * y, 30000, 20000 + 5 * x))
png(here / 'gray8.png', 3, 1, 8, 0, lambda x, y: (10 + 100 * x,))
png(here / 'grayalpha8.png', 2, 2, 8, 4, lambda x, y: (60 * x + 30 * y, 255 - 40 * x))
png(here / 'gray1.png', 9, 2, 1, 0, lambda x, y: ((x + y) % 2,))
palette = bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128])
png(here / 'palette4_trns.png', 5, 2, 4, 3, lambda x, y: ((x + 2 * y) % 4,),
    extra=chunk(b'PLTE', palette) + chunk(b'tRNS', bytes([255, 128, 0])))
png(here / 'rgb8_interlaced.png', 9, 10, 8, 2, lambda x, y: (25 * x, 20 * y, (7 * x + 11 * y) % 256), interlace=True)

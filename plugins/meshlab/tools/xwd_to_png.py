#!/usr/bin/env python3
"""Converts an X window dump (XWD, as `Xvfb -fbdir` keeps its screen) to PNG
with the standard library only (ImageMagick is not a dependency).

    xwd_to_png.py SCREEN.xwd OUT.png [--crop X,Y,W,H]

Handles the 24/32-bit TrueColor dumps Xvfb writes."""
import argparse
import struct
import sys
import zlib


def read_xwd(path):
    with open(path, "rb") as f:
        data = f.read()
    fields = struct.unpack(">25I", data[:100])
    (header_size, _version, _format, depth, width, height, _xoff, byte_order, _unit, _bit_order,
     _pad, bits_per_pixel, bytes_per_line, _visual, red_mask, green_mask, blue_mask, _bits_rgb,
     _cmap_entries, ncolors) = fields[:20]
    if bits_per_pixel != 32 or depth not in (24, 32):
        sys.exit(f"unsupported XWD: depth {depth}, {bits_per_pixel} bits per pixel")
    offset = header_size + 12 * ncolors
    endian = "<" if byte_order == 0 else ">"

    def shift(mask):
        return (mask & -mask).bit_length() - 1

    shifts = [shift(m) for m in (red_mask, green_mask, blue_mask)]
    rows = []
    for y in range(height):
        start = offset + y * bytes_per_line
        words = struct.unpack(endian + f"{width}I", data[start:start + 4 * width])
        row = bytearray(3 * width)
        for x, w in enumerate(words):
            row[3 * x] = (w >> shifts[0]) & 255
            row[3 * x + 1] = (w >> shifts[1]) & 255
            row[3 * x + 2] = (w >> shifts[2]) & 255
        rows.append(bytes(row))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, payload):
        body = kind + payload
        return struct.pack(">I", len(payload)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + r for r in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("xwd")
    p.add_argument("png")
    p.add_argument("--crop", help="X,Y,W,H")
    a = p.parse_args()
    width, height, rows = read_xwd(a.xwd)
    if a.crop:
        x, y, w, h = (int(v) for v in a.crop.split(","))
        rows = [r[3 * x:3 * (x + w)] for r in rows[y:y + h]]
        width, height = w, h
    write_png(a.png, width, height, rows)


if __name__ == "__main__":
    main()

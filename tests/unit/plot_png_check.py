#!/usr/bin/env python3
"""Decode the PNG figures test_plot left (OUTDIR/plots/*.png) with zlib alone and check that
each one is a drawing: the whole image decodes, the background is white, between 1 % and 60 %
of the pixels are not, and at least four colours appear (axes, grid, phase lines, curves).

usage: plot_png_check.py OUTDIR...   prints 'N passed, N failed'; exit 1 on any failure."""
import struct
import sys
import zlib
from pathlib import Path


def decode(path):
    data = path.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("no PNG signature")
    pos, idat, ihdr = 8, [], None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]:
            raise ValueError(f"bad CRC in chunk {kind!r}")
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        raise ValueError(f"unexpected format depth={depth} colour type={ctype}")
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    if len(raw) != h * (stride + 1):
        raise ValueError(f"{len(raw)} bytes decoded, expected {h * (stride + 1)}")
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        cur = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                cur[i] = (cur[i] + cur[i - bpp]) & 255
        elif f == 2:
            for i in range(stride):
                cur[i] = (cur[i] + prev[i]) & 255
        elif f == 3:
            for i in range(stride):
                left = cur[i - bpp] if i >= bpp else 0
                cur[i] = (cur[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = cur[i - bpp] if i >= bpp else 0
                b, c = prev[i], prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                cur[i] = (cur[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif f != 0:
            raise ValueError(f"row {y}: filter type {f}")
        rows.append(bytes(cur))
        prev = cur
    return w, h, bpp, rows


def check(path):
    w, h, bpp, rows = decode(path)
    colours, ink = set(), 0
    for row in rows[::2]:  # every other row: enough to see the drawing
        for x in range(0, w * bpp, bpp):
            px = row[x:x + 3]
            colours.add(px)
            ink += px != b"\xff\xff\xff"
    frac = ink / (w * len(rows[::2]))
    if not 0.01 < frac < 0.6:
        raise ValueError(f"{100 * frac:.1f} % of the pixels are not white")
    if len(colours) < 4:
        raise ValueError(f"only {len(colours)} colours")
    return frac, len(colours)


def main():
    passed = failed = 0
    for outdir in sys.argv[1:]:
        pngs = sorted(Path(outdir, "plots").glob("*.png"))
        if not pngs:
            print(f"{outdir}/plots: no PNG files")
            failed += 1
        for p in pngs:
            try:
                frac, n = check(p)
                print(f"ok   {p}: {100 * frac:.1f} % ink, {n} colours")
                passed += 1
            except (ValueError, OSError, zlib.error, TypeError) as e:
                print(f"FAIL {p}: {e}")
                failed += 1
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

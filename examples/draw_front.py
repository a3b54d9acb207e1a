"""Draws the neighbourhood of a failed rhomb fill as a PNG (a debugging aid).

The test `attempt_survey` of crates/hexmesh-core/src/rhomb/domain (run with
RHOMB_DUMP=FILE) writes a failed ladder's neighbourhood as JSON (the latest, or the
RHOMB_DUMP_NTH-th): the kept lattice triangles, the boundary segments, the ladder's
candidate points and the front corners around the corner where the ladder failed. This script paints them with numpy only (no imaging library):
kept triangles grey, segments blue, the candidate points of the inner chain green,
front corners black, the failing one red and its
three neighbours on each side orange.

    python3 examples/draw_front.py FILE.json OUT.png
"""
import json
import struct
import sys
import zlib

import numpy as np

SIZE = 900


def main(source, target):
    dump = json.load(open(source))
    cx, cy = dump["centre"]
    r = dump["r"]
    img = np.full((SIZE, SIZE, 3), 255, np.uint8)

    def pixel(p):
        return ((p[0] - cx + r) / (2 * r) * SIZE, (cy + r - p[1]) / (2 * r) * SIZE)

    def fill(q, colour):
        (x0, y0), (x1, y1), (x2, y2) = [pixel(p) for p in q]
        ys, xs = np.mgrid[0:SIZE, 0:SIZE]
        def edge(ax, ay, bx, by):
            return (bx - ax) * (ys - ay) - (by - ay) * (xs - ax)
        a, b, c = edge(x0, y0, x1, y1), edge(x1, y1, x2, y2), edge(x2, y2, x0, y0)
        inside = ((a <= 0) & (b <= 0) & (c <= 0)) | ((a >= 0) & (b >= 0) & (c >= 0))
        img[inside] = colour

    def clip(x0, y0, x1, y1):
        # The part of the line inside the picture (Liang-Barsky), or None: a segment many
        # pictures long is stepped only where it shows.
        t0, t1 = 0.0, 1.0
        for d, q in ((x0 - x1, x0 + 2), (x1 - x0, SIZE + 1 - x0), (y0 - y1, y0 + 2), (y1 - y0, SIZE + 1 - y0)):
            if d == 0:
                if q < 0:
                    return None
            elif d < 0:
                t0 = max(t0, q / d)
            else:
                t1 = min(t1, q / d)
        if t0 > t1:
            return None
        dx, dy = x1 - x0, y1 - y0
        return x0 + t0 * dx, y0 + t0 * dy, x0 + t1 * dx, y0 + t1 * dy

    def line(p, q, colour, width=1):
        clipped = clip(*pixel(p), *pixel(q))
        if clipped is None:
            return
        x0, y0, x1, y1 = clipped
        steps = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
        for k in range(steps + 1):
            x, y = x0 + (x1 - x0) * k / steps, y0 + (y1 - y0) * k / steps
            for dx in range(1 - width, width):
                for dy in range(1 - width, width):
                    xi, yi = int(x) + dx, int(y) + dy
                    if 0 <= xi < SIZE and 0 <= yi < SIZE:
                        img[yi, xi] = colour

    for q in dump["tris"]:
        fill(q, (220, 220, 220))
    for q in dump["tris"]:
        for k in range(3):
            line(q[k], q[(k + 1) % 3], (150, 150, 150))
    for s in dump["segs"]:
        line(s[0], s[1], (0, 0, 255), 2)
    for p in dump.get("inner", []):
        x, y = pixel(p)
        for dx in range(-1, 2):
            for dy in range(-1, 2):
                if 0 <= int(x) + dx < SIZE and 0 <= int(y) + dy < SIZE:
                    img[int(y) + dy, int(x) + dx] = (0, 160, 0)
    at = dump["at"]
    for i, p in dump["front"]:
        x, y = pixel(p)
        colour = (255, 0, 0) if i == at else (255, 140, 0) if abs(i - at) <= 3 else (0, 0, 0)
        for dx in range(-4, 5):
            for dy in range(-4, 5):
                if 0 <= int(x) + dx < SIZE and 0 <= int(y) + dy < SIZE:
                    img[int(y) + dy, int(x) + dx] = colour

    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(SIZE))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    open(target, "wb").write(png)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

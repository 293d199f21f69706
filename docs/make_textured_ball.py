#!/usr/bin/env python3
"""Writes a textured UV sphere for docs/textures.md: ball.obj, ball.mtl and ball.png
(a 256x128 checker of 8x4 panels with dark seams), into the folder given (default: .).
Python's standard library only, so that the example needs nothing Meander does not."""
import math
import os
import struct
import sys
import zlib

folder = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(folder, exist_ok=True)

# The texture: rows top to bottom, as PNG stores them.
W, H = 256, 128
rows = []
for y in range(H):
    row = bytearray()
    for x in range(W):
        colour = (235, 200, 40) if (x * 8 // W + y * 4 // H) % 2 else (40, 90, 200)
        row += bytes((30, 30, 30) if x % 32 == 0 or y % 32 == 0 else colour)
    rows.append(b"\x00" + bytes(row))


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


with open(os.path.join(folder, "ball.png"), "wb") as png:
    png.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0))
              + chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))

# The sphere: a latitude-longitude grid of quads; the seam column is doubled so that u
# runs from 0 to 1 around it.
N, M = 48, 24
with open(os.path.join(folder, "ball.obj"), "w") as obj:
    obj.write("mtllib ball.mtl\n")
    for j in range(M + 1):
        for i in range(N + 1):
            theta, phi = math.pi * j / M, 2 * math.pi * i / N
            obj.write("v %.6f %.6f %.6f\n" % (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
            obj.write("vt %.6f %.6f\n" % (i / N, 1 - j / M))
    obj.write("usemtl ball\n")
    for j in range(M):
        for i in range(N):
            corners = [j * (N + 1) + i + 1, (j + 1) * (N + 1) + i + 1, (j + 1) * (N + 1) + i + 2, j * (N + 1) + i + 2]
            obj.write("f " + " ".join("%d/%d" % (k, k) for k in corners) + "\n")

with open(os.path.join(folder, "ball.mtl"), "w") as mtl:
    mtl.write("newmtl ball\nKd 1 1 1\nmap_Kd ball.png\n")

"""The example of docs/python.md: a curve, a printable wire and a picture of a generated
pretzel, and a curve on a mesh made from your own arrays. Run from any folder; it
writes pretzel_wire.stl and pretzel_curve.png there."""

import numpy as np

import meander

pretzel = meander.generate("pretzel", faces=6400)
curves = meander.curve(pretzel, seed=7)
print(len(curves), curves[0].shape, curves[0].dtype)  # 1 (76800, 3) float32

# A wire 100 mm wide, its passes 3 mm apart, and its printability report.
vertices, faces, report = meander.wire(pretzel, model_size="100mm", spacing="3mm")
print(report["printable"], round(report["min_thickness"], 2))  # True 1.15
meander.write_mesh("pretzel_wire.stl", meander.Mesh(vertices, faces), millimetres=True)

# The curve drawn over its surface, which hides the curve's back parts.
picture = meander.render(curves=curves, occluder=pretzel, size="800x600")
meander.write_png("pretzel_curve.png", picture)

# Your own arrays: a cube of six quads.
corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float32)
cube = meander.Mesh(corners, [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])
print(len(meander.curve(cube, tree="bfs")[0]))  # 96 points: 24 triangles, 4 samples each

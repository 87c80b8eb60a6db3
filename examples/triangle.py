"""examples/triangle.cpp from Python: the same vertex-coloured triangle, built
from numpy arrays and rendered into numpy arrays; prints its centre pixel
(premultiplied linear RGBA) and depth.

    PYTHONPATH=build/python python3 examples/triangle.py
"""
import sys

import numpy as np

import quadra

positions = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32)
colors = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]], np.float32)  # linear RGBA
indices = np.array([0, 1, 2], np.uint32)

scene = quadra.Scene()
mesh = scene.add_mesh(positions, indices, colors=colors)
scene.add_instance(mesh, scene.add_material())  # identity transform
scene.set_camera(quadra.Camera(world=quadra.look_at((0, 0, 3), (0, 0, 0))))

try:
    out = quadra.Renderer(threads=2).render(scene, width=640, height=360)
except quadra.Error as error:  # the library's one-line message
    sys.exit(str(error))
r, g, b, a = out.color[180, 320]
print(f"quadra {quadra.__version__}: centre pixel {r:.4f} {g:.4f} {b:.4f} {a:.4f}, "
      f"depth {out.depth[180, 320]:.6f}")
sys.exit(0 if a == 1.0 else 1)

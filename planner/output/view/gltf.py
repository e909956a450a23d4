"""The 3D view as a binary glTF file (``.glb``, written by trimesh) for CAD and Blender.

One state (the level one by default): the body's surface, each rope and sling leg as a thin
cylinder in its colour on the page's colour scale, spreader bars and booms as grey cylinders,
the lugs as small cubes and the CG as a red one; each a named node ("rope L1", "lug P01",
...). glTF's own axes are y up: world ``z-up`` (x, y, z) is written as (x, z, -y), which is
the ``choi`` frame, so a file in either frame reads with its x forward and its up up.
"""

from __future__ import annotations

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import Normalize

from liftplan.model.extras import require
from liftplan.planner.output.view.geometry import to_file_frame

#: Rope radius as a fraction of the body's size (a rope is drawn, not sized).
ROPE_RADIUS = 0.004
#: Marker size (lugs, CG) as a fraction of the body's size.
MARKER = 0.015


def _gltf(points):
    """World z-up points in glTF's y-up axes."""
    return to_file_frame(points, "choi")


def glb_bytes(view, state=0):
    """The ``.glb`` file of one state of ``view`` (bytes)."""
    trimesh = require("mesh", "trimesh", what="--view FILE.glb")
    shown = view.states[state]
    lower, upper = view.bounds()
    size = float(np.max(upper - lower)) or 1.0
    scene = trimesh.Scene()
    body = _gltf(shown.world(view.body.reshape(-1, 3)))
    faces = np.arange(len(body)).reshape(-1, 3)
    mesh = trimesh.Trimesh(vertices=body, faces=faces, process=False)
    mesh.visual.face_colors = [154, 166, 178, 160]
    scene.add_geometry(mesh, node_name="body", geom_name="body")
    low, high = view.colour_range()
    norm, cmap = Normalize(low, high), colormaps["turbo"]
    for rope, value in zip(shown.ropes, view.colour_values(shown)):
        colour = (np.array(cmap(norm(rope.tension if value is None else value))) * 255).astype(int)
        _bar(trimesh, scene, f"rope {rope.key}", rope.lower, rope.upper, ROPE_RADIUS * size, colour)
    for crane, a, b in shown.spreaders:
        _bar(trimesh, scene, f"spreader {crane}", a, b, 2.5 * ROPE_RADIUS * size, [60, 60, 60, 255])
    centres = {c.name: c.centre for c in view.cranes}
    for name, tip in (shown.tips or {}).items():
        if centres.get(name) is not None:
            _bar(
                trimesh,
                scene,
                f"boom {name}",
                (*centres[name], 0.0),
                tip,
                3 * ROPE_RADIUS * size,
                [90, 90, 90, 255],
            )
    names = list(view.lugs)
    for name, point in zip(names, shown.world([view.lugs[n] for n in names])):
        chosen = name in view.labels
        _cube(
            trimesh,
            scene,
            f"lug {name}",
            point,
            MARKER * size * (1.0 if chosen else 0.5),
            [0, 0, 0, 255] if chosen else [90, 90, 90, 255],
        )
    _cube(trimesh, scene, "CG", shown.world([shown.cog])[0], 1.5 * MARKER * size, [220, 0, 0, 255])
    return scene.export(file_type="glb")


def _bar(trimesh, scene, name, a, b, radius, colour):
    ends = _gltf(np.array([a, b], dtype=float))
    if np.linalg.norm(ends[1] - ends[0]) < 1e-9:
        return
    bar = trimesh.creation.cylinder(radius=radius, segment=ends, sections=8)
    bar.visual.face_colors = colour
    scene.add_geometry(bar, node_name=name, geom_name=name)


def _cube(trimesh, scene, name, point, side, colour):
    cube = trimesh.creation.box(extents=[side, side, side])
    cube.apply_translation(_gltf(np.asarray(point, dtype=float)))
    cube.visual.face_colors = colour
    scene.add_geometry(cube, node_name=name, geom_name=name)

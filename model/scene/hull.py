"""Hull geometry: a closed, outward-oriented triangle mesh in the body frame.

A box is meshed here (12 triangles); any other hull is read from STL by trimesh, which
merges the file's repeated vertices so that closure and winding can be checked. The
hydrostatics (:mod:`liftplan.model.water.hydrostatics`) integrate over these triangles, so a box
and an STL mesh of the same box give the same numbers by construction of the method, and
the tests check that they do.

Water inside the hull (:class:`Flooding`):

* ``intact`` - the whole envelope is watertight and empty: it displaces water up to the
  waterline (a floating or stranded ship).
* ``flooded`` - free-flooding: water enters and drains freely, so inside and outside
  levels are equal at every instant and only the steel displaces water. The steel volume
  is ``weight / steel_density`` (or ``(weight - weight_in_water) / water density``) and is
  taken as spread like the envelope: its submerged fraction and centre are those of the
  envelope's submerged part. Watertight :class:`Compartment` boxes inside a flooded hull
  hold ``air`` (they displace water while submerged) or ``water`` (trapped: it never drains).

Trapped water is a weight (:meth:`Hull.trapped_water`), carried with the hull at every
hoist; its compartment, being watertight, displaces water like any other while it is
below the surface and so adds to the buoyancy. Submerged, the two cancel; clear of the
water the cranes carry the trapped water whole. Buoyancy is therefore always the weight
of the displaced water (>= 0), never a net force.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.extras import require
from liftplan.model.scene.objects import finite, point, positive

FLOODING = ("intact", "flooded")
CONTENTS = ("air", "water")
STEEL_DENSITY = 7.85  # t/m3, structural steel


def box_triangles(lower, upper):
    """The 12 outward-oriented triangles of an axis-aligned box.

    Parameters
    ----------
    lower, upper : sequence of 3 float  [m]
        Opposite corners, ``lower < upper`` on every axis.

    Returns
    -------
    numpy.ndarray, shape (12, 3, 3)  [m]
        Triangles, vertices counter-clockwise seen from outside.
    """
    lo, hi = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    corner = np.array([[(hi if (k >> axis) & 1 else lo)[axis] for axis in range(3)] for k in range(8)])
    # corner index bits: x = 1, y = 2, z = 4; each face as two triangles, outward
    faces = [
        (0, 2, 3, 1),  # z low, normal -z
        (4, 5, 7, 6),  # z high, +z
        (0, 1, 5, 4),  # y low, -y
        (2, 6, 7, 3),  # y high, +y
        (0, 4, 6, 2),  # x low, -x
        (1, 3, 7, 5),  # x high, +x
    ]
    tris = []
    for a, b, c, d in faces:
        tris.append(corner[[a, b, c]])
        tris.append(corner[[a, c, d]])
    return np.array(tris)


def mesh_volume(triangles):
    """Enclosed volume of a closed triangle mesh  [m3] (> 0 when normals point outward)."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _box(path, value):
    """Read ``{min = [...], max = [...]}``; returns (lower, upper)."""
    if not isinstance(value, dict) or set(value) != {"min", "max"}:
        raise InvalidScene(f"{path} = {value!r}: expected {{min = [x, y, z], max = [x, y, z]}} in m")
    lower, upper = point(f"{path}.min", value["min"]), point(f"{path}.max", value["max"])
    if not all(lo < hi for lo, hi in zip(lower, upper)):
        raise InvalidScene(f"{path} = {value!r}: expected min < max on every axis")
    return lower, upper


@dataclass(frozen=True)
class Compartment:
    """A watertight box inside a flooded hull.

    Parameters
    ----------
    name : str
    box : dict
        ``{"min": [x, y, z], "max": [x, y, z]}``, body frame  [m].
    contents : {"air", "water"}
        ``air``: displaces water while submerged. ``water``: trapped water that rises
        with the hull and does not drain.
    """

    name: str
    box: dict
    contents: str = "air"

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidScene(f"hull.compartments.name = {self.name!r}: expected a non-empty string")
        _box(f"hull.compartments[{self.name}].box", self.box)
        if self.contents not in CONTENTS:
            raise InvalidScene(
                f"hull.compartments[{self.name}].contents = {self.contents!r}: "
                f"expected one of {', '.join(CONTENTS)}"
            )

    @cached_property
    def triangles(self):
        """Outward triangles, body frame, shape (12, 3, 3)  [m]."""
        return box_triangles(*_box("box", self.box))

    @cached_property
    def volume(self):
        """Volume  [m3]."""
        return mesh_volume(self.triangles)

    @cached_property
    def centroid(self):
        """Centre of volume, body frame  [m]."""
        lower, upper = _box("box", self.box)
        return tuple(0.5 * (lo + hi) for lo, hi in zip(lower, upper))


@dataclass(frozen=True)
class Hull:
    """The hull's watertight envelope and how water fills it.

    Build with :meth:`box` or :meth:`from_stl`.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
        Closed mesh, body frame, vertices counter-clockwise seen from outside.
    source : str
        ``"box"`` or the STL path, for messages and reports.
    flooding : {"intact", "flooded"}
    steel_density : float or None  [t/m3]
        Flooded hull: steel volume = weight / steel_density (default 7.85).
    weight_in_water : float or None  [t]
        Flooded hull: the weight submerged, instead of a steel density.
    compartments : tuple of Compartment
        Flooded hull only.
    """

    triangles: np.ndarray = field(repr=False)
    source: str = "box"
    flooding: str = "intact"
    steel_density: float | None = None
    weight_in_water: float | None = None
    compartments: tuple[Compartment, ...] = ()

    def __post_init__(self):
        tris = np.asarray(self.triangles, dtype=float)
        if tris.ndim != 3 or tris.shape[1:] != (3, 3) or len(tris) < 4:
            raise InvalidScene(
                f"hull {self.source}: triangles of shape {tris.shape}: expected (m >= 4, 3, 3)"
            )
        if not np.all(np.isfinite(tris)):
            raise InvalidScene(f"hull {self.source}: non-finite vertex coordinates")
        tris.setflags(write=False)
        object.__setattr__(self, "triangles", tris)
        if self.flooding not in FLOODING:
            raise InvalidScene(f"hull.flooding = {self.flooding!r}: expected one of {', '.join(FLOODING)}")
        if self.steel_density is not None:
            object.__setattr__(self, "steel_density", positive("hull.steel_density", self.steel_density))
        if self.weight_in_water is not None:
            object.__setattr__(self, "weight_in_water", finite("hull.weight_in_water", self.weight_in_water))
        if self.flooding == "intact" and (
            self.compartments or self.steel_density is not None or self.weight_in_water is not None
        ):
            raise InvalidScene(
                "hull: compartments, steel_density and weight_in_water describe a flooded hull; "
                'expected flooding = "flooded" with them'
            )
        if self.steel_density is not None and self.weight_in_water is not None:
            raise InvalidScene("hull: both steel_density and weight_in_water given; expected one of them")
        compartments = tuple(self.compartments)
        names = [c.name for c in compartments]
        for name in names:
            if names.count(name) > 1:
                raise InvalidScene(f"hull.compartments.name = {name!r}: duplicate, expected unique names")
        object.__setattr__(self, "compartments", compartments)
        volume = mesh_volume(tris)
        if not volume > 0.0:
            raise InvalidScene(
                f"hull {self.source}: enclosed volume {volume:.6g} m3 is not positive: the normals "
                "point inward (or the mesh is flat); expected outward-facing triangles"
            )

    @classmethod
    def box(cls, lower, upper, **kwargs):
        """An axis-aligned box hull from corners ``lower`` and ``upper`` (body frame, m)."""
        lower, upper = _box("hull.box", {"min": lower, "max": upper})
        return cls(box_triangles(lower, upper), source="box", **kwargs)

    @classmethod
    def from_stl(cls, path, **kwargs):
        """A hull read from an STL file (ASCII or binary), body frame, metres.

        Raises
        ------
        InvalidScene
            The file cannot be read, or the mesh is not closed, not consistently wound,
            or its normals point inward.
        """
        path = Path(path)
        if not path.is_file():
            raise InvalidScene(f"hull.mesh = {str(path)!r}: no such file")
        trimesh = require("mesh", "trimesh", what=f"hull.mesh = {str(path)!r}")  # only when read
        try:
            mesh = trimesh.load_mesh(path, file_type="stl", process=True)
        except Exception as err:  # noqa: BLE001 - any reader failure is a bad file
            raise InvalidScene(f"hull.mesh = {str(path)!r}: cannot read STL ({err})") from None
        where = f"hull.mesh = {str(path)!r}"
        if len(mesh.faces) < 4:
            raise InvalidScene(f"{where}: {len(mesh.faces)} triangles, expected a closed mesh")
        if not mesh.is_watertight:
            raise InvalidScene(
                f"{where}: the mesh is not closed (open edges or holes); expected a closed "
                "(watertight) surface so that the submerged volume is defined"
            )
        if not mesh.is_winding_consistent:
            raise InvalidScene(
                f"{where}: triangle windings are inconsistent (some normals flipped); "
                "expected every triangle counter-clockwise seen from outside"
            )
        return cls(np.asarray(mesh.triangles, dtype=float), source=str(path), **kwargs)

    # -- derived ----------------------------------------------------------------------
    @cached_property
    def volume(self):
        """Enclosed volume of the envelope  [m3]."""
        return mesh_volume(self.triangles)

    @cached_property
    def bounds(self):
        """(lower, upper) corners of the bounding box, body frame  [m]."""
        pts = self.triangles.reshape(-1, 3)
        return pts.min(axis=0), pts.max(axis=0)

    @cached_property
    def vertices(self):
        """Distinct vertices, body frame, shape (k, 3)  [m]."""
        return np.unique(self.triangles.reshape(-1, 3), axis=0)

    @cached_property
    def size(self):
        """Largest bounding-box side  [m] (the moment residuals' length scale)."""
        lower, upper = self.bounds
        return float(max(upper - lower))

    def trapped_water(self, density):
        """Weight and centre of the water trapped in compartments.

        Parameters
        ----------
        density : float  [t/m3]   water density

        Returns
        -------
        weight : float  [t]
            0 without trapped water.
        centre : tuple of 3 float or None  [m]
            Body frame; None without trapped water.
        """
        tanks = [c for c in self.compartments if c.contents == "water"]
        volume = sum(c.volume for c in tanks)
        if not tanks:
            return 0.0, None
        centre = sum(c.volume * np.asarray(c.centroid) for c in tanks) / volume
        return density * volume, tuple(float(v) for v in centre)

    def steel_volume(self, weight, density):
        """Volume of steel that displaces water in a flooded hull  [m3].

        Parameters
        ----------
        weight : float  [t]   weight in air
        density : float  [t/m3]   water density
        """
        if self.weight_in_water is not None:
            volume = (weight - self.weight_in_water) / density
            if not 0.0 < volume <= self.volume:
                raise InvalidScene(
                    f"hull.weight_in_water = {self.weight_in_water:g} t with body.weight {weight:g} t "
                    f"gives a steel volume of {volume:.4g} m3; expected between 0 and the hull's "
                    f"{self.volume:.4g} m3"
                )
            return volume
        volume = weight / (self.steel_density or STEEL_DENSITY)
        if volume > self.volume:
            raise InvalidScene(
                f"hull: steel volume {volume:.4g} m3 exceeds the envelope's {self.volume:.4g} m3; "
                "expected a heavier steel_density or a larger hull"
            )
        return volume

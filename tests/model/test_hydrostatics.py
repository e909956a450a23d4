"""Clipped-mesh hydrostatics against closed forms; a box and an STL mesh of it agree."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from liftplan.model import InvalidScene, rotation_matrix
from liftplan.model.scene.hull import Hull, box_triangles
from liftplan.model.water.hydrostatics import MeshHydrostatics

L, B, D = 100.0, 30.0, 10.0  # the paper's barge; body origin at mid-depth
BOX = Hull.box([-L / 2, -B / 2, -D / 2], [L / 2, B / 2, D / 2])


def wall_sided(draft, heel):
    """Closed forms for a box heeled within its wall-sided range (deck edge dry, bilge
    wet): volume, centre of buoyancy in the body frame, waterplane area, I_T, I_L."""
    t = math.tan(heel)
    volume = L * B * draft
    y_b = -(B**2 / (12 * draft)) * t  # towards the low (starboard, -y) side
    z_b = -D / 2 + draft / 2 + (B**2 / (24 * draft)) * t**2
    breadth = B / math.cos(heel)
    return volume, (0.0, y_b, z_b), L * breadth, L * breadth**3 / 12, breadth * L**3 / 12


# (draft, heel deg) inside the wall-sided range: tan(heel) B / 2 < min(draft, D - draft)
CASES = [(5.0, 0.0), (5.0, 10.0), (3.0, 5.0), (8.0, 3.0), (2.0, 0.0), (6.5, 10.0)]


@pytest.mark.parametrize("draft, heel_deg", CASES)
@pytest.mark.parametrize("source", ["box", "stl"])
def test_box_against_closed_forms(draft, heel_deg, source, stl_box):
    """Tolerance 1e-9 relative: the method is exact for plane faces, so only round-off
    (~1e-13) separates it from the closed form."""
    hull = BOX if source == "box" else stl_box
    heel = math.radians(heel_deg)
    # the body origin's height over the water that puts draft `draft` at the centreline
    zo = (D / 2 - draft) * math.cos(heel)
    hs = MeshHydrostatics(hull.triangles).at(rotation_matrix(heel_deg, 0.0), zo)
    volume, centre_body, area, i_t, i_l = wall_sided(draft, heel)
    rot = np.array([[1, 0, 0], [0, math.cos(heel), -math.sin(heel)], [0, math.sin(heel), math.cos(heel)]])
    centre = rot @ np.array(centre_body) + [0.0, 0.0, zo]
    assert_allclose(hs.volume, volume, rtol=1e-9)
    assert_allclose(hs.centre, centre, rtol=1e-9, atol=1e-9)
    assert_allclose(hs.waterplane_area, area, rtol=1e-9)
    assert_allclose(hs.inertia[:2], (i_t, i_l), rtol=1e-9)
    assert_allclose(hs.bm_transverse, i_t / volume, rtol=1e-9)
    # the waterline crosses the centreline at body (0, 0, draft - D/2)
    assert_allclose(hs.flotation, (0.0, -math.sin(heel) * (draft - D / 2)), atol=1e-9)


def test_trimmed_box_waterplane_centre():
    """Trim moves the centre of flotation nowhere on a box (symmetric about amidships) but
    lengthens the waterplane by 1/cos(trim)."""
    trim = math.radians(2.0)
    hs = MeshHydrostatics(BOX.triangles).at(rotation_matrix(0.0, math.degrees(trim)), 0.0)
    assert_allclose(hs.waterplane_area, L * B / math.cos(trim), rtol=1e-12)
    assert_allclose(hs.volume, L * B * D / 2, rtol=1e-12)


@pytest.mark.parametrize(
    "zo, volume", [(-D, L * B * D), (-D / 2, L * B * D), (D / 2, 0.0), (D, 0.0), (0.0, L * B * D / 2)]
)
def test_submerged_touching_and_clear(zo, volume):
    """Fully submerged (deck at or below the surface), just touching from above, clear."""
    hs = MeshHydrostatics(BOX.triangles).at(np.eye(3), zo)
    assert_allclose(hs.volume, volume, rtol=1e-12, atol=1e-9)
    if 0 < volume < L * B * D:
        assert hs.waterplane_area == pytest.approx(L * B)
    elif volume == L * B * D and zo < -D / 2:
        assert hs.waterplane_area == 0.0 and hs.centre == pytest.approx((0, 0, zo))


def test_heel_90_capsized():
    """On its side, half immersed: the box is B deep and D wide, waterplane L x D."""
    hs = MeshHydrostatics(BOX.triangles).at(rotation_matrix(90.0, 0.0), 0.0)
    assert_allclose(hs.volume, L * B * D / 2, rtol=1e-12)
    assert_allclose(hs.centre, (0.0, 0.0, -B / 4), atol=1e-9)
    assert_allclose(hs.waterplane_area, L * D, rtol=1e-12)
    assert_allclose(hs.inertia[0], L * D**3 / 12, rtol=1e-12)


def test_random_attitudes_box_equals_mesh(stl_box):
    """A differently triangulated STL of the box gives the same numbers at any pose."""
    rng = np.random.default_rng(4)
    box, mesh = MeshHydrostatics(BOX.triangles), MeshHydrostatics(stl_box.triangles)
    for _ in range(20):
        rot = rotation_matrix(*rng.uniform(-90, 90, 3))
        zo = rng.uniform(-12, 12)
        assert_allclose(box.raw(rot, zo), mesh.raw(rot, zo), rtol=1e-9, atol=1e-6)


def test_open_and_inverted_meshes_refused(tmp_path):
    import trimesh

    tris = box_triangles([0, 0, 0], [1, 2, 3])
    open_mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(tris[:-1]))
    open_mesh.export(tmp_path / "open.stl")
    with pytest.raises(InvalidScene, match="not closed"):
        Hull.from_stl(tmp_path / "open.stl")
    inverted = trimesh.Trimesh(**trimesh.triangles.to_kwargs(tris[:, ::-1]), process=False)
    inverted.export(tmp_path / "inverted.stl")
    with pytest.raises(InvalidScene, match="inward"):
        Hull.from_stl(tmp_path / "inverted.stl")
    mixed = tris.copy()
    mixed[3] = mixed[3, ::-1]
    trimesh.Trimesh(**trimesh.triangles.to_kwargs(mixed), process=False).export(tmp_path / "mixed.stl")
    with pytest.raises(InvalidScene, match="inconsistent"):
        Hull.from_stl(tmp_path / "mixed.stl")
    with pytest.raises(InvalidScene, match="no such file"):
        Hull.from_stl(tmp_path / "missing.stl")


def test_attitude_angles_invert_rotation_matrix():
    """The decomposition used to report hydrostatic answers inverts the one convention."""
    from liftplan.model.frames import attitude_angles

    rng = np.random.default_rng(7)
    angles = zip(rng.uniform(-179, 179, 30), rng.uniform(-89, 89, 30), rng.uniform(-89, 89, 30))
    for heel, trim, yaw in angles:
        assert_allclose(attitude_angles(rotation_matrix(heel, trim, yaw)), (heel, trim, yaw), atol=1e-9)

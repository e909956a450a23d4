import pytest
from helpers import example


@pytest.fixture
def tanker():
    return example("tanker_upright")


@pytest.fixture
def capsized():
    return example("tanker_capsized")


@pytest.fixture
def block():
    return example("symmetric_block")


@pytest.fixture(scope="session")
def stl_box(tmp_path_factory):
    """The paper's barge as a subdivided STL mesh (a different triangulation than the box's)."""
    import trimesh

    from liftplan.model.hull import Hull

    mesh = trimesh.creation.box(extents=(100.0, 30.0, 10.0)).subdivide().subdivide()
    path = tmp_path_factory.mktemp("hull") / "barge.stl"
    mesh.export(path)
    return Hull.from_stl(path)

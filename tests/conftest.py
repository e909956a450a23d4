import pytest
from helpers import example
from hypothesis import settings

# The shared helpers' asserts (tests/support/, imported after this file) report their values as
# a test's own do.
pytest.register_assert_rewrite("support")

# Property tests draw the same examples on every run and keep no example database, so a
# clean checkout's `python -m pytest` cannot pass or fail by chance or by an earlier run.
# `python -m pytest --hypothesis-profile explore` searches afresh (random draws); pin what it
# finds with @example.
settings.register_profile("liftplan", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", derandomize=False, database=None, print_blob=True)
settings.load_profile("liftplan")


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

    from liftplan.model.scene.hull import Hull

    mesh = trimesh.creation.box(extents=(100.0, 30.0, 10.0)).subdivide().subdivide()
    path = tmp_path_factory.mktemp("hull") / "barge.stl"
    mesh.export(path)
    return Hull.from_stl(path)

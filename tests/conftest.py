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

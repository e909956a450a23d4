"""Shared helpers of the tests."""

from pathlib import Path

from liftplan.model import load_scene

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def example(name):
    """A scene from examples/ by file stem."""
    return load_scene(EXAMPLES / f"{name}.toml")

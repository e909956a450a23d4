"""The installed liftplan's version, from the one place it is written (pyproject.toml's
``[project] version``, read back from the installed package's metadata).

Imported only where the version is shown (``--version``, a JSON output, a report): reading
the metadata costs ~25 ms, which ``import liftplan.model`` and ``liftplan --help`` do not pay
(the packages export ``__version__`` lazily).
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

#: The key every JSON object liftplan writes carries its version under.
VERSION_KEY = "liftplan_version"

try:
    __version__: str = version("liftplan")
except PackageNotFoundError:  # the folders imported without installing (not a supported use)
    __version__ = "0+unknown"


def stamped(out: dict) -> dict:
    """``out`` with the version added as its last key (:data:`VERSION_KEY`): the keys a
    script relies on keep their names and order."""
    return {**out, VERSION_KEY: __version__}

"""The installed liftplan's version, from the one place it is written (pyproject.toml's
``[project] version``, read back from the installed package's metadata).

Imported only where the version is shown (``--version``, a JSON output, a report): reading
the metadata costs ~25 ms, which ``import liftplan.model`` and ``liftplan --help`` do not pay
(the packages export ``__version__`` lazily).
"""

from __future__ import annotations

import math
from importlib.metadata import PackageNotFoundError, version

#: The key every JSON object liftplan writes carries its version under.
VERSION_KEY = "liftplan_version"

try:
    __version__: str = version("liftplan")
except PackageNotFoundError:  # the folders imported without installing (not a supported use)
    __version__ = "0+unknown"


#: The key that lists the values JSON cannot hold (NaN, +-Infinity), written as null.
NOT_FINITE_KEY = "not_finite"


def stamped(out: dict) -> dict:
    """``out`` ready to be written as JSON: the version added as its last key
    (:data:`VERSION_KEY`), the keys a script relies on keeping their names and order.

    A NaN or an infinity is not JSON (a strict parser refuses the file): each is written as
    null, and :data:`NOT_FINITE_KEY` (before the version) maps its place in the object
    (``"capacity[0].utilisation"``) to what it was (``"Infinity"``, ``"-Infinity"``,
    ``"NaN"``), so the reason stands beside the null.
    """
    found: dict[str, str] = {}
    finite = _finite(out, "", found)
    if found:
        finite[NOT_FINITE_KEY] = found
    return {**finite, VERSION_KEY: __version__}


def _finite(value, path, found):
    """``value`` with every non-finite float replaced by None (recorded in ``found``)."""
    if isinstance(value, dict):
        return {k: _finite(v, f"{path}.{k}" if path else str(k), found) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v, f"{path}[{i}]", found) for i, v in enumerate(value)]
    if isinstance(value, float) and not math.isfinite(value):
        found[path] = "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
        return None
    return value

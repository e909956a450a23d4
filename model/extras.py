"""The optional parts of liftplan (pyproject.toml's extras) and the one-line error a command
gives when one it needs is not installed.

``pip install liftplan`` installs what solve, lift and plan need; ``liftplan[batch]`` adds
Dask for ``liftplan batch``, ``liftplan[mesh]`` trimesh for STL hulls, ``liftplan[pdf]``
WeasyPrint for the report's PDF (the HTML report is always written).
"""

from __future__ import annotations

import importlib
from types import ModuleType

from liftplan.model.errors import LiftPlanError


class MissingExtra(LiftPlanError, ImportError):
    """An optional part of liftplan that is needed is not installed; the message names the
    extra and the command that installs it."""


def missing(extra: str, *modules: str) -> str | None:
    """Why ``modules`` (the ``extra``'s) cannot be imported, in one line, or None if they can.

    ``OSError`` counts as missing too: WeasyPrint installed without the system's Pango
    raises it on import.
    """
    for module in modules:
        try:
            importlib.import_module(module)
        except ImportError as err:
            return f'needs the {extra} extra ({_one_line(err)}): pip install "liftplan[{extra}]"'
        except OSError as err:  # installed, but a system library it loads is not
            return f"needs the {extra} extra: {module} is installed but cannot load ({_one_line(err)})"
    return None


def _one_line(err):
    return " ".join(str(err).split()) or type(err).__name__


def require(extra: str, module: str, *more: str, what: str = "") -> ModuleType:
    """Import and return ``module`` (after ``more``, the other modules the ``extra`` must
    provide), or raise :class:`MissingExtra` naming the extra.

    Parameters
    ----------
    extra : str
        The extra of pyproject.toml that installs them, e.g. ``"batch"``.
    what : str, optional
        What needed them, put before the message (e.g. ``"hull.mesh = 'a.stl'"``).
    """
    reason = missing(extra, module, *more)
    if reason is not None:
        raise MissingExtra(f"{what}: {reason}" if what else reason)
    return importlib.import_module(module)

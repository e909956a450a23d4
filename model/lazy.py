"""Package exports loaded on first use (PEP 562), shared by ``liftplan.model`` and
``liftplan.planner``: ``import liftplan.model`` (and the command line's ``--help``) does not pay
for casadi, cvxpy, numpy or pydantic until a name that needs them is used."""

from __future__ import annotations

import importlib
import sys
import types


def lazy_package(name, exports):
    """Make the package ``name`` load each exported name from its submodule on first use.

    Parameters
    ----------
    name : str
        The package (``__name__`` of its ``__init__``).
    exports : dict of str to str
        Public name -> the submodule (dotted path relative to the package, or absolute from
        ``liftplan.``) that defines it.

    Returns
    -------
    (__getattr__, __dir__)
        The module-level functions the package's ``__init__`` binds.

    Notes
    -----
    A name that is also its submodule's name (``solve``, ``plan``) stays the function: the
    import system would otherwise bind the submodule over it when that is first imported.
    """
    public = sorted(exports)

    def __getattr__(attribute):
        try:
            module = exports[attribute]
        except KeyError:
            raise AttributeError(f"module {name!r} has no attribute {attribute!r}") from None
        absolute = module.startswith("liftplan.")  # another package's module (the version)
        value = getattr(importlib.import_module(module if absolute else f"{name}.{module}"), attribute)
        setattr(sys.modules[name], attribute, value)
        return value

    def __dir__():
        return sorted(set(vars(sys.modules[name])) | set(public))

    class _Package(types.ModuleType):
        def __setattr__(self, attribute, value):
            if (
                isinstance(value, types.ModuleType)
                and exports.get(attribute) == attribute
                and value.__name__ == f"{name}.{attribute}"
            ):
                value = getattr(value, attribute)
            super().__setattr__(attribute, value)

    sys.modules[name].__class__ = _Package
    return __getattr__, __dir__

"""The lifting rules a plan is checked to, as one table of implementations.

A rules code is a module with the functions and constants of :data:`INTERFACE` (each factor as
a small function citing its clause, and where each comes from, ``SOURCES``);
:class:`~liftplan.model.rules.chain.DesignLoadChain` calls them through the code the
planning file names (``[rules] code``, default ``"0027/ND"``). A new code is one module and
one row of :data:`CODES`.
"""

from __future__ import annotations

from types import ModuleType

from liftplan.model.rules import factors

#: What the design-load chain calls on a code.
INTERFACE = (
    "SOURCES",
    "LOCATIONS",
    "DEFAULT_SKEW_FACTOR",
    "weight_contingency",
    "cog_factor",
    "dynamic_amplification",
    "rules_tilt",
    "governing_tilt",
    "yaw_factor",
    "skew_factor",
    "code_margin",
)

#: ``[rules] code`` -> (its title, the module implementing :data:`INTERFACE`).
CODES: dict[str, tuple[str, ModuleType]] = {
    "0027/ND": ("GL Noble Denton 0027/ND Rev 11 (now DNVGL-ST-N001)", factors),
}
DEFAULT_CODE = "0027/ND"

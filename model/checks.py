"""Checks that can fail: one record per check, so every output flags them the same way.

A check is what an engineer signs against: a value, its limit and whether it is met. The
console prints a FAIL line for each failed check, ``--json`` carries them as ``"checks"``, and
the command line exits with a distinct code when any failed (README "Command line").
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class Check:
    """One check of a solved state or a plan.

    Parameters
    ----------
    name : str
        What is checked, e.g. ``"swl"``, ``"min_tension"``, ``"code_margin"``,
        ``"sling_angle"``, ``"bending_moment"``.
    subject : str
        What it is checked on: a rope, crane, lug or section label.
    value : float
        The computed value, in ``unit``.
    limit : float
        The limit, in ``unit``.
    unit : str
        ``"t"``, ``"t m"``, ``"deg"``, ``"%"`` or ``"-"``.
    ok : bool
        Whether the limit is met.
    kind : {"max", "min"}
        ``"max"``: value must not exceed limit; ``"min"``: value must not fall below it.
    note : str
        What the value is (e.g. "design hook load / chart SWL at 21.3 m").
    """

    name: str
    subject: str
    value: float
    limit: float
    unit: str
    ok: bool
    kind: str = "max"
    note: str = ""

    @classmethod
    def upper(cls, name, subject, value, limit, unit, note=""):
        """A check that ``value <= limit`` (NaN never passes)."""
        value, limit = float(value), float(limit)
        return cls(name, subject, value, limit, unit, bool(value <= limit), "max", note)

    @classmethod
    def lower(cls, name, subject, value, limit, unit, note=""):
        """A check that ``value >= limit`` (NaN never passes)."""
        value, limit = float(value), float(limit)
        return cls(name, subject, value, limit, unit, bool(value >= limit), "min", note)

    def to_json(self):
        """The contract's check object: name, subject, value, limit, unit, ok (+ kind, note)."""
        out = asdict(self)
        for key in ("value", "limit"):
            if not math.isfinite(out[key]):
                out[key] = None
        return out

    def line(self):
        """One console line, ``FAIL swl L2: 452.1 t > 400 t (note)`` or ``ok ...``."""
        upper = self.kind == "max"
        sign = ("<=" if upper else ">=") if self.ok else (">" if upper else "<")
        word = "ok  " if self.ok else "FAIL"
        note = f" ({self.note})" if self.note else ""
        return (
            f"{word} {self.name} {self.subject}: {self.value:.4g} {self.unit} {sign} "
            f"{self.limit:.4g} {self.unit}{note}"
        )


def failed(checks):
    """The checks that failed, in order."""
    return [c for c in checks if not c.ok]

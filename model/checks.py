"""Checks that can fail: one record per check, so every output flags them the same way.

A check is what an engineer signs against: a value, its limit and whether it is met. The
console prints a FAIL line for each failed check, ``--json`` carries them as ``"checks"``, and
the command line exits with a distinct code when any failed (README "Command line").
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

#: What each check is, in words, for the documents a person signs (the JSON keeps the names).
TITLES = {
    "swl": "rope tension within the SWL",
    "min_tension": "tension at or above the minimum",
    "taut": "every rope taut",
    "leg_taut": "every sling leg taut",
    "sling_angle": "sling angle from the horizontal",
    "code_margin": "crane-code margin",
    "design_hook_load": "design hook load within the chart SWL",
    "design_loads": "design loads computed",
    "lug_design_load": "lug design load within its capacity",
    "breakout_hook_load": "hook load at breakout within the chart SWL",
    "breakout_min_tension": "tension at breakout at or above the minimum",
    "model_agreement": "plan and rigging model agree",
    "roll": "roll of the body on its slings",
    "bending_moment": "bending moment within the allowable",
    "shear_force": "shear force within the allowable",
    "girder_states": "hull girder found at every state",
    "crane_clearance": "crane booms clear of each other in plan",
    "angle_held": "turning angle held at every angle of the stage",
    "lug_out_of_plane": "lug design load across its plate within its out-of-plane capacity",
    "pivot_friction": "horizontal force at the pivot within its friction",
    "vessel_heel": "crane vessel heel within its limit",
    "vessel_trim": "crane vessel trim within its limit",
    "vessel_freeboard": "crane vessel freeboard at or above its minimum",
}


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

    @property
    def title(self):
        """What is checked, in words (:data:`TITLES`; the name with spaces where none is set)."""
        return TITLES.get(self.name, self.name.replace("_", " "))

    def to_json(self):
        """The contract's check object: name, subject, value, limit, unit, ok (+ kind, note)."""
        out = asdict(self)
        for key in ("value", "limit"):
            if not math.isfinite(out[key]):
                out[key] = None
        return out

    @property
    def computed(self):
        """Value and limit are numbers (a check that could not be computed has NaN)."""
        return math.isfinite(self.value) and math.isfinite(self.limit)

    def shown(self, key):
        """``value`` or ``limit`` for a table: 4 significant digits (whole numbers from 10 000
        on, not ``2.969e+04``), ``-`` where not computed."""
        number = getattr(self, key)
        if not math.isfinite(number):
            return "-"
        return f"{number:.0f}" if abs(number) >= 1e4 else f"{number:.4g}"

    def line(self):
        """One console line, ``FAIL swl L2: 452.1 t > 400 t (note)`` or ``ok ...``; a check
        whose value or limit could not be computed reads ``FAIL name subject: not computed``."""
        word = "ok  " if self.ok else "FAIL"
        note = f" ({self.note})" if self.note else ""
        if not self.computed:
            said = self.note.startswith("not computed")  # the note already says so and why
            return f"{word} {self.name} {self.subject}: " + (self.note if said else f"not computed{note}")
        upper = self.kind == "max"
        sign = ("<=" if upper else ">=") if self.ok else (">" if upper else "<")
        return (
            f"{word} {self.name} {self.subject}: {self.value:.4g} {self.unit} {sign} "
            f"{self.limit:.4g} {self.unit}{note}"
        )


def failed(checks):
    """The checks that failed, in order."""
    return [c for c in checks if not c.ok]

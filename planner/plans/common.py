"""What every kind of plan shares: the plan JSON's fixed keys and the objectives in words."""

from __future__ import annotations

import numpy as np

from liftplan.model.frames import zup_to_choi
from liftplan.planner.problem.objectives import OBJECTIVES

#: The plan JSON keys scripts rely on (``docs/scene-files.md``); every kind of plan writes them
#: the same way.
CONTRACT_KEYS = (
    "lugs",
    "boom_heights",
    "tensions",
    "spread",
    "worst_spread",
    "objective",
    "cranes",
    "radius",
    "swl",
    "utilisation",
    "worst_utilisation_spread",
)


def contract_json(plan):
    """The plan JSON's fixed keys (:data:`CONTRACT_KEYS`), read off the plan's attributes."""
    return {key: getattr(plan, key) for key in CONTRACT_KEYS}


def weight_json(problem):
    """The plan JSON's ``weight``: W [t] and its basis (``"air"``, ``"water"`` or
    ``"not stated"``, ``[body] weight_basis``)."""
    return {"value": problem.body.weight, "basis": problem.weight_basis or "not stated"}


#: What each objective keeps small, in words.
OBJECTIVE_TEXT = {name: objective.text for name, objective in OBJECTIVES.items()}


class InFileFrame:
    """The planning file's frame for a plan with a ``problem``: every coordinate a person
    reads (JSON, console, report) goes through :meth:`in_file_frame`."""

    @property
    def frame(self):
        """Frame of the planning file (``"z-up"`` or ``"choi"``)."""
        return self.problem.frame

    def in_file_frame(self, vector):
        """A z-up body-frame point or vector in the planning file's frame  [m]."""
        vector = tuple(float(v) for v in vector)
        return tuple(float(v) for v in zup_to_choi(vector)) if self.frame == "choi" else vector

    def cog_at(self, scenario):
        """The CG position of a scenario (nominal CG + its offset) in the file's frame  [m]."""
        cog = np.asarray(self.problem.body.cog) + np.asarray(scenario.cog_offset)
        return self.in_file_frame(cog)

    def scenario_json(self, scenario):
        """A scenario as JSON: heel, trim [deg], CG offset and CG position [m] in the file's frame."""
        return {
            "heel": scenario.heel,
            "trim": scenario.trim,
            "cog_offset": list(self.in_file_frame(scenario.cog_offset)),
            "cog": list(self.cog_at(scenario)),
            "frame": self.frame,
        }

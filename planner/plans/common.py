"""What every kind of plan shares: the plan JSON's fixed keys and the objectives in words."""

from __future__ import annotations

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

"""How accurate the lift's live readings are (``[readings]`` in a planning file).

``liftplan watch`` weighs each reading by one over its variance: a load cell's tension, an
inclinometer's heel and trim, a hook's measured height. Each accuracy is one standard
deviation of that instrument's reading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from liftplan.model.errors import InvalidScene

#: Defaults: a load cell good to 1 t, an inclinometer to 0.05 deg, a hook height to 0.01 m.
DEFAULT_LOAD_CELL = 1.0
DEFAULT_INCLINOMETER = 0.05
DEFAULT_HOOK = 0.01


@dataclass(frozen=True)
class ReadingsAccuracy:
    """One standard deviation of each instrument's reading.

    Parameters
    ----------
    load_cell : float  [t]
        Of each crane's load-cell tension.
    inclinometer : float  [deg]
        Of the hull's heel and of its trim.
    hook : float  [m]
        Of each hook's measured height (boom-tip height above the datum).
    """

    load_cell: float = DEFAULT_LOAD_CELL
    inclinometer: float = DEFAULT_INCLINOMETER
    hook: float = DEFAULT_HOOK

    def __post_init__(self):
        for key, unit in (("load_cell", "t"), ("inclinometer", "deg"), ("hook", "m")):
            value = getattr(self, key)
            if (
                isinstance(value, bool)
                or not isinstance(value, (int, float))
                or not math.isfinite(value)
                or value <= 0
            ):
                raise InvalidScene(
                    f"readings.{key}_accuracy = {value!r}: expected a standard deviation > 0 {unit}"
                )
            object.__setattr__(self, key, float(value))

    def to_json(self):
        return {
            "load_cell_accuracy": self.load_cell,
            "inclinometer_accuracy": self.inclinometer,
            "hook_accuracy": self.hook,
        }

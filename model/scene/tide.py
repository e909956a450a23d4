"""The tide over the operation (``[tide]``): a water level that changes during the lift.

A tide table gives the water level (a world height, m, on the datum of the boom heights) at
times (h), linear between points. The scene's boom heights and ``[water] level`` are those at
the table's first time; solved at ``time``, the water has risen by level(time) - level(first):

* every floating crane (``[[cranes]] vessel``) rises with it: its boom tip is that much higher
  (the tidal lift of a salvage: the vessels, made fast to the wreck, lift it as the tide comes
  in); a crane on land or a jack-up stays where it is;
* a hull in water (``[water]``) sees the water level that much higher.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene


@dataclass(frozen=True)
class Tide:
    """A tide table and the time the scene is solved at.

    Parameters
    ----------
    table : tuple of (float, float)  [h, m]
        (time, water level) points, times strictly increasing, two or more.
    time : float or None  [h]
        When the scene is solved, within the table (None: its first time).
    """

    table: tuple[tuple[float, float], ...]
    time: float | None = None

    def __post_init__(self):
        expected = "expected [[time h, level m], ...] with two or more points, times increasing"
        try:
            rows = [tuple(float(v) for v in row) for row in self.table]
        except (TypeError, ValueError):
            raise InvalidScene(f"tide.table = {self.table!r}: {expected}") from None
        if len(rows) < 2 or any(len(r) != 2 for r in rows):
            raise InvalidScene(f"tide.table = {self.table!r}: {expected}")
        if not all(math.isfinite(v) for r in rows for v in r):
            raise InvalidScene(f"tide.table = {self.table!r}: expected finite numbers")
        if any(b[0] <= a[0] for a, b in zip(rows, rows[1:])):
            raise InvalidScene(f"tide.table: times {[r[0] for r in rows]} h; {expected}")
        object.__setattr__(self, "table", tuple(rows))
        if self.time is not None:
            time = float(self.time)
            first, last = rows[0][0], rows[-1][0]
            if not first <= time <= last:
                raise InvalidScene(
                    f"tide.time = {self.time!r}: outside the table ({first:g} to {last:g} h); expected "
                    "a time within it"
                )
            object.__setattr__(self, "time", time)

    def level(self, time=None):
        """The water level at a time (default :attr:`time`)  [m]."""
        time = (
            self.table[0][0] if time is None and self.time is None else (self.time if time is None else time)
        )
        times, levels = zip(*self.table)
        return float(np.interp(time, times, levels))

    @property
    def rise(self):
        """How much the water has risen at :attr:`time` since the table's first time  [m]."""
        return self.level() - self.table[0][1]


@dataclass(frozen=True)
class TideState:
    """The tide a scene was solved at.

    Parameters
    ----------
    time : float  [h]
    level : float  [m]
        The water level then.
    rise : float  [m]
        Since the table's first time: what the floating cranes' tips and the water rose by.
    """

    time: float
    level: float
    rise: float

    def to_json(self):
        return {"time": self.time, "level": self.level, "rise": self.rise}


def apply_tide(scene):
    """The scene at its tide's time, and the tide's state (None without a tide).

    Returns
    -------
    (Scene, TideState or None)
        The scene with every floating crane's boom height and the water level raised by the
        tide's rise, and no tide (so it is applied once).
    """
    tide = scene.tide
    if tide is None:
        return scene, None
    rise = tide.rise
    cranes = tuple(
        dataclasses.replace(c, boom_height=c.boom_height + rise)
        if c.vessel is not None and c.boom_height is not None
        else c
        for c in scene.cranes
    )
    water = None if scene.water is None else dataclasses.replace(scene.water, level=scene.water.level + rise)
    time = tide.table[0][0] if tide.time is None else tide.time
    state = TideState(time=time, level=tide.level(), rise=rise)
    return dataclasses.replace(scene, cranes=cranes, water=water, tide=None), state

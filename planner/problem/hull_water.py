"""The hull's stiffness and the water in a planning file: what a plan of them needs.

A planning file may give a scene's ``[hull]`` and ``[water]`` tables:

* ``[hull] EI`` (and ``GJ``): the hull girder's stiffness. The planner searches on the rigid
  hull and then evaluates the ranked sets again on the flexible hull at their worst states
  (:mod:`liftplan.planner.plans.flexible`); where flexibility changes a tension by more than
  1 % (the rule ``liftplan solve`` uses) the flexible numbers govern that set.
* ``[water]`` with ``[hull]`` geometry (``box`` or ``mesh``) and ``[plan] start_lift_height``:
  the lift starts with the hull partly submerged. The buoyancy and its centre at that height
  change each rope's share; that state is one more case of the plan's worst states
  (:mod:`liftplan.planner.plans.in_water`).

:func:`check_hull_water` refuses the combinations the two are not planned for, each in one
line (docs/planning.md "What the planner does not plan").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from liftplan.model.errors import InvalidScene
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.objects import Water


@dataclass(frozen=True)
class InWater:
    """Where the lift starts: the hull partly submerged.

    Parameters
    ----------
    hull : Hull
        Its geometry (``[hull] box`` or ``mesh``; body frame, z-up), with its flooding.
    water : Water
        Density and surface height (``[water]``).
    start_lift_height : float  [m]
        World height of the body origin when the lift starts (``[plan] start_lift_height``),
        the body level: the hull's draft there is ``water.level`` minus its lowest point.
    hull_lines : tuple of str
        The ``[hull]`` geometry keys as TOML lines in the planning file's frame (a mesh by its
        absolute path), for the plan's written scene.
    """

    hull: Hull
    water: Water
    start_lift_height: float
    hull_lines: tuple = ()

    def __post_init__(self):
        if not isinstance(self.hull, Hull):
            raise InvalidScene(f"hull = {self.hull!r}: expected a Hull (box or mesh)")
        if not isinstance(self.start_lift_height, int | float) or not math.isfinite(self.start_lift_height):
            raise InvalidScene(
                f"plan.start_lift_height = {self.start_lift_height!r}: expected a finite number (m)"
            )


def check_hull_water(problem):
    """Refuse the plans the flexible hull and the lift in water are not made for (one line each).

    Both are planned for single ropes of fixed length on cranes on land with a held preload
    (spread, utilisation and reserve objectives, any search); the flexible hull needs the
    weight curve (its beam's loads).

    Raises
    ------
    InvalidScene
    """
    stiff, water = problem.hull_stiffness, problem.in_water
    if stiff is None and water is None:
        return
    fleet = problem.fleet
    what = "[hull] EI" if stiff is not None else "[water]"
    if stiff is not None and problem.body.weight_curve is None:
        raise InvalidScene(
            "hull.EI: the flexible hull is a beam loaded by the body's weight curve; expected "
            "body.weight_curve = [[x m, t/m], ...]"
        )
    if stiff is not None:
        span = (problem.body.weight_curve[0][0], problem.body.weight_curve[-1][0])
        for c in problem.candidates:
            if not span[0] <= c.at[0] <= span[1]:
                raise InvalidScene(
                    f"candidates[{c.name}].at: x {c.at[0]:g} m lies outside the hull girder "
                    f"(body.weight_curve spans {span[0]:g} to {span[1]:g} m); expected every candidate on it"
                )
    if water is not None and problem.weight_basis == "water":
        raise InvalidScene(
            'body.weight_basis = "water" with [water]: the plan subtracts the hull\'s buoyancy at '
            'the start in water itself; expected the weight in air (weight_basis = "air")'
        )
    if any(c.sling is not None for c in fleet):
        raise InvalidScene(
            f"{what}: planned for single ropes (the legs of a sling pull the lugs along their lines, "
            "which the flexible hull and the held state in water do not model); expected no cranes.sling"
        )
    if problem.objective in ("bending", "shear", "strength"):
        raise InvalidScene(
            f"{what}: planned with the spread, utilisation or reserve objective; the strength "
            f"objective {problem.objective!r} plans its own forces on the rigid hull in air"
        )
    if any(c.rope_length_range is not None for c in fleet):
        raise InvalidScene(
            f"{what}: planned at fixed rope lengths; expected rope_length a number, not a range "
            "(choose the lengths first, then plan with them)"
        )
    if any(c.vessel is not None for c in fleet):
        raise InvalidScene(
            f"{what}: planned for cranes on land; a floating crane's vessel in series with the "
            "flexible hull or the hull in water is not modelled; expected no cranes.vessel"
        )

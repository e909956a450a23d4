"""Implausible magnitudes in a planning problem: warnings, not errors.

The same idea as :mod:`liftplan.model.scene.plausibility` (whose weight and height rules are
reused), plus the planning keys a unit slip hits most: the hook-height tolerance (mm typed
as m) and the heel/trim tolerance box.
"""

from __future__ import annotations

from liftplan.model.scene.plausibility import coordinate_warnings, height_warnings, weight_warnings
from liftplan.model.water.breakout import bed_warnings
from liftplan.model.water.equilibrium import WaterSetup

#: A hook-height tolerance above this is likely in mm  [m].
MAX_HOOK_TOLERANCE = 0.5
#: A heel or trim tolerance above this is no lift anyone would plan  [deg].
MAX_TOLERANCE = 30.0


def _swl_total(problem):
    """The fleet's total capacity (largest SWL of each crane's chart)  [t]."""
    total = 0.0
    for crane in problem.fleet:
        if crane.swl:
            total += crane.swl
        elif crane.load_chart:
            total += max(swl for _, swl in crane.load_chart)
        else:
            return None
    return total


def problem_warnings(problem):
    """Implausible magnitudes of a planning problem.

    Parameters
    ----------
    problem : PlanProblem

    Returns
    -------
    list of str
        One line each, naming the key, the value and the likely slip.
    """
    out = [
        *weight_warnings("body.weight", problem.body.weight, _swl_total(problem)),
        *height_warnings("attitude.lift_height", problem.lift_height),
        *coordinate_warnings("candidates", [(c.name, c.at) for c in problem.candidates]),
    ]
    out += _undrained_water(problem)
    out += _daf_in_water(problem)
    if problem.breakout_scene is not None:
        out += bed_warnings(problem.breakout_scene, "plan.breakout_scene: ground.breakout")
    if problem.hook_tolerance > MAX_HOOK_TOLERANCE:
        out.append(
            f"plan.hook_tolerance = {problem.hook_tolerance:g} m: more than "
            f"{MAX_HOOK_TOLERANCE:g} m of hook-height error; mm typed as m?"
        )
    for axis in ("heel", "trim"):
        value = getattr(problem, f"{axis}_tolerance")
        if value > MAX_TOLERANCE:
            out.append(
                f"plan.tolerance.{axis} = {value:g} deg: a box wider than {MAX_TOLERANCE:g} deg "
                "each way; a slip (radians? a total instead of a half-width?)"
            )
    return out


def _daf_in_water(problem):
    """A weight in water with the DAF from 0027/ND Table 5-1, the table for lifts in air."""
    rules = problem.rules
    if problem.weight_basis != "water" or rules.daf is not None or rules.chart_includes_dynamics:
        return []
    return [
        'body.weight_basis = "water" with the DAF from 0027/ND Table 5-1, which is for lifts in '
        "air: below the surface added mass, drag and slamming load the hooks too; expected "
        "[rules] daf from a calculation for the lift in water where it governs (the in-air "
        "Table 5-1 DAF is applied to W as given)"
    ]


def _undrained_water(problem):
    """The breakout scene's water in compartments, which the in-air case leaves out."""
    if problem.breakout_scene is None or problem.breakout_scene.hull is None:
        return []
    water = WaterSetup(problem.breakout_scene).trapped
    if water <= 0.0:
        return []
    weight = problem.body.weight
    return [
        f"plan.breakout_scene: its compartments hold {water:.1f} t of water that the in-air case "
        f"(body.weight = {weight:g} t) takes as drained; if it has not drained when the body "
        f"clears the water the hooks carry up to {weight + water:.1f} t (liftplan lift --speed "
        "shows how much drains; plan that case with a heavier [body])"
    ]

"""Checks of the hull girder against the allowable envelopes of ``[strength]``."""

from __future__ import annotations

from liftplan.model.checks import Check
from liftplan.model.strength.girder import hull_girder

#: (check name, what the value is, unit, the GirderForces curve) of the two quantities.
QUANTITIES = (
    ("bending_moment", "|M|", "t m", "moment_curve"),
    ("shear_force", "|Q|", "t", "shear_curve"),
)


def worst_ratios(strength, girder):
    """Where |M| / allowable and |Q| / allowable are largest along the body, exactly.

    Parameters
    ----------
    strength : Strength
        The allowable envelopes (``[strength]``); a quantity without one is left out.
    girder : GirderForces
        A solved state's curves (:func:`~liftplan.model.strength.hull_girder`).

    Returns
    -------
    list of (str, float, float, float)
        (check name, x [m], |value| [t m or t], allowable there [t m or t]) per envelope
        given, bending first (:meth:`~liftplan.model.strength.piecewise.Piecewise.worst_ratio`).
    """
    out = []
    for name, _, _, curve in QUANTITIES:
        envelope = getattr(strength, name)
        if envelope is not None:
            x, value, limit = getattr(girder, curve).worst_ratio(envelope)
            out.append((name, float(x), float(value), float(limit)))
    return out


def strength_checks(scene, eq, girder=None):
    """The bending-moment and shear-force checks of a solved state, at the worst ratio point.

    Parameters
    ----------
    scene : Scene
        Its ``strength`` gives the envelopes; none, or no ``body.weight_curve``: no checks.
    eq : Equilibrium
    girder : GirderForces, optional
        Already computed by :func:`~liftplan.model.strength.hull_girder` for this state.

    Returns
    -------
    list of Check
        ``Check.upper("bending_moment", "x = 40.2 m", |M|, allowable, "t m")`` and the same for
        ``"shear_force"`` (t), each where |value| / allowable(x) is largest along the body
        (found exactly, :func:`worst_ratios`).
    """
    if scene.strength is None or scene.body.weight_curve is None:
        return []
    if girder is None:
        girder = hull_girder(scene, eq)
    symbols = {name: (what, unit) for name, what, unit, _ in QUANTITIES}
    checks = []
    for name, x, value, limit in worst_ratios(scene.strength, girder):
        what, unit = symbols[name]
        checks.append(
            Check.upper(
                name,
                f"x = {x:.1f} m",
                value,
                limit,
                unit,
                note=f"{what} / allowable = {value / limit:.0%}, the worst along the body",
            )
        )
    return checks

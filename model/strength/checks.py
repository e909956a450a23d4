"""Checks of the hull girder against the allowable envelopes of ``[strength]``."""

from __future__ import annotations

from liftplan.model.checks import Check
from liftplan.model.strength.girder import hull_girder


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
        (found exactly, :meth:`~liftplan.model.strength.piecewise.Piecewise.worst_ratio`).
    """
    if scene.strength is None or scene.body.weight_curve is None:
        return []
    if girder is None:
        girder = hull_girder(scene, eq)
    checks = []
    for name, curve, unit in (
        ("bending_moment", girder.moment_curve, "t m"),
        ("shear_force", girder.shear_curve, "t"),
    ):
        envelope = getattr(scene.strength, name)
        if envelope is None:
            continue
        x, value, limit = curve.worst_ratio(envelope)
        what = "|M|" if name == "bending_moment" else "|Q|"
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

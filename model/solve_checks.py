"""The checks of a solved state that can fail (see :class:`~liftplan.model.checks.Check`).

Each rope against its crane's SWL (where the scene gives one), each rope's tension against
zero (a rope cannot push), and, for a body in air, all ropes taut (a slack rope carries
nothing and leaves the body on the others). ``liftplan solve`` prints a FAIL line per
failed check and exits with its own code; ``--json`` carries them all as ``"checks"``.
"""

from __future__ import annotations

from liftplan.model.checks import Check


def equilibrium_checks(scene, eq):
    """Checks of one equilibrium, in lug order.

    Parameters
    ----------
    scene : Scene
    eq : Equilibrium

    Returns
    -------
    list of Check
        ``swl`` per rope with an SWL (tension <= SWL  [t]), ``min_tension`` per rope
        (tension >= 0  [t]) and, without a hull in water, one ``taut`` check (ropes carrying
        load >= all ropes  [-]); with crane vessels, :func:`vessel_checks`. Empty for a body
        with no ropes. With a wind the tensions are the windy ones and each ``swl`` note
        gives the wind's share of it.
    """
    checks = []
    share = (eq.wind.load_changes if eq.wind is not None else None) or {}
    for name, tension in eq.tensions.items():
        swl = eq.swl.get(name)
        if swl:
            note = f"rope tension / crane SWL = {tension / swl:.0%}"
            if name in share:
                note += f", the wind's share {share[name]:+.2f} t included"
            checks.append(Check.upper("swl", name, tension, swl, "t", note=note))
    for name, tension in eq.tensions.items():
        checks.append(Check.lower("min_tension", name, tension, 0.0, "t", note="a rope cannot push"))
    if eq.tensions and scene.hull is None:
        # in water or on the ground a slack rope is a state (the water or the ground carries
        # the body), not a failure; in air the ropes alone must hold it
        slack = [name for name in eq.tensions if name in eq.slack]
        verb = "carries" if len(slack) == 1 else "carry"
        note = f"slack: {', '.join(slack)} {verb} nothing, the body hangs on the others" if slack else ""
        checks.append(
            Check.lower("taut", "ropes", len(eq.tensions) - len(slack), len(eq.tensions), "-", note=note)
        )
    checks += vessel_checks(eq.vessels or {})
    return checks


def vessel_checks(vessels):
    """Each crane vessel's heel and trim against its limits, where the scene gives them.

    Parameters
    ----------
    vessels : dict of str to VesselState

    Returns
    -------
    list of Check
        ``vessel_heel`` and ``vessel_trim`` per vessel with ``max_heel`` / ``max_trim``
        (|angle| <= limit  [deg]); ``vessel_freeboard`` per vessel with ``freeboard``
        (the lowest deck corner's freeboard >= ``min_freeboard``  [m]).
    """
    checks = []
    for name, state in vessels.items():
        for key, angle, limit, sense in (
            ("vessel_heel", state.heel, state.max_heel, "starboard down"),
            ("vessel_trim", state.trim, state.max_trim, "bow down"),
        ):
            if limit is not None:
                note = f"{angle:+.3f} deg (+ {sense}) under {state.load:.1f} t, ballast included"
                checks.append(Check.upper(key, name, abs(angle), limit, "deg", note=note))
        if state.freeboard is not None:
            note = f"lowest deck corner under {state.load:.1f} t: heave, heel and trim, ballast included"
            checks.append(
                Check.lower("vessel_freeboard", name, state.freeboard, state.min_freeboard, "m", note=note)
            )
    return checks

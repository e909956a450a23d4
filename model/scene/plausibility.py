"""Implausible magnitudes in a scene: warnings, not errors.

A value can be valid and still many orders off its neighbours: a weight typed in kg where t
is meant, a hook tolerance in mm where m is meant. Such a scene solves, and the answer is
nonsense. Each rule here returns one line naming the key, the value and the likely slip;
the command line prints them as ``warning:`` lines on stderr and carries on.
"""

from __future__ import annotations

#: Heavier than anything lifted by cranes (the heaviest salvage lifts are ~ 1e4 t)  [t].
MAX_WEIGHT = 1e5
#: The cranes' total SWL below this fraction of the weight: the weight is likely in kg  [-].
MIN_SWL_FRACTION = 0.01
#: Lower than this below the datum is no lift height  [m].
LOWEST_HEIGHT = -100.0
#: Lug or candidate coordinates beyond this are likely in mm  [m].
LARGEST_COORDINATE = 1000.0


def weight_warnings(key, weight, swl_total=None):
    """Warnings on a weight  [t], given the cranes' total SWL  [t] when known."""
    out = []
    if weight > MAX_WEIGHT:
        out.append(f"{key} = {weight:g} t: heavier than any crane lift (> {MAX_WEIGHT:g} t); kg typed as t?")
    elif swl_total and swl_total < MIN_SWL_FRACTION * weight:
        out.append(
            f"{key} = {weight:g} t: over {1 / MIN_SWL_FRACTION:g} times the cranes' total SWL "
            f"{swl_total:g} t; kg typed as t?"
        )
    return out


def height_warnings(key, height):
    """Warnings on a height of the body above the datum  [m]."""
    if height < LOWEST_HEIGHT:
        return [
            f"{key} = {height:g} m: far below the datum (< {LOWEST_HEIGHT:g} m); "
            "a sign slip, or mm typed as m?"
        ]
    return []


def coordinate_warnings(key, points):
    """Warnings on body-frame points  [m] (one line for the first point far out)."""
    for name, at in points:
        far = max(abs(v) for v in at)
        if far > LARGEST_COORDINATE:
            return [
                f"{key}[{name}].at: {far:g} m from the body origin (> {LARGEST_COORDINATE:g} m); "
                "mm typed as m?"
            ]
    return []


def scene_warnings(scene):
    """Implausible magnitudes of a scene.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    list of str
        One line each, naming the key, the value and the likely slip.
    """
    swl = [c.swl for c in scene.cranes]
    total = sum(swl) if swl and all(swl) else None
    # a stranded ship with no ropes is no crane lift: its weight may be anything
    lifted = weight_warnings("body.weight", scene.body.weight, total) if scene.cranes else []
    return [
        *lifted,
        *height_warnings("attitude.lift_height", scene.attitude.lift_height),
        *coordinate_warnings("lugs", [(lug.name, lug.at) for lug in scene.lugs]),
    ]


def equilibrium_warnings(scene, eq):
    """Implausible results of a solve (the body hanging far below the datum).

    Parameters
    ----------
    scene : Scene
    eq : Equilibrium

    Returns
    -------
    list of str
    """
    height = eq.pose.lift_height
    if height < LOWEST_HEIGHT and scene.attitude.lift_height >= LOWEST_HEIGHT:
        return [
            f"solved lift_height = {height:.4g} m: the body hangs far below the datum "
            f"(< {LOWEST_HEIGHT:g} m); check body.weight (kg typed as t?), EA and rope_length"
        ]
    return []

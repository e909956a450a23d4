"""Rigging gear between a crane's hook and the body: sling sets and spreader bars.

Scene data only (frozen dataclasses that check their own values); the equilibrium with the
hook and the bar ends as free points is :mod:`liftplan.model.statics.rigging`.

A crane with a :class:`Sling` hangs its hoist rope (tip to hook, the crane's ``rope_length``
and ``EA``) and 2 to 4 legs from the hook to lugs. With a :class:`Spreader` the hook carries
two top legs to the bar's ends, and the legs (each naming its bar end) run from the ends
to the lugs. Sling stiffness is given as ``EA`` or as a wire-rope ``diameter``, from which
EA follows as Noble Denton 0027/ND (Rev 11, section 5.6.13) computes it for skew loads:
E = 80 000 N/mm2 on the area A = 0.785 d^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from liftplan.model.errors import InvalidScene

#: Elastic modulus of a wire-rope sling on its nominal area, N/mm2 (0027/ND 5.6.13).
SLING_MODULUS = 80_000.0
#: Nominal area factor, A = 0.785 d^2 (pi / 4 to three digits, as 0027/ND writes it).
AREA_FACTOR = 0.785
#: Newtons in one tonne-force (standard gravity 9.80665 m/s2).
NEWTON_PER_T = 9806.65
#: Default axial stiffness of a spreader bar [t]: a stiff steel strut (a 610 x 20 mm pipe has
#: EA = 210 000 N/mm2 x 37 100 mm2 = 0.79e6 t). The bar shortens by C L / EA under a
#: compression C, which moves the legs' geometry by millimetres: give the real EA if known.
SPREADER_EA = 1.0e6
#: Default lowest sling-leg angle from the horizontal [deg]; see README "Rigging".
MIN_SLING_ANGLE = 60.0


def sling_ea(diameter):
    """Axial stiffness of a wire-rope sling from its nominal diameter.

    Parameters
    ----------
    diameter : float  [mm]

    Returns
    -------
    float  [t]
        E A with E = 80 000 N/mm2 and A = 0.785 d^2 (0027/ND 5.6.13), in tonne-force.
    """
    return SLING_MODULUS * AREA_FACTOR * diameter**2 / NEWTON_PER_T


def _number(path, value, low=0.0, strict=True, unit=""):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{path} = {value!r}: expected a number") from None
    ok = number > low if strict else number >= low
    if not (math.isfinite(number) and ok):
        raise InvalidScene(
            f"{path} = {value!r}: expected a finite number {'>' if strict else '>='} {low:g}{unit}"
        )
    return number


def _set(obj, name, value):
    object.__setattr__(obj, name, value)


@dataclass(frozen=True)
class Leg:
    """One sling leg: an elastic line that carries tension only (a slack leg carries nothing).

    Parameters
    ----------
    lug : str or None
        The lug it is shackled to; None for a spreader's top leg (hook to bar end).
    length : float  [m]
        Unstretched length, pin to pin.
    EA : float or None  [t]
        Axial stiffness; or give ``diameter``.
    diameter : float or None  [mm]
        Wire-rope diameter; EA = :func:`sling_ea` (diameter).
    end : int or None
        With a spreader: the bar end (1 or 2) the leg hangs from.
    """

    lug: str | None
    length: float
    EA: float | None = None
    diameter: float | None = None
    end: int | None = None

    def __post_init__(self):
        if self.lug is not None and (not isinstance(self.lug, str) or not self.lug.strip()):
            raise InvalidScene(f"sling.legs.lug = {self.lug!r}: expected a lug name")
        where = f"sling.legs[{self.lug}]" if self.lug is not None else "sling.spreader.top[]"
        _set(self, "length", _number(f"{where}.length", self.length, unit=" m"))
        if (self.EA is None) == (self.diameter is None):
            both = "both EA and" if self.EA is not None else "neither EA nor"
            raise InvalidScene(
                f"{where}: {both} diameter given; expected exactly one (EA in t, or the "
                "wire diameter in mm, from which EA = 80 000 N/mm2 x 0.785 d^2)"
            )
        if self.EA is not None:
            _set(self, "EA", _number(f"{where}.EA", self.EA, unit=" t"))
        else:
            _set(self, "diameter", _number(f"{where}.diameter", self.diameter, unit=" mm"))
        if self.end is not None and self.end not in (1, 2):
            raise InvalidScene(f"{where}.end = {self.end!r}: expected 1 or 2 (a spreader bar end)")

    @property
    def stiffness(self):
        """EA  [t], given or from the diameter."""
        return self.EA if self.EA is not None else sling_ea(self.diameter)


@dataclass(frozen=True)
class Spreader:
    """A spreader bar between the hook's two top legs and the sling legs.

    Modelled as a stiff strut between its two end points (each a free point of the
    equilibrium), with half its weight at each end; see :mod:`liftplan.model.statics.rigging`.

    Parameters
    ----------
    length : float  [m]
        Unstressed distance between the two end pins.
    top : tuple of two Leg
        Hook to end 1 and hook to end 2 (``lug`` None).
    weight : float  [t]
        The bar's weight (with its shackles), half at each end.
    EA : float  [t]
        Axial stiffness (default :data:`SPREADER_EA`).
    """

    length: float
    top: tuple[Leg, ...]
    weight: float = 0.0
    EA: float = SPREADER_EA

    def __post_init__(self):
        _set(self, "length", _number("sling.spreader.length", self.length, unit=" m"))
        _set(self, "weight", _number("sling.spreader.weight", self.weight, strict=False, unit=" t"))
        _set(self, "EA", _number("sling.spreader.EA", self.EA, unit=" t"))
        top = tuple(self.top)
        if len(top) != 2 or any(not isinstance(leg, Leg) or leg.lug is not None for leg in top):
            raise InvalidScene(
                f"sling.spreader.top: {len(top)} given; expected two legs (hook to end 1, hook to "
                "end 2) with length and EA or diameter, and no lug"
            )
        _set(self, "top", top)


@dataclass(frozen=True)
class Sling:
    """A sling set of 2 to 4 legs on one crane hook, optionally through a spreader bar.

    Parameters
    ----------
    legs : tuple of Leg
        Hook (or bar end) to lug; each lug once.
    spreader : Spreader or None
    equalised : bool
        The two legs are one continuous rope over a sheave at the hook (or an equaliser):
        both carry the same tension whatever the hook height, and their unstretched lengths
        add up to the legs' total, the split following the equilibrium. Two legs of one
        EA, no spreader.
    """

    legs: tuple[Leg, ...]
    spreader: Spreader | None = None
    equalised: bool = False

    def __post_init__(self):
        legs = tuple(self.legs)
        if not 2 <= len(legs) <= 4:
            raise InvalidScene(f"sling.legs: {len(legs)} given; expected 2 to 4 legs")
        for leg in legs:
            if not isinstance(leg, Leg) or leg.lug is None:
                raise InvalidScene(f"sling.legs: {leg!r}: expected a leg with lug, length and EA or diameter")
        names = [leg.lug for leg in legs]
        for name in names:
            if names.count(name) > 1:
                raise InvalidScene(f"sling.legs.lug = {name!r}: used twice; expected each lug once")
        if self.spreader is None:
            for leg in legs:
                if leg.end is not None:
                    raise InvalidScene(
                        f"sling.legs[{leg.lug}].end = {leg.end!r}: no spreader bar; expected no end"
                    )
        else:
            if len(legs) == 2 and all(leg.end is None for leg in legs):
                legs = tuple(
                    Leg(leg.lug, leg.length, leg.EA, leg.diameter, end=k + 1) for k, leg in enumerate(legs)
                )
            missing = [leg.lug for leg in legs if leg.end is None]
            if missing:
                raise InvalidScene(
                    f"sling.legs[{missing[0]}].end: missing; expected end = 1 or 2 (the spreader "
                    "bar end it hangs from) on every leg, or two legs (ends 1 and 2 in order)"
                )
            for end in (1, 2):
                if not any(leg.end == end for leg in legs):
                    raise InvalidScene(
                        f"sling.legs: no leg hangs from spreader end {end}; expected at least one "
                        "leg on each end"
                    )
        _set(self, "legs", legs)
        if not isinstance(self.equalised, bool):
            raise InvalidScene(f"sling.equalised = {self.equalised!r}: expected true or false")
        if self.equalised:
            if len(legs) != 2 or self.spreader is not None:
                raise InvalidScene(
                    f"sling.equalised = true with {len(legs)} legs"
                    f"{' and a spreader bar' if self.spreader is not None else ''}; expected two "
                    "legs and no spreader (one rope over a sheave at the hook)"
                )
            if legs[0].stiffness != legs[1].stiffness:
                raise InvalidScene(
                    f"sling.equalised = true with legs of EA {legs[0].stiffness:g} t and "
                    f"{legs[1].stiffness:g} t; expected one rope: the same EA (or diameter) on both"
                )

    @property
    def rope_length(self):
        """An equalised sling's whole rope, lug over the sheave to lug (unstretched)  [m]."""
        return sum(leg.length for leg in self.legs)

    @property
    def lugs(self):
        """The lugs of the legs, in leg order."""
        return tuple(leg.lug for leg in self.legs)


@dataclass(frozen=True)
class RiggingLimits:
    """Limits checked on the rigging (the scene's ``[rigging]`` table).

    Parameters
    ----------
    min_sling_angle : float  [deg]
        Lowest leg angle from the horizontal (default :data:`MIN_SLING_ANGLE`); legs below it
        are flagged by :func:`liftplan.model.statics.rigging.rigging_checks`.
    """

    min_sling_angle: float = MIN_SLING_ANGLE

    def __post_init__(self):
        angle = _number("rigging.min_sling_angle", self.min_sling_angle, unit=" deg")
        if angle > 90.0:
            raise InvalidScene(
                f"rigging.min_sling_angle = {self.min_sling_angle!r}: expected an angle in (0, 90] "
                "deg from the horizontal"
            )
        _set(self, "min_sling_angle", angle)

"""The rules' settings for one lift: every factor with its default, each overridable.

:class:`Rules` is what a ``[rules]`` table of a planning file becomes (see
:mod:`liftplan.model.rules.table`); built in Python it checks the same values with the same
one-line errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import factors
from liftplan.model.rules.codes import CODES, DEFAULT_CODE


def _set(obj, name, value):
    object.__setattr__(obj, name, value)


def _optional_factor(obj, name):
    value = getattr(obj, name)
    if value is not None:
        _set(obj, name, factors.factor_at_least_one(f"rules.{name}", value))


def _non_negative(key, value):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{key} = {value!r}: expected a number >= 0") from None
    if not math.isfinite(number) or number < 0.0:
        raise InvalidScene(f"{key} = {value!r}: expected a finite number >= 0")
    return number


#: The DAF column assumed when none is given: the most onerous.
DEFAULT_LOCATION = "offshore"


@dataclass(frozen=True)
class Rules:
    """Settings of the design-load chain (0027/ND Rev 11 unless a field says otherwise).

    Parameters
    ----------
    location : {"onshore", "inshore", "offshore"} or None
        Column of the DAF table (Table 5-1). Default (None): ``"offshore"``, the most
        onerous, assumed (:attr:`location_assumed`).
    weight_contingency : float  [-]
        Design Weight = weight x this (6.2.1). Default 1.05 (project assumption, see
        :func:`~liftplan.model.rules.factors.weight_contingency`).
    cog_factor : float or None  [-]
        Factor on the shares when no CoG envelope is searched (6.2.3); required then.
    daf : float or None  [-]
        Replaces Table 5-1.
    skew_factor : float or None  [-]
        Replaces both the computed skew factor and the default 1.25 (5.6.12).
    tilt : float or None  [deg]
        Replaces the rules' tilt (3 deg one vessel, 5 deg separate vessels; 5.4).
    hook_elevation : float or None  [m]
        Replaces the rules' hook elevation difference (+-1.0 m; 5.4.2, 5.4.5).
    yaw_factor : float  [-]
        5.4.7, default 1.05; lift points of hooks carrying more than one sling.
    separate_vessels : bool
        Cranes on separate vessels (5.4.4, 5.4.5: 5 deg).
    synchronised_sheerleg : bool
        Hooks of one sheerleg vessel, closely synchronised (5.4.6: the one-vessel factors halved).
    rigging_weight : float or dict of str -> float  [t]
        Hook block, slings, shackles and spreader hanging on each hook (6.2.4), one value for
        every crane or one per crane name (missing names: 0).
    consequence_factor : float  [-]
        Lift points (Table 11-1): 1.30.
    lateral_fraction : float  [-]
        Lateral load on a lift point as a fraction of its factored load (default 0.05).
    chart_includes_dynamics : bool
        The load chart already includes a dynamic allowance (10.3.2): the static hook load is
        compared with it instead of the dynamic one.
    code_margin : float or None  [-]
        Replaces the crane-code margin 20 / 33 / 50 % (0 switches the check off).
    code : str
        The rules code the factors come from (:data:`~liftplan.model.rules.codes.CODES`);
        default ``"0027/ND"``, the only one implemented.
    location_assumed : bool
        Set when ``location`` is not given (None): the most onerous column, ``"offshore"``,
        was assumed; every output that shows the DAF says so.
    """

    location: str | None = None
    weight_contingency: float = factors.DEFAULT_WEIGHT_CONTINGENCY
    cog_factor: float | None = None
    daf: float | None = None
    skew_factor: float | None = None
    tilt: float | None = None
    hook_elevation: float | None = None
    yaw_factor: float = factors.DEFAULT_YAW_FACTOR
    separate_vessels: bool = False
    synchronised_sheerleg: bool = False
    rigging_weight: float | dict = 0.0
    consequence_factor: float = factors.LIFT_POINT_CONSEQUENCE
    lateral_fraction: float = factors.LATERAL_FRACTION
    chart_includes_dynamics: bool = False
    code_margin: float | None = field(default=None)
    code: str = DEFAULT_CODE
    location_assumed: bool = False  # an init field: dataclasses.replace carries it

    def __post_init__(self):
        if self.location is None:  # not given: the most onerous column, and say so
            _set(self, "location", DEFAULT_LOCATION)
            _set(self, "location_assumed", True)
        if self.code not in CODES:
            raise InvalidScene(f"rules.code = {self.code!r}: expected one of {', '.join(CODES)}")
        if self.location not in factors.LOCATIONS:
            raise InvalidScene(
                f"rules.location = {self.location!r}: expected one of {', '.join(factors.LOCATIONS)}"
            )
        for name in ("separate_vessels", "synchronised_sheerleg", "chart_includes_dynamics"):
            if not isinstance(getattr(self, name), bool):
                raise InvalidScene(f"rules.{name} = {getattr(self, name)!r}: expected true or false")
        _set(self, "weight_contingency", factors.weight_contingency(self.weight_contingency))
        _set(self, "yaw_factor", factors.factor_at_least_one("rules.yaw_factor", self.yaw_factor))
        _set(
            self,
            "consequence_factor",
            factors.factor_at_least_one("rules.consequence_factor", self.consequence_factor),
        )
        for name in ("cog_factor", "daf", "skew_factor"):
            _optional_factor(self, name)
        if self.tilt is not None:
            tilt = _non_negative("rules.tilt", self.tilt)
            if tilt >= 30.0:
                raise InvalidScene(f"rules.tilt = {self.tilt!r}: expected a design tilt in [0, 30) deg")
            _set(self, "tilt", tilt)
        if self.hook_elevation is not None:
            _set(self, "hook_elevation", _non_negative("rules.hook_elevation", self.hook_elevation))
        lateral = _non_negative("rules.lateral_fraction", self.lateral_fraction)
        if lateral >= 1.0:
            raise InvalidScene(
                f"rules.lateral_fraction = {self.lateral_fraction!r}: expected a fraction in [0, 1)"
            )
        _set(self, "lateral_fraction", lateral)
        if isinstance(self.rigging_weight, dict):
            _set(
                self,
                "rigging_weight",
                {
                    str(k): _non_negative(f"rules.rigging_weight.{k}", v)
                    for k, v in self.rigging_weight.items()
                },
            )
        else:
            _set(self, "rigging_weight", _non_negative("rules.rigging_weight", self.rigging_weight))
        if self.code_margin is not None:
            _set(self, "code_margin", factors.code_margin(2, self.code_margin))
        factors.rules_tilt(self.separate_vessels, self.synchronised_sheerleg)  # refuses the bad pair
        if self.daf is None and self.separate_vessels and self.location == "offshore":
            raise InvalidScene(
                "rules.daf: missing; Table 5-1 covers lifts by 2 or more vessels only inshore in totally "
                "sheltered waters (0027/ND 5.5.2), offshore multi-vessel DAFs are set by 5.5.4-5.5.6 "
                '(not stored here): expected [rules] daf for location = "offshore" with separate_vessels'
            )

    def rigging_for(self, crane):
        """Rigging weight hanging on ``crane``'s hook  [t]."""
        if isinstance(self.rigging_weight, dict):
            return self.rigging_weight.get(crane, 0.0)
        return self.rigging_weight

    def design_tilt(self):
        """The tilt and hook elevation difference this lift is designed for: (deg, m)."""
        tilt, elevation = factors.rules_tilt(self.separate_vessels, self.synchronised_sheerleg)
        return (
            self.tilt if self.tilt is not None else tilt,
            self.hook_elevation if self.hook_elevation is not None else elevation,
        )

    @property
    def factors(self):
        """The module of the rules code's factors (:data:`~liftplan.model.rules.codes.INTERFACE`)."""
        return CODES[self.code][1]

    @property
    def code_title(self):
        """The rules code in words (for the basis of a plan)."""
        return CODES[self.code][0]

    @property
    def location_text(self):
        """The location (the DAF column) in words, saying when it was assumed."""
        if self.location_assumed:
            return f"{self.location} (assumed: [rules] location not given)"
        return self.location

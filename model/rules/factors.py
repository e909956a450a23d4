"""The rules' factors, one small function each, with the clause it comes from.

Source, unless a docstring says otherwise: GL Noble Denton *Guidelines for marine lifting &
lowering operations*, 0027/ND Rev 11 (14 Dec 2015; Rev 11.2, 8 Jul 2016, which points to
DNVGL-ST-N001 as its replacement). The clause text quoted in the docstrings was read from
stored public copies of that edition; where a value could not be found stored, the docstring
says so and the value is this project's stated assumption, overridable in ``[rules]``.

Every function takes and returns plain floats (t, m, deg) and raises
:class:`~liftplan.model.errors.InvalidScene` with one line naming the key, the value and
what is expected.
"""

from __future__ import annotations

import math

from liftplan.model.errors import InvalidScene

#: Where each factor comes from (shown beside its value in every output).
SOURCES = {
    "weight_contingency": "0027/ND Rev 11 6.2.1 -> 0001/ND 8.3.1-8.3.3 (value: project default, "
    "clause value not stored here)",
    "cog_envelope": "0027/ND Rev 11 6.2.3 / 6.3.1: hook and lift point loads at the extremes of "
    "the CoG envelope (searched by the planner)",
    "cog_factor": "0027/ND Rev 11 6.2.3 -> 0001/ND 8.3.3 (hooks), 6.3.1 -> 0001/ND 8.4.3 (lift "
    "points); value not stored here, given in [rules]",
    "tilt": "0027/ND Rev 11 5.4.2-5.4.6, Appendix B.1 (2-hook lift factors)",
    "daf": "0027/ND Rev 11 5.5.1 Table 5-1 (in air), 5.5.2",
    "skew": "0027/ND Rev 11 5.6.12 (SKL 1.25, matched slings) / 5.6.13 (computed: E = 80 000 N/mm2, "
    "A = 0.785 d2)",
    "yaw": "0027/ND Rev 11 5.4.7 (yaw effect factor 1.05, more than one sling on the hook)",
    "rigging": "0027/ND Rev 11 6.2.2, 6.2.4 (static hook load = design weight + rigging weight)",
    "hook_check": "0027/ND Rev 11 10.3.1 (dynamic hook load against the load-radius curve) / 10.3.2",
    "consequence": "0027/ND Rev 11 11.4.1 Table 11-1 (lift points 1.30), 11.4.2",
    "lateral": "lift point lateral load, 5 % of the factored lift point load: common practice "
    "(0027/ND Section 12); clause text not stored here",
    "code_margin": "crane-code capacity margin over the calculated share: 20 % for 2 cranes "
    "(AS 2550.1, non-synchronised), 33 % / 50 % for 3 / 4+ (common practice; "
    "no stored clause)",
}

LOCATIONS = ("onshore", "inshore", "offshore")

#: 0027/ND Rev 11 Table 5-1 rows above 100 t: (upper gross weight [t], onshore, inshore, offshore).
DAF_TABLE = (
    (300.0, 1.05, 1.12, 1.25),
    (1000.0, 1.05, 1.10, 1.20),
    (2500.0, 1.03, 1.08, 1.15),
    (math.inf, 1.03, 1.05, 1.10),
)
#: Table 5-1 note 1: items under 3 t are taken as 3 t.
DAF_MIN_WEIGHT = 3.0

#: 0027/ND Rev 11 5.6.12: skew load factor for indeterminate 4-sling lifts, matched slings.
DEFAULT_SKEW_FACTOR = 1.25
#: 0027/ND Rev 11 5.6.13: sling modulus for a computed skew load [N/mm2] and area factor (A = 0.785 d2).
SLING_MODULUS = 80_000.0
SLING_AREA_FACTOR = 0.785
#: 0027/ND Rev 11 5.4.7.
DEFAULT_YAW_FACTOR = 1.05
#: 0027/ND Rev 11 5.4.2 (one vessel) and 5.4.4 / 5.4.5 (separate vessels): tilt [deg] and hook
#: elevation difference [m]; 5.4.6 halves the one-vessel values for a synchronised sheerleg.
TILT_ONE_VESSEL = 3.0
TILT_SEPARATE_VESSELS = 5.0
HOOK_ELEVATION = 1.0
#: 0027/ND Rev 11 Table 11-1: consequence factor for lift points.
LIFT_POINT_CONSEQUENCE = 1.30
#: Lateral lift point load as a fraction of the factored lift point load (see SOURCES["lateral"]).
LATERAL_FRACTION = 0.05
#: Project default weight contingency (see :func:`weight_contingency`).
DEFAULT_WEIGHT_CONTINGENCY = 1.05

#: Crane-code capacity margin over the calculated share for 2, 3 cranes; 4 or more: CODE_MARGIN_MANY.
CODE_MARGIN = {2: 0.20, 3: 0.33}
CODE_MARGIN_MANY = 0.50

_G = 9.80665  # m/s2: N per kg, for t (tonne-force) = 9806.65 N


def factor_at_least_one(key, value):
    """A load factor: finite and >= 1 (1 = no increase)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{key} = {value!r}: expected a number >= 1 (a load factor)") from None
    if not math.isfinite(number) or number < 1.0:
        raise InvalidScene(f"{key} = {value!r}: expected a finite factor >= 1 (1 = no increase)")
    return number


def weight_contingency(factor=DEFAULT_WEIGHT_CONTINGENCY):
    """Weight contingency factor: Design Weight = weight x factor  [-].

    Source: 0027/ND Rev 11 6.2.1 (Design Weight = Net, Weighed or NTE weight x Weight
    Contingency Factor), which takes the factor from 0001/ND 8.3.1-8.3.3. The stored pages
    give the pointer but not 0001/ND's values, so the default 1.05 is this project's
    assumption (a commonly used minimum for a calculated, not weighed, weight); set
    ``[rules] weight_contingency`` to the value your estimate class asks for.
    """
    return factor_at_least_one("rules.weight_contingency", factor)


def cog_factor(searched, factor=None):
    """CoG factor on the static shares  [-]: 1 when the planner searched a CoG envelope.

    Source: 0027/ND Rev 11 6.2.3 (hooks) and 6.3.1 (lift points): "Where a CoG envelope is used
    [...] the loads should be calculated for a CoG position at the extremes of the CoG envelope.
    Where no CoG envelope is used, the loads are to be increased by the factor given in
    0001/ND 8.3.3 / 8.4.3." The planner searches the envelope (``[plan] cog_tolerance``), so a
    factor on top would count the CoG uncertainty twice. 0001/ND's value is not stored here,
    so with no envelope the factor must be given (``[rules] cog_factor``).

    Parameters
    ----------
    searched : bool
        Whether the static shares are already the worst over a CoG envelope.
    factor : float or None
        ``[rules] cog_factor``.
    """
    if searched:
        return 1.0
    if factor is None:
        raise InvalidScene(
            "rules.cog_factor: missing; no CoG envelope was searched (plan.cog_tolerance = 0), so "
            "0027/ND 6.2.3 asks for a CoG factor (0001/ND 8.3.3): expected [rules] cog_factor >= 1 "
            "or a [plan] cog_tolerance"
        )
    return factor_at_least_one("rules.cog_factor", factor)


def dynamic_amplification(gross_weight, location, static_hook_load=None):
    """Dynamic amplification factor (DAF) for a lift in air  [-].

    Source: 0027/ND Rev 11 5.5.1, Table 5-1 "Dynamic Amplification Factors (DAF) in Air":

    ==================  ========  =========================  ======================
    gross weight W [t]  onshore   inshore                    offshore
    ==================  ========  =========================  ======================
    3 < W <= 100        1.10      1.07 + 0.05 sqrt(100/SHL)  1 + 0.25 sqrt(100/SHL)
    100 < W <= 300      1.05      1.12                       1.25
    300 < W <= 1000     1.05      1.10                       1.20
    1000 < W <= 2500    1.03      1.08                       1.15
    W > 2500            1.03      1.05                       1.10
    ==================  ========  =========================  ======================

    Note 1: items under 3 t are taken as 3 t. Note 5: SHL is the static hook load (6.2.2,
    6.2.3). 5.5.2: the table also applies to 2 cranes on one vessel, onshore lifts by 2 or
    more cranes, and inshore lifts by 2 or more vessels in totally sheltered waters.

    Parameters
    ----------
    gross_weight : float  [t]
    location : {"onshore", "inshore", "offshore"}
    static_hook_load : float or None  [t]
        Needed only for 3 < W <= 100 t inshore / offshore.
    """
    if location not in LOCATIONS:
        raise InvalidScene(f"rules.location = {location!r}: expected one of {', '.join(LOCATIONS)}")
    weight = float(gross_weight)
    if not math.isfinite(weight) or weight <= 0.0:
        raise InvalidScene(f"gross weight = {gross_weight!r}: expected a finite weight > 0 t")
    weight = max(weight, DAF_MIN_WEIGHT)
    column = LOCATIONS.index(location)
    if weight <= 100.0:
        if location == "onshore":
            return 1.10
        if static_hook_load is None or not float(static_hook_load) > 0.0:
            raise InvalidScene(
                f"static hook load = {static_hook_load!r}: expected a load > 0 t "
                f"(Table 5-1 {location} DAF for W <= 100 t depends on it)"
            )
        root = math.sqrt(100.0 / float(static_hook_load))
        return 1.07 + 0.05 * root if location == "inshore" else 1.0 + 0.25 * root
    for upper, *values in DAF_TABLE:
        if weight <= upper:
            return values[column]
    raise AssertionError("unreachable: the last row has no upper bound")


def rules_tilt(separate_vessels=False, synchronised_sheerleg=False):
    """The rules' tilt angle and hook elevation difference for a multi-hook lift.

    Source: 0027/ND Rev 11 5.4.2 (hooks on one vessel: the more onerous of a tilt of 3 deg or a
    hook elevation difference of +-1.0 m), 5.4.4 / 5.4.5 (cranes on separate vessels: 5 deg, or a
    hook elevation difference of +-1.0 m inshore, by analysis offshore), 5.4.6 (the same sheerleg
    vessel with closely synchronised hooks: the 5.4.2 factors reduced by 50 %).

    Returns
    -------
    tuple (tilt [deg], hook elevation difference [m])
    """
    if separate_vessels and synchronised_sheerleg:
        raise InvalidScene(
            "rules.synchronised_sheerleg = true: 0027/ND 5.4.6 halves the factors only for hooks on the "
            "same sheerleg vessel; expected separate_vessels = false with it"
        )
    if separate_vessels:
        return TILT_SEPARATE_VESSELS, HOOK_ELEVATION
    if synchronised_sheerleg:
        return TILT_ONE_VESSEL / 2.0, HOOK_ELEVATION / 2.0
    return TILT_ONE_VESSEL, HOOK_ELEVATION


def governing_tilt(tilt, hook_elevation, hook_spacing):
    """The worse of a tilt and a hook elevation difference, as one tilt angle  [deg].

    Source: 0027/ND Rev 11 Appendix B.1.2: "the angle used is the highest of 3 deg or
    sin^-1(1.0/L) where L is the distance between the cranes".

    Parameters
    ----------
    tilt : float  [deg]
    hook_elevation : float  [m]
    hook_spacing : float  [m]
        Plan distance between the hooks (for more than two hooks: the least distance between
        two of them, the most onerous pair).
    """
    spacing = float(hook_spacing)
    if not math.isfinite(spacing) or spacing <= 0.0:
        raise InvalidScene(f"hook spacing = {hook_spacing!r}: expected a distance > 0 m")
    ratio = float(hook_elevation) / spacing
    if ratio >= 1.0:
        raise InvalidScene(
            f"rules.hook_elevation = {hook_elevation!r}: expected less than the hook spacing {spacing:.3g} m"
        )
    return max(float(tilt), math.degrees(math.asin(ratio)))


def yaw_factor(slings_on_hook, hooks, factor=DEFAULT_YAW_FACTOR):
    """Yaw effect factor on lift point and sling loads  [-].

    Source: 0027/ND Rev 11 5.4.7: "a yaw effect factor of 1.05 is normally sufficient [...] the
    yaw effect for a 2-hook lift only applies when there is more than one sling connected to the
    hook"; 6.3.1 applies it to lift point loads of twin-hook lifts. It redistributes load among the
    slings of one hook, so it is not a factor on the hook load.

    Parameters
    ----------
    slings_on_hook : int
    hooks : int
    factor : float
        ``[rules] yaw_factor``.
    """
    factor = factor_at_least_one("rules.yaw_factor", factor)
    return factor if hooks >= 2 and slings_on_hook > 1 else 1.0


def skew_factor(indeterminate, computed=None, override=None):
    """Skew load factor (SKL) used, and the rules' default shown beside it  [-].

    Source: 0027/ND Rev 11 5.6.12 (indeterminate 4-sling lifts with matched pairs of slings,
    length tolerance +-2.0 d, pairs within 1.0 d: SKL = 1.25 on each diagonal pair in turn) and
    5.6.13 (otherwise the skew load is computed with E = 80 000 N/mm2 on A = 0.785 d2 and the
    most onerous sling lengths). A determinate arrangement has no skew (factor 1).

    Parameters
    ----------
    indeterminate : bool
        Whether the loads are statically indeterminate (four or more hooks, or four or more
        slings on one hook).
    computed : float or None
        The planner's computed factor (elastic model, hook and sling tolerances).
    override : float or None
        ``[rules] skew_factor``: used instead of both.

    Returns
    -------
    tuple (factor used, how it was found: "rules", "computed", "default" or "determinate")
    """
    if override is not None:
        return factor_at_least_one("rules.skew_factor", override), "rules"
    if not indeterminate:
        return 1.0, "determinate"
    if computed is not None:
        return factor_at_least_one("computed skew factor", computed), "computed"
    return DEFAULT_SKEW_FACTOR, "default"


def sling_stiffness(diameter):
    """Axial stiffness EA of a sling for a computed skew load  [t].

    Source: 0027/ND Rev 11 5.6.13: E = 80 000 N/mm2 on an area 0.785 d2 (d in mm).

    Parameters
    ----------
    diameter : float  [m]
    """
    d = float(diameter)
    if not math.isfinite(d) or d <= 0.0:
        raise InvalidScene(f"sling diameter = {diameter!r}: expected a diameter > 0 m")
    area = SLING_AREA_FACTOR * (d * 1000.0) ** 2  # mm2
    return SLING_MODULUS * area / (1000.0 * _G)  # N -> t


def code_margin(cranes, override=None):
    """Crane-code capacity margin over each crane's calculated share  [-].

    20 / 33 / 50 % for 2 / 3 / 4 or more cranes lifting together. Source: AS 2550.1 asks 20 %
    per crane for two non-synchronised cranes (as quoted by a stored public lift calculator);
    33 % and 50 % are the common practice the project was given (PHYSICS.md section 3); no
    stored clause was found for them. One crane: no margin.

    Parameters
    ----------
    cranes : int
    override : float or None
        ``[rules] code_margin`` (fraction, e.g. 0.25).
    """
    if override is not None:
        value = float(override)
        if not math.isfinite(value) or not 0.0 <= value < 10.0:
            raise InvalidScene(f"rules.code_margin = {override!r}: expected a fraction >= 0 (0.2 = 20 %)")
        return value
    if cranes < 2:
        return 0.0
    return CODE_MARGIN.get(cranes, CODE_MARGIN_MANY)

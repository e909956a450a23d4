"""The design-load chain: from the planner's static shares to design hook and lug loads.

Per crane (0027/ND Rev 11 6.2, 10.3)::

    static share   S = max(worst tension, share at the rules' tilt)             [t]
                   (worst tension: the crane's largest over the heel/trim tolerance box
                   and the CG envelope, as the planner found it)
    static hook    SHL = S x weight contingency x CoG factor x skew (hook) + rigging weight
    dynamic hook   DHL = SHL x DAF            -> checked against the chart SWL at the radius

Per lug (6.3, 11.4)::

    vertical       V = lug share x tilt x weight contingency x CoG factor x DAF x yaw x skew (lug)
    leg load       V / sin(sling angle)
    design load    leg load x consequence factor (1.30), with its in-plane and out-of-plane parts
                   (the leg's own angle out of the lug's plane, plus the lateral allowance)

The CoG factor is 1 when the planner searched a CoG envelope (the worst tension already holds
the envelope's extremes); the tilt factor only raises the share to the rules' tilt when the
planner's own tolerance box did not already reach it (the larger of the two is used, never
their product); skew applies to hook loads only when the hooks share the load indeterminately
(four or more), to lug loads also when one hook carries four or more slings; yaw only to lug
loads of a hook with more than one sling. Each factor is reported with its value, source and
what it applies to, so a reader can redo the sums. A caller whose static input is not that
worst tension (the planner's breakout tension) names it in the notes through
:meth:`DesignLoadChain.factor_notes`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from functools import cached_property

from liftplan.model.checks import Check
from liftplan.model.errors import InvalidScene
from liftplan.model.rules.settings import Rules
from liftplan.model.scene.objects import finite, positive


@dataclass(frozen=True)
class LugLoads:
    """The planner's static load at one lug.

    Parameters
    ----------
    name : str
    share : float  [t]
        Vertical static load, the worst the planner found (tolerance box, CoG envelope).
    tilt_share : float or None  [t]
        Vertical static load at the rules' tilt; None: the hook's tilt increase is shared by
        its lugs in proportion (as 0027/ND Appendix B.1.5 does).
    sling_angle : float  [deg]
        Leg angle from the horizontal (90: a vertical rope).
    out_of_plane : float  [deg]
        Angle between the leg and the lug's plane.
    capacity : float or None  [t]
        The lug's allowed design load, for its check.
    """

    name: str
    share: float
    tilt_share: float | None = None
    sling_angle: float = 90.0
    out_of_plane: float = 0.0
    capacity: float | None = None

    def __post_init__(self):
        where = f"lugs[{self.name}]"
        object.__setattr__(self, "share", _load(f"{where}.share", self.share))
        if self.tilt_share is not None:
            object.__setattr__(self, "tilt_share", _load(f"{where}.tilt_share", self.tilt_share))
        angle = finite(f"{where}.sling_angle", self.sling_angle)
        if not 0.0 < angle <= 90.0:
            raise InvalidScene(
                f"{where}.sling_angle = {self.sling_angle!r}: expected an angle in "
                "(0, 90] deg from the horizontal"
            )
        object.__setattr__(self, "sling_angle", angle)
        out = finite(f"{where}.out_of_plane", self.out_of_plane)
        if not 0.0 <= out < 90.0:
            raise InvalidScene(
                f"{where}.out_of_plane = {self.out_of_plane!r}: expected an angle in [0, 90) deg"
            )
        object.__setattr__(self, "out_of_plane", out)
        if self.capacity is not None:
            object.__setattr__(self, "capacity", positive(f"{where}.capacity", self.capacity))


@dataclass(frozen=True)
class CraneLoads:
    """The planner's static loads for one crane.

    Parameters
    ----------
    name : str
    nominal : float  [t]
        Share at the level attitude, nominal weight and CG.
    worst : float  [t]
        The crane's worst tension: its largest share over the heel/trim tolerance box and the
        CG envelope, as the planner found it.
    tilt : float or None  [t]
        Share at the rules' tilt (worst direction and CoG vertex; see
        :meth:`~liftplan.model.rules.tilt.TiltGeometry.worst`). Needed with two or more cranes.
    swl : float  [t]
        Chart SWL at the crane's radius.
    radius : float or None  [m]
    skew : float or None  [-]
        Skew factor the planner computed with the elastic model (hook and sling tolerances).
    lugs : tuple of LugLoads
        The lugs on this crane's hook (may be empty: no lug checks).
    """

    name: str
    nominal: float
    worst: float
    tilt: float | None
    swl: float
    radius: float | None = None
    skew: float | None = None
    lugs: tuple = ()

    def __post_init__(self):
        where = f"cranes[{self.name}]"
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidScene(f"cranes.name = {self.name!r}: expected a non-empty string")
        for key in ("nominal", "worst"):
            object.__setattr__(self, key, _load(f"{where}.{key}", getattr(self, key)))
        if self.worst < self.nominal:
            raise InvalidScene(
                f"{where}.worst = {self.worst!r}: expected >= nominal {self.nominal:g} t "
                "(the worst over a box that holds the level attitude)"
            )
        if self.tilt is not None:
            object.__setattr__(self, "tilt", _load(f"{where}.tilt", self.tilt))
        object.__setattr__(self, "swl", positive(f"{where}.swl", self.swl))
        if self.radius is not None:
            object.__setattr__(self, "radius", finite(f"{where}.radius", self.radius))
        object.__setattr__(self, "lugs", tuple(self.lugs))
        for lug in self.lugs:
            if not isinstance(lug, LugLoads):
                raise InvalidScene(f"{where}.lugs = {lug!r}: expected LugLoads")


@dataclass(frozen=True)
class Factor:
    """One factor of the chain as applied to one crane.

    Parameters
    ----------
    name : str
    value : float  [-]
    source : str
        Clause it comes from.
    applies_to : {"hook and lug", "lug", "none"}
    note : str
        How the value was found (e.g. "computed 1.08; rules' default 1.25").
    """

    name: str
    value: float
    source: str
    applies_to: str
    note: str = ""


@dataclass(frozen=True)
class LugDesignLoad:
    """Design load of one lug  [t]: vertical, along the leg, and factored for the lug's check."""

    lug: str
    crane: str
    share: float
    vertical: float
    sling_angle: float
    leg_load: float
    design_load: float
    in_plane: float
    out_of_plane: float
    product: float
    check: Check | None

    def to_json(self):
        out = asdict(self)
        out["check"] = self.check.to_json() if self.check is not None else None
        return out


@dataclass(frozen=True)
class CraneDesignLoad:
    """Design hook load of one crane against its chart, with every factor shown."""

    crane: str
    radius: float | None
    swl: float
    nominal: float
    worst: float
    tilt_share: float | None
    factors: tuple
    product: float
    rigging_weight: float
    static_hook_load: float
    dynamic_hook_load: float
    design_hook_load: float
    utilisation: float
    check: Check
    code_margin: Check | None
    lugs: tuple = field(default=())

    def to_json(self):
        return {
            "crane": self.crane,
            "radius": self.radius,
            "swl": self.swl,
            "nominal": self.nominal,
            "worst": self.worst,
            "tilt_share": self.tilt_share,
            "factors": [asdict(f) for f in self.factors],
            "product": self.product,
            "rigging_weight": self.rigging_weight,
            "static_hook_load": self.static_hook_load,
            "dynamic_hook_load": self.dynamic_hook_load,
            "design_hook_load": self.design_hook_load,
            "utilisation": self.utilisation,
            "check": self.check.to_json(),
            "code_margin": self.code_margin.to_json() if self.code_margin is not None else None,
            "lugs": [lug.to_json() for lug in self.lugs],
        }


@dataclass(frozen=True)
class DesignLoadChain:
    """The rules' design loads of a multi-crane lift.

    Parameters
    ----------
    cranes : tuple of CraneLoads
    weight : float  [t]
        The lifted item's weight before contingency (net, weighed or NTE weight).
    rules : Rules
    cog_searched : bool
        The worst tensions already hold a CG envelope's extremes (then no CoG factor).
    tilt_note : str
        How the tilt shares were found (shown with the tilt factor), e.g. "3 deg governs
        (hook elevation 1 m over 25 m = 2.29 deg)".
    """

    cranes: tuple
    weight: float
    rules: Rules = field(default_factory=Rules)
    cog_searched: bool = True
    tilt_note: str = ""

    def __post_init__(self):
        object.__setattr__(self, "cranes", tuple(self.cranes))
        if not self.cranes:
            raise InvalidScene("cranes = (): expected one or more cranes")
        names = [c.name for c in self.cranes]
        if len(set(names)) != len(names):
            raise InvalidScene(f"cranes = {names!r}: expected unique crane names")
        lugs = [lug.name for c in self.cranes for lug in c.lugs]
        if len(set(lugs)) != len(lugs):
            raise InvalidScene(f"lugs = {lugs!r}: expected each lug on one crane only")
        object.__setattr__(self, "weight", positive("body.weight", self.weight))
        if not isinstance(self.rules, Rules):
            raise InvalidScene(f"rules = {self.rules!r}: expected a Rules")
        if isinstance(self.rules.rigging_weight, dict):
            unknown = sorted(set(self.rules.rigging_weight) - set(names))
            if unknown:
                raise InvalidScene(
                    f"rules.rigging_weight.{unknown[0]}: no such crane, expected one of {', '.join(names)}"
                )
        if len(self.cranes) >= 2:
            for crane in self.cranes:
                if crane.tilt is None:
                    raise InvalidScene(
                        f"cranes[{crane.name}].tilt: missing; a multi-hook lift needs each crane's share at "
                        "the rules' tilt (0027/ND 5.4): expected a load in t (TiltGeometry.worst)"
                    )
        # refuses a missing factor now
        self.rules.factors.cog_factor(self.cog_searched, self.rules.cog_factor)

    @property
    def design_weight(self):
        """Weight x weight contingency  [t] (0027/ND 6.2.1); the DAF table's gross weight."""
        return self.weight * self.rules.weight_contingency

    @cached_property
    def results(self):
        """Per crane, in the order given: :class:`CraneDesignLoad`."""
        return tuple(self._crane(c) for c in self.cranes)

    def result(self, crane):
        """The :class:`CraneDesignLoad` of the crane named ``crane``."""
        for r in self.results:
            if r.crane == crane:
                return r
        raise InvalidScene(
            f"crane = {crane!r}: no such crane, expected one of {', '.join(c.name for c in self.cranes)}"
        )

    @property
    def checks(self):
        """Every check: design hook loads, code margins, lug design loads."""
        out = []
        for r in self.results:
            out.append(r.check)
            if r.code_margin is not None:
                out.append(r.code_margin)
            out.extend(lug.check for lug in r.lugs if lug.check is not None)
        return out

    def to_json(self):
        return {
            "weight": self.weight,
            "design_weight": self.design_weight,
            "rules": _rules_json(self.rules),
            "cog_searched": self.cog_searched,
            "cranes": [r.to_json() for r in self.results],
        }

    def factor_notes(self, crane):
        """The notes of the ``cog`` and ``tilt`` factors of one crane, in words.

        The public hook for a caller whose static input is not the crane's worst tension over
        the tolerance box and the CG envelope (the planner's breakout tension,
        :class:`liftplan.planner.plans.design_loads.PlanChain`): override it to name that input,
        calling this one for the notes it keeps. The factors' values never depend on the notes.

        Parameters
        ----------
        crane : CraneLoads

        Returns
        -------
        dict of str to str
            ``{"cog": ..., "tilt": ...}``.
        """
        worst = crane.worst
        if self.cog_searched and crane.nominal > 0:
            cog = (
                f"CoG envelope searched by the planner: in the worst tension (worst / nominal = "
                f"{worst / crane.nominal:.4f})"
            )
        elif self.cog_searched:
            cog = "CoG envelope searched by the planner"
        else:
            cog = "no CoG envelope searched: [rules] cog_factor"
        if crane.tilt is None:
            tilt = "single hook: no multi-hook tilt"
        else:
            over = (
                "the heel/trim tolerance box and the CG envelope"
                if self.cog_searched
                else "the heel/trim tolerance box (no CG envelope)"
            )
            tilt = (
                f"share at the rules' tilt {crane.tilt:.4g} t against {worst:.4g} t, the crane's "
                f"worst tension over {over}"
            )
        if self.tilt_note:
            tilt += f"; {self.tilt_note}"
        return {"cog": cog, "tilt": tilt}

    # -- one crane ------------------------------------------------------------------------------
    def _crane(self, crane):
        rules, hooks = self.rules, len(self.cranes)
        code = rules.factors  # the rules code's factors ([rules] code)
        wc = rules.weight_contingency
        cog = code.cog_factor(self.cog_searched, rules.cog_factor)
        base = crane.worst
        static = max(base, crane.tilt) if crane.tilt is not None else base
        tilt = static / base if base > 0.0 else 1.0
        many_slings = len(crane.lugs) >= 4
        skew, how = code.skew_factor(hooks >= 4 or many_slings, crane.skew, rules.skew_factor)
        skew_on_hook = hooks >= 4  # skew between hooks; within one hook's slings it is lug-only
        yaw = code.yaw_factor(len(crane.lugs), hooks, rules.yaw_factor)
        rigging = rules.rigging_for(crane.name)
        share_design = static * wc * cog
        if rules.daf is not None:
            daf, daf_note = rules.daf, "[rules] daf"
        else:
            shl_for_table = share_design * (skew if skew_on_hook else 1.0) + rigging
            daf = code.dynamic_amplification(self.design_weight, rules.location, shl_for_table)
            daf_note = f"Table 5-1, {rules.location}, gross weight {self.design_weight:.1f} t"

        hook_skew = skew if skew_on_hook else 1.0
        static_hook = share_design * hook_skew + rigging
        dynamic_hook = static_hook * daf
        design_hook = static_hook if rules.chart_includes_dynamics else dynamic_hook
        where = f" at {crane.radius:.3g} m" if crane.radius is not None else ""
        kind = "static (chart includes dynamics, 10.3.2)" if rules.chart_includes_dynamics else "dynamic"
        check = Check.upper(
            "design_hook_load",
            crane.name,
            design_hook,
            crane.swl,
            "t",
            note=f"{kind} hook load / chart SWL{where}",
        )
        margin = code.code_margin(hooks, rules.code_margin)
        margin_check = None
        if margin > 0.0:
            share = crane.nominal * wc + rigging
            margin_check = Check.upper(
                "code_margin",
                crane.name,
                share * (1.0 + margin),
                crane.swl,
                "t",
                note=f"calculated share {share:.4g} t x {1.0 + margin:.2f} ({hooks} cranes)",
            )

        skew_note = f"{how}; rules' default {code.DEFAULT_SKEW_FACTOR:g}"
        if crane.skew is not None and how != "computed":
            skew_note += f", computed {crane.skew:.4g}"
        own = self.factor_notes(crane)
        cog_note, tilt_note = own["cog"], own["tilt"]
        table = (
            Factor("weight_contingency", wc, code.SOURCES["weight_contingency"], "hook and lug"),
            Factor(
                "cog",
                cog,
                code.SOURCES["cog_envelope" if self.cog_searched else "cog_factor"],
                "hook and lug",
                cog_note,
            ),
            Factor(
                "tilt",
                tilt,
                code.SOURCES["tilt"],
                "hook and lug" if crane.tilt is not None else "none",
                tilt_note,
            ),
            Factor(
                "skew",
                skew,
                code.SOURCES["skew"],
                "hook and lug" if skew_on_hook else "lug" if skew > 1.0 else "none",
                skew_note,
            ),
            Factor(
                "yaw",
                yaw,
                code.SOURCES["yaw"],
                "lug" if yaw > 1.0 else "none",
                "more than one sling on the hook" if yaw > 1.0 else "one sling on the hook, or one hook",
            ),
            Factor("daf", daf, code.SOURCES["daf"], "hook and lug", daf_note),
        )
        product = tilt * wc * cog * hook_skew * daf
        lugs = tuple(self._lug(crane, lug, tilt, cog, daf, yaw, skew) for lug in crane.lugs)
        return CraneDesignLoad(
            crane=crane.name,
            radius=crane.radius,
            swl=crane.swl,
            nominal=crane.nominal,
            worst=crane.worst,
            tilt_share=crane.tilt,
            factors=table,
            product=product,
            rigging_weight=rigging,
            static_hook_load=static_hook,
            dynamic_hook_load=dynamic_hook,
            design_hook_load=design_hook,
            utilisation=design_hook / crane.swl,
            check=check,
            code_margin=margin_check,
            lugs=lugs,
        )

    def _lug(self, crane, lug, tilt, cog, daf, yaw, skew):
        rules = self.rules
        if lug.tilt_share is not None:
            static = max(lug.share, lug.tilt_share)
        else:
            static = lug.share * tilt
        product = rules.weight_contingency * cog * daf * yaw * skew
        vertical = static * product
        leg = vertical / math.sin(math.radians(lug.sling_angle))
        design = leg * rules.consequence_factor
        off = math.radians(lug.out_of_plane)
        in_plane = design * math.cos(off)
        out_of_plane = design * math.sin(off) + rules.lateral_fraction * design
        check = None
        if lug.capacity is not None:
            check = Check.upper(
                "lug_design_load",
                lug.name,
                design,
                lug.capacity,
                "t",
                note=f"leg load x consequence {rules.consequence_factor:g} (crane {crane.name})",
            )
        return LugDesignLoad(
            lug=lug.name,
            crane=crane.name,
            share=lug.share,
            vertical=vertical,
            sling_angle=lug.sling_angle,
            leg_load=leg,
            design_load=design,
            in_plane=in_plane,
            out_of_plane=out_of_plane,
            product=product * (static / lug.share if lug.share > 0 else 1.0),
            check=check,
        )


def _load(key, value):
    number = finite(key, value)
    if number < 0.0:
        raise InvalidScene(f"{key} = {value!r}: expected a load >= 0 t")
    return number


def _rules_json(rules):
    return asdict(rules)

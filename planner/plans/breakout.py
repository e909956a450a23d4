"""The breakout case of a plan: each crane's load when a bedded hull breaks out of the seabed.

A planning file's ``[plan] breakout_scene`` names a scene file of the hull resting on the
seabed (``[hull]``, ``[water]``, ``[ground]`` with its breakout model). Its
:func:`~liftplan.model.water.breakout.breakout_load` is computed once: the peak total hook
load ``total`` (submerged weight + breakout force, t) and a body-frame point on its line of
action. For a lug set, each crane's share of that load follows from the held-preload model
the planner uses everywhere (:class:`~liftplan.planner.search.scenarios.LugSet`): the boom
heights that dial in the plan's level preload T*, then hook motions that are a rigid motion of
the level hook pattern (c0 + c1 x + c2 y, the twist held), fixed by the statics at the level
attitude with the weight ``total`` acting at the breakout point. Three statics rows and the
held compatibility make it exact and linear; it equals the ``elastic`` solve of the plan's
scene with that weight and CG and the hooks moved by :attr:`BreakoutCase.hook_shift`.

The crew's hook errors act at breakout as anywhere: each rope's tension there is taken at its
worst over every hook within its tolerance (``T + |dT/dH| delta``, the same closed form as in
the box, with dT/dH at the breakout state), so the hook tolerance and the skew factor 1 of the
chain hold for the breakout case too.

With floating cranes the held model takes each rope in series with its vessel at the lug its
crane takes (the lug set's stiffness, :func:`~liftplan.planner.search.scenarios.set_lugset`):
the crew's hook motions stay a rigid motion of the level hook pattern, each tension changes by
the series stiffness 1 / (l0 / EA + c) times its hook's motion, c the vessel's tip compliance.
Each vessel's heel, trim and freeboard at breakout, the largest hook loads of the lift, are
checked against its limits (``breakout_vessel_heel``, ``breakout_vessel_trim``,
``breakout_vessel_freeboard``): with the levelling ballast set for the level tension T0, heel
(T - T0) y_t / (disp GM_T) at the rope's least and largest breakout tension over the hook
errors (:func:`~liftplan.planner.problem.vessels.vessel_worst`).

Each crane's static input to the rules' chain becomes the larger of its worst in the box and
its breakout tension (:mod:`liftplan.planner.plans.design_loads`), and a check per crane compares
the breakout hook load (tension + the rules' rigging weight, no dynamic factor) with the chart
SWL at its radius.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from liftplan.model.checks import Check
from liftplan.planner.problem.vessels import limit_checks, tip_offsets, vessel_worst
from liftplan.planner.search.scenarios import held_model, pack, run_block


@dataclass(frozen=True)
class BreakoutCase:
    """Each crane's load at breakout for one lug set.

    Parameters
    ----------
    load : BreakoutLoad
        The scene's breakout case (z-up body frame).
    cranes : tuple of str
        Crane names, in the lug set's order.
    lugs : tuple of str
        Candidate names, in the lug set's order.
    tensions : numpy.ndarray, shape (n,)  [t]
        Held tension of each rope at breakout (level attitude, preload held, hooks at their
        planned heights); below 0 a rope would go slack and the held model no longer holds.
    gain : numpy.ndarray, shape (n, n)  [t/m]
        dT_i / dH_j at breakout (row = rope), the pose held.
    hook_tolerance : numpy.ndarray, shape (n,)  [m]
        Each hook's height tolerance.
    hook_shift : numpy.ndarray, shape (n,)  [m]
        Each hook's motion from its planned height that holds the body level under the
        breakout load (a rigid motion of the level hook pattern).
    swl : numpy.ndarray, shape (n,)  [t]
        Chart SWL at each crane's radius.
    rigging : numpy.ndarray, shape (n,)  [t]
        The rules' rigging weight on each hook (with a spreader bar's weight on its hook).
    extremes : tuple of 2 numpy.ndarray, shape (n,), or None  [t]
        (least, worst) of each tension over the hook errors where the tensions are not affine
        in the hook heights (two cranes on slings: the lever rule at the tilts along the hook
        line the errors give, :func:`~liftplan.planner.plans.slings.two_crane.hooks_breakout`;
        ``gain`` is then its slope at level). None: ``T -+ |dT/dH| delta``, exact for the
        held model.
    vessels : tuple of BreakoutVessel
        Each floating crane's vessel at breakout (empty: every crane on land).
    min_tension : float  [t]
        The plan's ``min_tension`` (0 where it is lower): the lowest tension at breakout must
        reach it, as every state of the lift must.
    """

    load: object
    cranes: tuple[str, ...]
    lugs: tuple[str, ...]
    tensions: np.ndarray
    gain: np.ndarray
    hook_tolerance: np.ndarray
    hook_shift: np.ndarray
    swl: np.ndarray
    rigging: np.ndarray
    extremes: tuple | None = None
    vessels: tuple = ()
    min_tension: float = 0.0

    @property
    def hook_widening(self):
        """What the worst hook errors add to each tension at breakout  [t]."""
        if self.extremes is not None:
            return self.extremes[1] - self.tensions
        return np.abs(self.gain) @ self.hook_tolerance

    @property
    def worst(self):
        """Each tension at breakout at its largest over the hook errors  [t]."""
        return self.tensions + self.hook_widening

    @property
    def least(self):
        """Each tension at breakout at its smallest over the hook errors  [t]."""
        if self.extremes is not None:
            return self.extremes[0]
        return self.tensions - self.hook_widening

    def ordered(self, order):
        """The same case with its ropes in ``order`` (indices into this case's order): a sling
        plan's fleet order from its lug set's."""
        order = list(order)
        extremes = None if self.extremes is None else tuple(v[order] for v in self.extremes)
        return dataclasses.replace(
            self,
            cranes=tuple(self.cranes[k] for k in order),
            lugs=tuple(self.lugs[k] for k in order),
            tensions=self.tensions[order],
            gain=self.gain[np.ix_(order, order)],
            hook_tolerance=self.hook_tolerance[order],
            hook_shift=self.hook_shift[order],
            swl=self.swl[order],
            rigging=self.rigging[order],
            extremes=extremes,
        )

    @property
    def hook_loads(self):
        """Worst breakout tension (hook errors included) + rigging weight per hook  [t]."""
        return self.worst + self.rigging

    @property
    def checks(self):
        """Per crane the breakout hook load against the chart SWL; the lowest tension >= 0."""
        out = [
            Check.upper(
                "breakout_hook_load",
                crane,
                hook,
                swl,
                "t",
                note=f"held tension at breakout {t:.4g} t (hook errors at worst) + rigging "
                f"{r:.4g} t / chart SWL (static peak, no DAF)",
            )
            for crane, hook, swl, t, r in zip(
                self.cranes, self.hook_loads, self.swl, self.worst, self.rigging
            )
        ]
        out.append(
            Check.lower(
                "breakout_min_tension",
                "all ropes",
                float(self.least.min()),
                self.min_tension,
                "t",
                note="lowest held tension at breakout, hook errors at worst, against the plan's "
                "min_tension; below 0 a rope goes slack and the held model no longer holds",
            )
        )
        for v in self.vessels:
            out += limit_checks("breakout_", v.crane, v.worst, v.limits, "at breakout, hook errors at worst")
        return out

    @property
    def ok(self):
        return all(c.ok for c in self.checks)


@dataclass(frozen=True)
class BreakoutVessel:
    """A floating crane's vessel at breakout.

    Parameters
    ----------
    crane : str
    offset, load, extremes
        As :func:`~liftplan.planner.problem.vessels.vessel_worst` takes them: the tip's offset
        (x_t, y_t) [m], the level tension T0 [t] the ballast levels, and the rope's least and
        largest tension at breakout over the hook errors [t].
    worst : VesselWorst
        The largest |heel|, |trim| [deg] and the least freeboard [m] there.
    limits : tuple
        (max_heel, max_trim, min_freeboard) of the vessel, each None when not given.
    """

    crane: str
    offset: tuple[float, float]
    load: float
    extremes: tuple[float, float]
    worst: object
    limits: tuple

    def to_json(self):
        return {
            "heel": self.worst.heel,
            "trim": self.worst.trim,
            "freeboard": self.worst.freeboard,
            "tensions": list(self.extremes),
        }


def breakout_vessels(problem, lugset, preload, least, worst):
    """:class:`BreakoutVessel` of each floating crane of a lug set (in its order)."""
    out = []
    for k, (i, j) in enumerate(zip(lugset.indices, lugset.cranes)):
        vessel = problem.fleet[j].vessel
        if vessel is None:
            continue
        offset = tuple(float(v) for v in tip_offsets(vessel, problem.plan_points[i]))
        extremes = (float(least[k]), float(worst[k]))
        out.append(
            BreakoutVessel(
                crane=problem.fleet[j].name,
                offset=offset,
                load=float(preload[k]),
                extremes=extremes,
                worst=vessel_worst(vessel, offset, float(preload[k]), extremes),
                limits=(vessel.max_heel, vessel.max_trim, vessel.min_freeboard),
            )
        )
    return tuple(out)


def breakout_case(problem, lugset, preload):
    """Each crane's held tension at breakout for one lug set (single ropes, or the hooks of
    three or more cranes on slings: the lug set is then of the slings' hooks, hinged where
    the problem carries hinges, and each tension is the body's share on that hook).

    Parameters
    ----------
    problem : PlanProblem
        With ``breakout_scene`` (``problem.breakout`` is its :class:`BreakoutLoad`).
    lugset : LugSet
        Each floating crane in series with its vessel at its lug
        (:func:`~liftplan.planner.search.scenarios.set_lugset`).
    preload : array_like, shape (n,)  [t]
        The level preload T* the boom heights dial in.

    Returns
    -------
    BreakoutCase
    """
    load = problem.breakout
    boom = lugset.boom_heights(np.asarray(preload, dtype=float))
    params = pack(
        problem,
        lugset.points,
        np.asarray(load.point, dtype=float),
        boom,
        weight=load.total,
        rope_length=lugset.rope_length,
        EA=lugset.EA,
        hinges=lugset.hinges,
    )
    level = np.array([[problem.lift_height, 0.0, 0.0]])
    model = held_model(problem, lugset.n)  # hooks hinged about their lug pairs where slings are
    tensions, shift, gain = run_block(model.held_block, lugset.n, level, params)
    rigging = np.array([problem.rules.rigging_for(name) for name in lugset.crane_names], dtype=float)
    widening = np.abs(gain[0]) @ np.asarray(lugset.hook_tolerance, dtype=float)
    vessels = breakout_vessels(problem, lugset, preload, tensions[0] - widening, tensions[0] + widening)
    return BreakoutCase(
        load=load,
        cranes=lugset.crane_names,
        lugs=lugset.names,
        tensions=tensions[0],
        gain=gain[0],
        hook_tolerance=np.asarray(lugset.hook_tolerance, dtype=float),
        hook_shift=shift[0],
        swl=np.asarray(lugset.swl, dtype=float),
        rigging=rigging,
        vessels=vessels,
        min_tension=max(float(problem.min_tension), 0.0),
    )


def _case_json(plan, case, names):
    """The breakout scene's case (its point in the file's frame) and each tension, without and
    with the hook errors at worst, keyed by ``names``."""
    out = case.load.to_json()
    out["point"] = list(plan.in_file_frame(case.load.point))
    out["frame"] = plan.frame
    out["scene"] = plan.problem.breakout_scene.name
    out["tensions"] = dict(zip(names, case.tensions.tolist()))
    out["tensions_with_hook_errors"] = dict(zip(names, case.worst.tolist()))
    return out


def breakout_json(plan):
    """``{"breakout": {...}}`` for the plan JSON, or ``{}`` without a breakout case.

    The scene's :meth:`~liftplan.model.water.breakout.BreakoutLoad.to_json` with ``point`` in
    the planning file's frame, then per crane of the chosen set its breakout tension, hook
    load, chart SWL, box worst and which of the two is the chain's static input, the breakout
    checks, and each ranked set's tensions.
    """
    design = plan.design_loads
    case = design.breakout
    if case is None:
        return {}
    out = _case_json(plan, case, plan.labels)
    out["cranes"] = [
        {
            "lug": c.label,
            "candidate": c.lug,
            "crane": c.crane,
            "tension": float(t),
            "hook_errors": float(w),
            "tension_with_hook_errors": c.breakout,
            "rigging": float(r),
            "hook_load": float(h),
            "swl": c.swl,
            "hook_shift": float(d),
            "box_worst": max(c.worst, c.nominal),
            "static_input": c.static_input,
            "governs": c.governs,
            "note": c.static_note,
        }
        for c, t, w, r, h, d in zip(
            design.cranes, case.tensions, case.hook_widening, case.rigging, case.hook_loads, case.hook_shift
        )
    ]
    if case.vessels:
        out["vessels"] = {v.crane: v.to_json() for v in case.vessels}
    out["checks"] = [c.to_json() for c in case.checks]
    out["ok"] = case.ok
    out["ranking"] = [
        {
            "lugs": list(d.breakout.lugs),
            "cranes": list(d.breakout.cranes),
            "tensions": d.breakout.tensions.tolist(),
            "tensions_with_hook_errors": d.breakout.worst.tolist(),
            "ok": d.breakout.ok,
        }
        for d in plan.ranked_design
    ]
    return {"breakout": out}


def hooks_breakout_json(plan):
    """``{"breakout": {...}}`` for a sling plan's JSON, or ``{}`` without a breakout case.

    As :func:`breakout_json`, per crane (fleet order): its lugs, the body's share on its hook
    at breakout and with the hook errors at worst and least, the rigging (a spreader bar's
    weight in it), the hook load against the chart SWL, the share's box worst, which of the two
    is the chain's static input, and each of its legs' tension at breakout (the worst hook
    load split by the sling's statics, the lug design loads' input where it governs).
    """
    case = plan.breakout
    if case is None:
        return {}
    out = _case_json(plan, case, case.cranes)
    labels = iter(plan.labels)
    cranes = []
    for c, name in enumerate(case.cranes):
        box = float(plan.box_shares[c])
        worst = float(case.worst[c])
        mine = [next(labels) for _ in plan.groups[c]]
        cranes.append(
            {
                "crane": name,
                "lugs": {label: plan.lugs[label] for label in mine},
                "tension": float(case.tensions[c]),
                "hook_errors": float(case.hook_widening[c]),
                "tension_with_hook_errors": worst,
                "least_with_hook_errors": float(case.least[c]),
                "rigging": float(case.rigging[c]),
                "hook_load": float(case.hook_loads[c]),
                "swl": float(case.swl[c]),
                "hook_shift": float(case.hook_shift[c]),
                "box_worst": box,
                "static_input": max(box, worst),
                "governs": "breakout" if worst > box else "box",
                "legs": dict(zip(mine, np.asarray(plan.breakout_legs[c], dtype=float).tolist())),
            }
        )
    out["cranes"] = cranes
    out["checks"] = [c.to_json() for c in case.checks]
    out["ok"] = case.ok
    out["ranking"] = [
        {
            "lugs": list(lugs),
            "cranes": list(ranked.cranes),
            "tensions": ranked.tensions.tolist(),
            "tensions_with_hook_errors": ranked.worst.tolist(),
            "ok": ranked.ok,
        }
        for lugs, ranked in plan.ranked_breakouts
    ]
    return {"breakout": out}

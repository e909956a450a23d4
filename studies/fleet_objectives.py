"""What each objective picks on the same unequal fleet: ``spread`` against ``utilisation``.

Conclusion, as measured (studies/out/fleet_objectives.json, which a re-run rewrites; W0 =
904 t, the tanker example's 1000 t-class sheerlegs and 600 t-class cranes and its [rules],
the hook-height tolerance in the worst case; "first at SWL" with every crane keeping its
planned share as the weight grows):

1. ``utilisation`` does keep the cranes at more even fractions of their SWL: worst
   utilisation spread 0.295 against 0.388 (tanker fleet) and 0.174 against 0.389 (diagonal
   fleet). ``spread`` evens the tensions instead (worst spread 91 t against 141 t, and 92 t
   against 239 t), and with unequal cranes that loads the small cranes to a higher fraction
   of their SWL: level T*/SWL 0.53 and 0.50 on the 600 t-class cranes against 0.31 and 0.28
   on the sheerlegs (tanker), 0.55 and 0.54 against 0.31 and 0.31 (diagonal).
2. Whether that carries more weight depends on the fleet, because ``utilisation`` minimises
   the *difference* of T/SWL between cranes, not the *largest* T/SWL:
   * diagonal fleet (big cranes on one diagonal): yes, by far. Highest design load / SWL
     0.55 against 0.77; in the box no crane reaches its SWL up to 2 W0 (1808 t) against
     crane D at 1439 t; the first design check fails at 1571 t against 1031 t (52 % more
     weight), the first design hook load reaches its SWL at 1795 t against 1239 t.
   * tanker fleet (the example, both sheerlegs on one side): no. To bring the sheerlegs up to
     0.42-0.47 of their SWL the utilisation plan takes a set that puts crane C at 0.55,
     where the spread plan leaves it at 0.53: highest design load / SWL 0.770 against 0.753,
     crane C at its SWL in the box at 1420 t against 1473 t, first design check failing at
     1027 t against 1077 t (crane C's code margin in both).
3. Re-planned at every weight, both objectives reach the same limit (1108 t tanker fleet,
   1605 t diagonal fleet, the same lugs and cranes there): whether a body can be held within
   every limit over the box does not depend on the objective, which only chooses among the
   feasible plans. The objective matters for the reserve a plan keeps when the weight turns
   out higher than planned, not for the heaviest body the fleet can lift. A plan that is to
   keep the largest reserve would minimise the largest T/SWL, which neither objective does.

Method. Each fleet is planned twice, ``[plan] objective = "spread"`` and ``"utilisation"``,
everything else equal. For each plan: the lugs, which crane takes which, the level tensions
T*, T* / SWL, the worst tension over the tolerance box and CG envelope / SWL (the search's
constraint), the rules' design hook load / SWL (``Plan.capacity``, docs/design-loads.md),
the worst tension spread and the worst utilisation spread. Then the weight grows:

* *shares held*: the plan as handed over (its lugs, cranes and level tensions T* W / W0,
  i.e. every crane keeps its planned share of the weight, as the rules' weight contingency
  scales the loads); at each weight the in-box worst and the design chain are recomputed
  (``design_loads``), on a grid of GRID_STEP x W0 and bisected to BISECT_T, to find the
  first crane whose in-box worst reaches its SWL and the first design check that fails;
* *re-planned*: the planner run again at each weight (steps of REPLAN_STEP x W0, then
  bisection) until no lug set and assignment is feasible.

Run:  python studies/fleet_objectives.py   (writes studies/out/fleet_objectives.json, then
      studies/out/fleet_objectives.png from that file; a few minutes on one core)
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.model.frames import choi_to_zup
from liftplan.planner.plan import plan
from liftplan.planner.plans.design_loads import design_loads
from liftplan.planner.problem.file import load_problem

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"
OUT = HERE / "out"
OBJECTIVES = ("spread", "utilisation")
#: Weight grid of the shares-held sweep and of the re-planning sweep, as fractions of the
#: nominal weight W0, the largest factor looked at, and the bisection tolerance.
GRID_STEP, REPLAN_STEP, MAX_FACTOR, BISECT_T = 0.02, 0.05, 2.0, 0.5  # [-], [-], [-], [t]


def fleets():
    """The fleets compared: name -> (PlanProblem, one line on where the cranes stand)."""
    tanker = load_problem(EXAMPLES / "tanker_fleet.toml")
    big_a, big_b, small_c, small_d = tanker.fleet

    def at(x, z):  # the example's positions are in the papers' frame (x, y up, z to starboard)
        return tuple(choi_to_zup((x, 0.0, z))[:2])

    diagonal = dataclasses.replace(
        tanker,
        name="1500 GT tanker, big cranes on a diagonal",
        fleet=(
            big_a,
            dataclasses.replace(big_b, position=at(60.0, 37.0)),
            dataclasses.replace(small_c, position=at(60.0, -25.0)),
            dataclasses.replace(small_d, position=at(20.0, 37.0)),
        ),
    )
    return {
        "tanker_fleet": (
            tanker,
            "examples/tanker_fleet.toml: both sheerlegs off the port side "
            "(x = 20, 60 m), both smaller cranes off starboard",
        ),
        "diagonal_fleet": (
            diagonal,
            "the same hull, candidates, charts and rules; sheerleg A port "
            "quarter, sheerleg B starboard bow, crane C port bow, crane D "
            "starboard quarter: the big cranes on one diagonal",
        ),
    }


def _with_weight(problem, weight):
    return dataclasses.replace(problem, body=dataclasses.replace(problem.body, weight=weight))


class SharesHeld:
    """A plan's loads when the body weighs more and every crane keeps its planned share."""

    def __init__(self, problem, result):
        self.problem, self.chosen, self.labels = problem, result.chosen, result.labels
        self._cache = {}

    def at(self, weight):
        """In-box worst / SWL and design hook load / SWL per crane, and the failed checks.

        Returns
        -------
        in_box, design : numpy.ndarray  [-]
        failed : list of str
            ``"check subject"`` of every design check that fails (the chain's checks).
        """
        key = round(float(weight), 9)
        if key not in self._cache:
            heavier = _with_weight(self.problem, weight)
            scaled = dataclasses.replace(
                self.chosen, preload=self.chosen.preload * weight / self.problem.body.weight
            )
            loads = design_loads(heavier, [scaled], self.labels)[0]
            in_box = np.array([c.worst / c.swl for c in loads.cranes])
            design = np.array([c.utilisation for c in loads.cranes])
            failed = [f"{c.name} {c.subject}" for c in loads.checks if not c.ok]
            self._cache[key] = (in_box, design, failed)
        return self._cache[key]


def _first(predicate, weights, low_tol=BISECT_T):
    """First weight of an increasing grid at which ``predicate`` (ok) turns False, bisected
    between grid points to ``low_tol``  [t]; None if it holds on the whole grid; the first
    grid weight if it fails there already."""
    previous = None
    for weight in weights:
        if not predicate(weight):
            if previous is None:
                return float(weight)
            low, high = previous, weight
            while high - low > low_tol:
                middle = 0.5 * (low + high)
                low, high = (middle, high) if predicate(middle) else (low, middle)
            return float(0.5 * (low + high))
        previous = weight
    return None


def plan_entry(problem, objective):
    """Plan with one objective: what it picks and its loads at the planned weight."""
    result = plan(dataclasses.replace(problem, objective=objective))
    chosen = result.chosen
    capacity = result.capacity
    design = {c.label: c.utilisation for c in capacity}
    worst = {c.label: c.worst / c.swl for c in capacity}
    highest = max(design, key=design.get)
    return result, {
        "lugs": result.lugs,
        "cranes": result.cranes,
        "radius": result.radius,
        "swl": result.swl,
        "tensions": result.tensions,
        "utilisation": result.utilisation,
        "worst_over_swl": worst,
        "design_hook_load": {c.label: c.design_hook_load for c in capacity},
        "design_utilisation": design,
        "failed_checks": [f"{c.name} {c.subject}" for c in result.design_loads.checks if not c.ok],
        "worst_spread": result.worst_spread,
        "worst_utilisation_spread": result.worst_utilisation_spread,
        "max_worst_over_swl": chosen.max_utilisation,
        "max_design_utilisation": design[highest],
        "max_design_crane": result.cranes[highest],
    }


def shares_held(problem, result):
    """Sweep the weight up, shares held, until the plan's first crane is past its SWL in the
    box and the first design check has failed (or MAX_FACTOR x W0)."""
    held = SharesHeld(problem, result)
    w0 = problem.body.weight
    names = list(result.chosen.crane_names)
    grid = []
    for k in range(int(round((MAX_FACTOR - 1.0) / GRID_STEP)) + 1):
        weight = w0 * (1.0 + GRID_STEP * k)
        grid.append(weight)
        in_box, _, failed = held.at(weight)
        if np.max(in_box) > 1.0 and failed:
            grid += [w0 * (1.0 + GRID_STEP * (k + j)) for j in (1, 2)]  # a little past, to draw
            break
    in_box_at = {name: _first(lambda w, j=j: held.at(w)[0][j] <= 1.0, grid) for j, name in enumerate(names)}
    design_at = {name: _first(lambda w, j=j: held.at(w)[1][j] <= 1.0, grid) for j, name in enumerate(names)}
    check_fails = _first(lambda w: not held.at(w)[2], grid)
    first = min((w, n) for n, w in in_box_at.items() if w is not None) if any(in_box_at.values()) else None
    curves = [held.at(w) for w in grid]
    return {
        "weights": grid,
        "in_box": {name: [float(c[0][j]) for c in curves] for j, name in enumerate(names)},
        "design": {name: [float(c[1][j]) for c in curves] for j, name in enumerate(names)},
        "in_box_reaches_swl_at": in_box_at,
        "design_reaches_swl_at": design_at,
        "first_in_box_at_swl": None if first is None else {"crane": first[1], "weight": first[0]},
        "first_failed_check": None
        if check_fails is None
        else {"weight": check_fails, "checks": held.at(check_fails + BISECT_T)[2]},
        "design_ok_at_planned_weight": not held.at(w0)[2],
        "design_over_swl_at_planned_weight": [n for n, v in zip(names, held.at(w0)[1]) if v > 1.0],
    }


def replanned_limit(problem, objective):
    """The heaviest body the planner can still plan for, re-planning at every weight  [t]."""
    w0 = problem.body.weight

    def attempt(weight):
        try:
            return plan(_with_weight(dataclasses.replace(problem, objective=objective), weight), top=1)
        except PlanInfeasible as err:
            return err

    low, last, step = w0, None, 0
    while True:
        step += 1
        high = w0 * (1.0 + REPLAN_STEP * step)
        found = attempt(high)
        if isinstance(found, PlanInfeasible):
            failure = found
            break
        low, last = high, found
        if high >= MAX_FACTOR * w0:
            return {"weight": None, "note": f"still feasible at {high:g} t"}
    while high - low > BISECT_T:
        middle = 0.5 * (low + high)
        found = attempt(middle)
        if isinstance(found, PlanInfeasible):
            high, failure = middle, found
        else:
            low, last = middle, found
    last = last or attempt(low)
    return {
        "weight": low,
        "infeasible_at": high,
        "lugs": last.lugs,
        "cranes": last.cranes,
        "reason": str(failure),
    }


def study():
    data = {"fleets": {}}
    for key, (problem, where) in fleets().items():
        plans = {}
        for objective in OBJECTIVES:
            result, entry = plan_entry(problem, objective)
            entry["shares_held"] = shares_held(problem, result)
            entry["replanned"] = replanned_limit(problem, objective)
            plans[objective] = entry
        data["fleets"][key] = {
            "name": problem.name,
            "where": where,
            "weight": problem.body.weight,
            "frame": problem.frame,
            "cog": list(problem.body.cog),
            "rules": dataclasses.asdict(problem.rules),
            "candidates": {c.name: p for c, p in zip(problem.candidates, problem.plan_points.tolist())},
            "outline": [list(p) for p in problem.outline],
            "fleet": [
                {
                    "name": c.name,
                    "position": list(c.position),
                    "reach": c.reach,
                    "load_chart": [list(p) for p in c.load_chart],
                }
                for c in problem.fleet
            ],
            "plans": plans,
        }
    return data


COLORS = ["tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink"]
STYLES = {"spread": ("-", "o"), "utilisation": ("--", "s")}


def _plan_view(ax, key, f, color):
    from matplotlib.patches import Circle

    flip = -1.0 if f["frame"] == "choi" else 1.0  # draw in the file's frame (papers': z = -y)
    if f["outline"]:
        outline = np.array(f["outline"] + f["outline"][:1])
        ax.plot(outline[:, 0], flip * outline[:, 1], color="0.3", lw=1.0)
    points = f["candidates"]
    xy = np.array(list(points.values()))
    ax.scatter(xy[:, 0], flip * xy[:, 1], s=12, color="0.6", zorder=2)
    for crane in f["fleet"]:
        cx, cy = crane["position"][0], flip * crane["position"][1]
        ax.scatter([cx], [cy], marker="s", s=50, color=color[crane["name"]], zorder=4)
        ax.annotate(
            crane["name"],
            (cx, cy),
            fontsize=8,
            color=color[crane["name"]],
            ha="center",
            xytext=(0, -12 if cy > 0 else 7),
            textcoords="offset points",
        )
        ax.add_patch(Circle((cx, cy), crane["reach"], fill=False, ec=color[crane["name"]], ls=":", lw=0.6))
    for objective, entry in f["plans"].items():
        ls, marker = STYLES[objective]
        for label, lug in entry["lugs"].items():
            crane = next(c for c in f["fleet"] if c["name"] == entry["cranes"][label])
            x, y = points[lug][0], flip * points[lug][1]
            ax.plot(
                [crane["position"][0], x],
                [flip * crane["position"][1], y],
                ls=ls,
                lw=1.3,
                color=color[crane["name"]],
            )
            ax.scatter([x], [y], marker=marker, s=40, facecolor="none", edgecolor="k", zorder=3)
        ax.plot([], [], color="k", ls=ls, marker=marker, mfc="none", label=f"objective = {objective}")
    cgx, cgy, _ = f["cog"]  # z-up
    ax.scatter([cgx], [flip * cgy], marker="x", color="tab:red", s=60, zorder=5, label="CG")
    positions = np.array([c["position"] for c in f["fleet"]])
    xs, ys = np.r_[xy[:, 0], positions[:, 0]], flip * np.r_[xy[:, 1], positions[:, 1]]
    ax.set_xlim(xs.min() - 10, xs.max() + 10)
    ax.set_ylim(ys.min() - 10, ys.max() + 10)
    ax.set_aspect("equal")
    if f["frame"] == "choi":
        ax.invert_yaxis()  # seen from above with x to the right, starboard is down
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel("z [m] (to starboard)" if f["frame"] == "choi" else "y [m] (to port)")
    ax.set_title(f"{key}: which crane takes which lug (W = {f['weight']:g} t)", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", ncol=3)
    ax.grid(True, lw=0.3)


def _bars(ax, f, color):
    names = [c["name"] for c in f["fleet"]]
    width = 0.38
    for k, (objective, entry) in enumerate(f["plans"].items()):
        by_crane = {entry["cranes"][label]: label for label in entry["lugs"]}
        x = np.arange(len(names)) + (k - 0.5) * width
        in_box = [entry["worst_over_swl"][by_crane[n]] for n in names]
        ax.bar(
            x,
            in_box,
            width,
            color=[color[n] for n in names],
            alpha=0.35 if k else 0.8,
            edgecolor="k",
            hatch="//" if k else None,
            label=f"{objective}: worst in the box / SWL (bar)",
        )
        ax.scatter(
            x,
            [entry["utilisation"][by_crane[n]] for n in names],
            marker="_",
            s=250,
            color="k",
            zorder=3,
            label="level T* / SWL" if k == 0 else None,
        )
        design = [entry["design_utilisation"][by_crane[n]] for n in names]
        ax.scatter(
            x,
            design,
            marker="v",
            s=30,
            color="k",
            zorder=3,
            label="design hook load / SWL (rules' chain)" if k == 0 else None,
        )
        for xi, v, d in zip(x, in_box, design):
            ax.annotate(
                f"{v:.2f}",
                (xi, v),
                fontsize=6.5,
                ha="center",
                va="top",
                xytext=(0, -2),
                textcoords="offset points",
            )
            ax.annotate(
                f"{d:.2f}", (xi, d), fontsize=6.5, ha="center", xytext=(0, 4), textcoords="offset points"
            )
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(np.arange(len(names)), names, fontsize=8)
    ax.set_ylabel("load / chart SWL at the crane's radius [-]")
    ax.set_ylim(0, 1.3)
    ax.set_title(
        "\n".join(
            f"{o}: worst tension spread {e['worst_spread']:.0f} t, worst utilisation "
            f"spread {e['worst_utilisation_spread']:.3f}"
            for o, e in f["plans"].items()
        ),
        fontsize=8,
    )
    ax.legend(fontsize=6.5, loc="upper left", ncol=2)
    ax.grid(True, axis="y", lw=0.3)


def _sweep(ax, f, color, which):
    for objective, entry in f["plans"].items():
        ls, marker = STYLES[objective]
        held = entry["shares_held"]
        weights = np.array(held["weights"])
        for name, ratio in held[which].items():
            ax.plot(weights, ratio, ls=ls, color=color[name], lw=1.2)
        reached = held[f"{which}_reaches_swl_at"]
        hit = {n: w for n, w in reached.items() if w is not None}
        if hit:
            name = min(hit, key=hit.get)
            ax.plot([hit[name]], [1.0], marker=marker, color=color[name], mec="k", ms=8, zorder=4)
            text = f"{objective} plan: {name} first at SWL, {hit[name]:.0f} t"
        else:
            text = f"{objective} plan: no crane at SWL up to {weights[-1]:.0f} t"
        if which == "design" and held["first_failed_check"] is not None:
            failed = held["first_failed_check"]
            ax.axvline(failed["weight"], color="0.45", ls=ls, lw=0.9)
            text += f"; first failed check {', '.join(failed['checks'])} at {failed['weight']:.0f} t (grey)"
        limit = entry["replanned"]["weight"]
        if which == "in_box" and limit is not None:
            ax.axvline(limit, color="tab:red", ls=ls, lw=0.9)
            text += f"; re-planned limit {limit:.0f} t (red)"
        ax.plot([], [], color="k", ls=ls, marker=marker, mfc="0.6", label=text)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("body weight [t] (each crane keeps its planned share)")
    what = (
        "worst tension in the tolerance box / SWL"
        if which == "in_box"
        else "design hook load / SWL (rules' chain)"
    )
    ax.set_ylabel(f"{what} [-]")
    ax.set_title(
        f"weight grows, shares held: {what}\nper crane (colour); solid: spread plan, "
        "dashed: utilisation plan",
        fontsize=8,
    )
    ax.legend(fontsize=6.5, loc="lower right")
    ax.grid(True, lw=0.3)


def draw(data, path):
    from matplotlib.figure import Figure

    fleets_data = data["fleets"]
    fig = Figure(figsize=(24, 5.6 * len(fleets_data)), layout="constrained")
    axes = fig.subplots(
        len(fleets_data), 4, gridspec_kw={"width_ratios": [1.3, 1.0, 1.0, 1.0]}, squeeze=False
    )
    for row, (key, f) in zip(axes, fleets_data.items()):
        color = {c["name"]: COLORS[j % len(COLORS)] for j, c in enumerate(f["fleet"])}
        _plan_view(row[0], key, f, color)
        _bars(row[1], f, color)
        _sweep(row[2], f, color, "in_box")
        _sweep(row[3], f, color, "design")
    fig.savefig(path, dpi=100)


def _summary(data):
    for key, f in data["fleets"].items():
        print(f"{key} (W = {f['weight']:g} t)")
        for objective, e in f["plans"].items():
            held, re_plan = e["shares_held"], e["replanned"]
            r3 = lambda d: [round(v, 3) for v in d.values()]  # noqa: E731
            print(f"  {objective}: " + ", ".join(f"{e['lugs'][k]} {e['cranes'][k]}" for k in e["lugs"]))
            print(
                f"    T* {[round(v, 1) for v in e['tensions'].values()]} t, T*/SWL {r3(e['utilisation'])}, "
                f"worst/SWL {r3(e['worst_over_swl'])}, design/SWL {r3(e['design_utilisation'])}"
            )
            print(
                f"    worst spread {e['worst_spread']:.1f} t, worst utilisation spread "
                f"{e['worst_utilisation_spread']:.3f}, highest design/SWL "
                f"{e['max_design_utilisation']:.3f} ({e['max_design_crane']}), failed checks "
                f"{e['failed_checks']}"
            )
            print(
                f"    shares held: first in box at SWL {held['first_in_box_at_swl']}; design at SWL "
                f"{held['design_reaches_swl_at']}; first failed check {held['first_failed_check']}"
            )
            print(f"    re-planned limit {re_plan['weight']} t ({re_plan.get('reason', '')[:160]})")


def main():
    OUT.mkdir(exist_ok=True)
    path = OUT / "fleet_objectives.json"
    path.write_text(json.dumps(study(), indent=1))
    data = json.loads(path.read_text())  # the figure is drawn from the file
    draw(data, OUT / "fleet_objectives.png")
    _summary(data)


if __name__ == "__main__":
    main()

"""Planning features two at a time: which combinations plan, which are refused and why.

Issue 24 item 6. Each *feature* is one small, stated change to a planning file (below,
:data:`FEATURES`); each *cell* is one feature alone or two features together, applied to one
*base* (an example planning file with the features' own keys taken out, :data:`BASES`), written
to a temporary file and planned by the real command line in a child process::

    python -m liftplan.planner.cli plan FILE --json

with a per-cell time-out (60 s; the child's process group is killed past it). Every cell is
measured on every run; nothing in the tables is typed in.

A pair's base is the first base of its more restrictive feature that the other accepts
(slings: the hull block; breakout: the sunken block; everything else: the tanker first). A
feature that needs another brings it (``strength_objective`` the girder data,
``force_control`` the bending objective), and is also measured once alone without it (a
*bare* cell: the refusal that says what it needs). Two features that set the same key
(``search_local``, ``search_mip``) are not paired. The three bases are also planned alone.

For a feature an IGNORED cell does not show, the plan is compared with the plan of the same
base without that feature: a different plan proves the input was used (the JSON just does
not say so); the same plan proves nothing either way.

Outcomes:

  plan      exit 0, or 4 (planned, a check failed: the failed checks are listed), and every
            feature's input is visible in the plan's JSON (the fleet's crane names, the hook
            tolerance in ``hooks.tolerance``, ``girder``, ``strength``, ``breakout``,
            ``rope_lengths``, ``search.method``, ``search.limits.time_limit``, ...: see each
            feature's ``honoured`` test)
  IGNORED   planned, but a feature's input is not visible in the plan: the worst outcome
            (the input may have been dropped silently; at best the plan does not say it
            used it)
  refused   exit 1 (no feasible plan) or 2 (bad input), with the planner's one-line reason
  FAILED    exit 3 (internal error), a traceback, any other exit code or unreadable JSON
  timeout   still running after the time-out (the cell's features may be fine, but not
            within the time-out on this machine)

Run:  python studies/combinations.py              (writes studies/out/combinations.json, then
                                                   studies/out/combinations.md from it;
                                                   15 minutes on 2 busy cores)
      python studies/combinations.py --summary    (only the .md, from the .json)
      python studies/combinations.py --only girder slings   (the cells with either; merged
                                                   into the existing .json)
      python studies/combinations.py --again timeout   (re-measure the cells that timed out,
                                                   e.g. when the machine was busy)
      python studies/combinations.py --files DIR  (also keep every planning file written)

Times are wall times of the whole child process (Python start-up and imports, about 2 s,
included) on a 2-core machine shared with other work: indicative, compare ratios rather
than seconds.
"""

from __future__ import annotations

import argparse
import copy
import datetime
import itertools
import json
import os
import platform
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path

import tomli_w

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
OUT = ROOT / "studies" / "out"
TIMEOUT = 60.0
OUTCOMES = ("plan", "IGNORED", "refused", "FAILED", "timeout")

#: The hook tolerance, CG envelope, time limit and CoG factor the features and bases set.
HOOK_TOLERANCE = 0.02
COG_TOLERANCE = [0.5, 0.2, 0.3]
TIME_LIMIT = 30.0
COG_FACTOR = 1.03  # the file reference's example value; bases without a CG envelope need one


# -- the bases ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Base:
    """An example planning file, neutralised, and the data the features take on it.

    ``fleet``: [[cranes]] tables (and [crane] defaults, [rules] entries) the ``fleet``
    feature puts in; ``girder``: ``body.weight_curve`` and ``[strength]``; ``sling``: the
    sling every crane gets; ``payout``: the rope-length range; ``length``: the body's x
    extent (for the flexible hull's EI / GJ).
    """

    name: str
    file: str
    note: str
    fleet: dict
    girder: dict
    payout: dict
    length: tuple[float, float]
    sling: dict | None = None  # None: the slings feature is not tried on this base
    equal_cranes: dict | None = None  # [crane] that replaces the example's [[cranes]]


def _read(name):
    return tomllib.loads((EXAMPLES / name).read_text(encoding="utf-8"))


def _tanker_girder():
    strength = _read("tanker_strength.toml")
    return {"weight_curve": strength["body"]["weight_curve"], "strength": strength["strength"]}


def _tanker_fleet():
    fleet = _read("tanker_fleet.toml")
    return {"cranes": fleet["cranes"], "crane": fleet["crane"], "rules": fleet["rules"]}


def _block_fleet():
    cranes = [
        {k: v for k, v in c.items() if k != "sling"} for c in _read("block_four_leg_plan.toml")["cranes"]
    ]
    return {"cranes": cranes, "crane": {}, "rules": {}}


#: ASSUMED for this study (no example has one): a fleet for the sunken block, two 800 t-class
#: sheerlegs off its port side and two 500 t-class cranes off its starboard side.
SUNKEN_FLEET = {
    "crane": {},
    "rules": {},
    "cranes": [
        {
            "name": name,
            "position": [x, y, 0.0],
            "load_chart": chart,
            "EA": 50000.0,
            "rope_length": 44.0,
        }
        for name, x, y, chart in (
            ("Sheerleg A", 15.0, 25.0, [[15.0, 800.0], [25.0, 600.0], [35.0, 450.0], [45.0, 320.0]]),
            ("Sheerleg B", 45.0, 25.0, [[15.0, 800.0], [25.0, 600.0], [35.0, 450.0], [45.0, 320.0]]),
            ("Crane C", 15.0, -25.0, [[12.0, 500.0], [22.0, 380.0], [32.0, 280.0], [40.0, 200.0]]),
            ("Crane D", 45.0, -25.0, [[12.0, 500.0], [22.0, 380.0], [32.0, 280.0], [40.0, 200.0]]),
        )
    ],
}

#: ASSUMED: the 180 t block's weight as a linear curve over x -8..8 m (180 t, centroid at the
#: CG's x = 0.4 m) and allowables of a light double-bottom block.
BLOCK_GIRDER = {
    "weight_curve": [[-8.0, 9.5625], [8.0, 12.9375]],
    "strength": {
        "bending_moment": [[-8.0, 400.0], [8.0, 400.0]],
        "shear_force": [[-8.0, 100.0], [8.0, 100.0]],
    },
}
#: ASSUMED: the 600 t sunken block evenly over its 60 m (centroid at the CG's x = 30 m).
SUNKEN_GIRDER = {
    "weight_curve": [[0.0, 10.0], [60.0, 10.0]],
    "strength": {
        "bending_moment": [[0.0, 3000.0], [60.0, 3000.0]],
        "shear_force": [[0.0, 300.0], [60.0, 300.0]],
    },
}

BASES = {
    "tanker": Base(
        name="tanker",
        file="tanker_plan.toml",
        note="the 1500 GT tanker, 16 candidates, four equal 400 t cranes",
        fleet=_tanker_fleet(),
        girder=_tanker_girder(),
        payout={"min": 25.0, "max": 55.0},
        length=(0.0, 82.05),
    ),
    "block": Base(
        name="block",
        file="block_four_leg_plan.toml",
        note="the 180 t hull block, 24 deck candidates, four equal 100 t crawlers (no reach limit)",
        fleet=_block_fleet(),
        girder=BLOCK_GIRDER,
        sling={"legs": 4, "length": 9.0, "diameter": 56.0},
        payout={"min": 18.0, "max": 36.0},
        length=(-8.0, 8.0),
        equal_cranes={
            "EA": 30000.0,
            "rope_length": 24.0,
            "swl": 100.0,
            "boom_height": {"min": 30.0, "max": 60.0},
        },
    ),
    "sunken": Base(
        name="sunken",
        file="sunken_block_plan.toml",
        note="the 600 t sunken block, 12 candidates, four equal 400 t cranes, lifted from -20 m",
        fleet=SUNKEN_FLEET,
        girder=SUNKEN_GIRDER,
        # 2 legs of 10 m: its candidates (x = 5 .. 55 m) hold only two disjoint 4-leg rigs, and
        # the hooks must stay low enough for the boom tips' 40 m with 44 m of hoist rope
        sling={"legs": 2, "length": 10.0, "diameter": 56.0},
        payout={"min": 30.0, "max": 50.0},
        length=(0.0, 60.0),
    ),
}

#: Keys the features set, taken out of every base so that a feature is off unless a cell has it.
FEATURE_PLAN_KEYS = ("hook_tolerance", "cog_tolerance", "cog_envelope", "objective", "breakout_scene")


def base_document(base):
    """The base's planning file as a dict: the example with every feature's key taken out,
    the fixed [[cranes]] replaced by equal cranes where the base has them, and a CoG factor
    (the rules ask for one when no CG envelope is searched)."""
    doc = _read(base.file)
    doc.pop("report", None)
    for key in FEATURE_PLAN_KEYS:
        doc["plan"].pop(key, None)
    if base.equal_cranes is not None:
        doc["plan"]["cranes"] = len(doc.pop("cranes"))
        doc["crane"] = copy.deepcopy(base.equal_cranes)
    doc.setdefault("rules", {})["cog_factor"] = COG_FACTOR
    return doc


# -- the features ---------------------------------------------------------------------------
def _cranes(doc):
    """The [[cranes]] tables; equal cranes ([crane] and plan.cranes = n) become n tables
    named crane 1..n that take everything from [crane]."""
    if "cranes" not in doc:
        count = doc["plan"].pop("cranes")
        doc["cranes"] = [{"name": f"crane {i + 1}"} for i in range(count)]
    return doc["cranes"]


def apply_fleet(doc, base):
    fleet = copy.deepcopy(base.fleet)
    doc["plan"].pop("cranes", None)
    doc["cranes"] = fleet["cranes"]
    doc["crane"] = fleet["crane"]
    doc["rules"] = {**doc.get("rules", {}), **fleet["rules"]}


def apply_hook_tolerance(doc, base):
    doc["plan"]["hook_tolerance"] = HOOK_TOLERANCE


def apply_cog_envelope(doc, base):
    doc["plan"]["cog_tolerance"] = list(COG_TOLERANCE)
    doc.get("rules", {}).pop("cog_factor", None)  # the envelope is searched: no factor on top


def apply_girder(doc, base):
    doc["body"]["weight_curve"] = copy.deepcopy(base.girder["weight_curve"])
    doc["strength"] = copy.deepcopy(base.girder["strength"])


def apply_strength_objective(doc, base):
    doc["plan"]["objective"] = "bending"


def apply_slings(doc, base):
    for crane in _cranes(doc):
        crane["sling"] = dict(base.sling)


def apply_breakout(doc, base):
    doc["plan"]["breakout_scene"] = str(EXAMPLES / "sunken_block_breakout.toml")


def apply_rope_lengths(doc, base):
    for table in [doc.get("crane", {}), *doc.get("cranes", [])]:
        if "rope_length" in table:
            table["rope_length"] = dict(base.payout)


def apply_force_control(doc, base):
    doc.setdefault("crane", {})["control"] = "force"


def apply_search_local(doc, base):
    doc["plan"]["search"] = "local"


def apply_search_mip(doc, base):
    doc["plan"]["search"] = "mip"


def apply_time_limit(doc, base):
    doc["plan"]["time_limit"] = TIME_LIMIT


def apply_flexible_hull(doc, base):
    start, end = base.length
    doc["hull"] = {"EI": [[start, 5.3e7], [end, 5.3e7]], "GJ": [[start, 5.2e7], [end, 5.2e7]]}


#: The sunken block's hull (examples/sunken_block_breakout.toml), for the start in water.
SUNKEN_HULL = {
    "box": {"min": [0.0, -6.0, 0.0], "max": [60.0, 6.0, 6.0]},
    "flooding": "flooded",
    "steel_density": 7.85,
    "compartments": [
        {"name": "fore tank", "box": {"min": [55.0, -6.0, 0.0], "max": [60.0, 6.0, 2.0]}, "contents": "air"},
        {"name": "aft tank", "box": {"min": [0.0, -6.0, 0.0], "max": [6.0, 6.0, 2.0]}, "contents": "water"},
    ],
}


def apply_water(doc, base):
    """The lift starting with the sunken block's hull half submerged (its home base)."""
    doc["water"] = {"density": 1.025, "level": 0.0}
    doc.setdefault("hull", {}).update(copy.deepcopy(SUNKEN_HULL))
    doc["plan"]["start_lift_height"] = -3.0


# -- is each feature visible in the plan? ---------------------------------------------------
def _values(obj, key):
    """Every value of ``key`` anywhere in a JSON object."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if k == key:
                yield v
            yield from _values(v, key)
    elif isinstance(obj, list):
        for item in obj:
            yield from _values(item, key)


def _checks(out):
    return {c["name"] for c in out.get("checks", [])}


def _search_methods(out):
    return [m for m in _values(out, "method") if isinstance(m, str)]


def honoured_fleet(out, doc):
    names = {c["name"] for c in doc["cranes"]}
    used = set(out.get("cranes", {}).values()) | set(out.get("hook_loads", {}))
    return None if used == names else f"crane names in the plan {sorted(used)}, expected {sorted(names)}"


def honoured_hook_tolerance(out, doc):
    tolerances = [t for v in _values(out, "tolerance") if isinstance(v, dict) for t in v.values()]
    if tolerances and all(t == HOOK_TOLERANCE for t in tolerances):
        return None
    return f"no hooks.tolerance of {HOOK_TOLERANCE} m in the plan (found {tolerances or 'none'})"


def honoured_cog_envelope(out, doc):
    offsets = [o for o in _values(out, "cog_offset") if any(abs(x) > 0 for x in o)]
    searched = list(_values(out, "cog_searched"))
    if (offsets or searched) and all(searched):
        return None
    return f"no non-zero cog_offset, cog_searched {searched or 'absent'}"


def honoured_girder(out, doc):
    missing = {"bending_moment", "shear_force"} - _checks(out)
    if (out.get("girder") or out.get("strength")) and not missing:
        return None
    return f"no girder / strength result, or checks missing: {sorted(missing)}"


def honoured_strength_objective(out, doc):
    if out.get("objective") == "bending" and "strength" in out:
        return None
    return f"objective {out.get('objective')!r}, strength result {'strength' in out}"


def honoured_slings(out, doc):
    if "sling" in str(out.get("lift", "")) and "sling_angle" in _checks(out):
        return None
    return f"lift {out.get('lift')!r}, sling_angle check {'sling_angle' in _checks(out)}"


def honoured_breakout(out, doc):
    if out.get("breakout") and "breakout_hook_load" in _checks(out):
        return None
    return "no breakout result or breakout_hook_load check"


def honoured_rope_lengths(out, doc):
    lengths = out.get("rope_lengths")
    if lengths and "rope_length_search" in out:
        return None
    return "no rope_lengths / rope_length_search in the plan"


def honoured_force_control(out, doc):
    controls = list(_values(out, "control"))
    return None if controls and all(c == "force" for c in controls) else f"control {controls or 'absent'}"


def _honoured_search(method):
    def test(out, doc):
        methods = _search_methods(out)
        if any(m == method or m.startswith(method) for m in methods):
            return None
        return f"search.method {methods or 'absent'}, expected {method!r}"

    return test


def honoured_time_limit(out, doc):
    """The limit in ``search.limits`` (a rope-length trial shows what was left of it), or a
    search stopped by it."""
    limits = [t for t in _values(out, "time_limit") if isinstance(t, int | float)]
    if any(0 < t <= TIME_LIMIT for t in limits) or "time_limit" in list(_values(out, "stopped")):
        return None
    return f"time_limit in the plan: {limits or 'absent'}"


def honoured_flexible_hull(out, doc):
    if "flexible_hull" in out and all("hull_model" in r for r in out.get("ranking", [])):
        return None
    return "no flexible_hull in the plan"


def honoured_water(out, doc):
    names = [c.get("name") for c in out.get("checks", [])]
    if "in_water" in out and "in_water_min_tension" in names:
        return None
    return "no in_water in the plan"


def honoured_never(out, doc):
    return "planned, but the plan has no trace of this table (the planner does not model it)"


@dataclass(frozen=True)
class Feature:
    name: str
    change: str  # what it does to the file, for the docs
    apply: object  # (doc, base) -> None, changes doc in place
    honoured: object  # (plan JSON, doc) -> None, or why the input is not visible
    bases: tuple[str, ...] = ("tanker", "block", "sunken")  # where it makes sense, home first
    requires: tuple[str, ...] = ()  # features it needs, applied with it (but see bare cells)
    excludes: tuple[str, ...] = ()  # features that set the same key: no such pair


#: In the order they are applied (the fleet before the slings and the rope lengths).
FEATURES = [
    Feature(
        "fleet",
        "unequal cranes with load charts and positions: the example fleet (tanker: "
        "tanker_fleet.toml's cranes and [rules]; block: block_four_leg_plan.toml's crawlers "
        "without slings; sunken block: a fleet assumed here)",
        apply_fleet,
        honoured_fleet,
    ),
    Feature(
        "hook_tolerance",
        f"`[plan] hook_tolerance = {HOOK_TOLERANCE}`",
        apply_hook_tolerance,
        honoured_hook_tolerance,
    ),
    Feature(
        "cog_envelope",
        f"`[plan] cog_tolerance = {COG_TOLERANCE}` (and no `[rules] cog_factor`)",
        apply_cog_envelope,
        honoured_cog_envelope,
    ),
    Feature(
        "girder",
        "`body.weight_curve` and `[strength]` allowables (tanker: tanker_strength.toml's; "
        "blocks: assumed here)",
        apply_girder,
        honoured_girder,
    ),
    Feature(
        "strength_objective",
        '`[plan] objective = "bending"`; needs `girder` (the base\'s weight curve and allowables), '
        "which comes with it",
        apply_strength_objective,
        honoured_strength_objective,
        requires=("girder",),
    ),
    Feature(
        "slings",
        "a sling on every crane (block: 4 legs of 9 m, 56 mm, as block_four_leg_plan.toml; "
        "sunken block: 2 legs of 10 m; equal cranes become [[cranes]] tables)",
        apply_slings,
        honoured_slings,
        bases=("block", "sunken"),
    ),
    Feature(
        "breakout",
        "`[plan] breakout_scene = sunken_block_breakout.toml`",
        apply_breakout,
        honoured_breakout,
        bases=("sunken",),
    ),
    Feature(
        "rope_lengths",
        "every `rope_length` a payout range (tanker 25-55 m, block 18-36 m, sunken block 30-50 m)",
        apply_rope_lengths,
        honoured_rope_lengths,
    ),
    Feature(
        "force_control",
        '`[crane] control = "force"`; needs `strength_objective` (force control is planned for the '
        "hull girder only), which comes with it",
        apply_force_control,
        honoured_force_control,
        requires=("strength_objective",),
    ),
    Feature(
        "search_local",
        '`[plan] search = "local"`',
        apply_search_local,
        _honoured_search("local"),
        excludes=("search_mip",),
    ),
    Feature(
        "search_mip",
        '`[plan] search = "mip"`',
        apply_search_mip,
        _honoured_search("mip"),
        excludes=("search_local",),
    ),
    Feature("time_limit", f"`[plan] time_limit = {TIME_LIMIT:g}`", apply_time_limit, honoured_time_limit),
    Feature(
        "flexible_hull",
        "`[hull] EI, GJ` (constant along the body, the tanker_flexible.toml values; with the "
        "girder's weight curve, which the beam is loaded by)",
        apply_flexible_hull,
        honoured_flexible_hull,
        requires=("girder",),
    ),
    Feature(
        "water",
        "`[water] density = 1.025, level = 0.0`, the sunken block's `[hull]` box, `[plan] "
        "start_lift_height = -3.0` (half submerged)",
        apply_water,
        honoured_water,
        bases=("sunken",),
    ),
]
BY_NAME = {f.name: f for f in FEATURES}


def cell_base(features):
    """The base on which every feature of the cell makes sense: the first feature's home
    (its first base) that the others accept, the most restrictive feature first."""
    ordered = sorted(features, key=lambda f: len(f.bases))
    for f in ordered:
        for name in f.bases:
            if all(name in g.bases for g in features):
                return BASES[name]
    raise ValueError(f"no base for {[f.name for f in features]}")


@dataclass(frozen=True)
class Cell:
    """One planning file to measure: a base and features (``bare``: without what they need)."""

    base: Base
    features: tuple[Feature, ...]
    bare: bool = False

    @property
    def names(self):
        return [f.name for f in self.features]

    @property
    def label(self):
        return " x ".join(self.names) + (
            " (alone, without " + ", ".join(self.needs) + ")" if self.bare else ""
        )

    @property
    def needs(self):
        return [n for f in self.features for n in f.requires]

    def applied(self):
        """The features applied, with what they need unless ``bare``."""
        names = set(self.names)
        while not self.bare and (
            more := {n for f in FEATURES if f.name in names for n in f.requires} - names
        ):
            names |= more
        return [f for f in FEATURES if f.name in names]  # in FEATURES order, whatever the cell's


def cells(only=()):
    """Every base alone, every feature alone, every feature that needs another without it
    (``bare``), and every pair but those setting the same key."""
    out = [Cell(base, ()) for base in BASES.values()]
    out += [Cell(cell_base([f]), (f,)) for f in FEATURES]
    out += [Cell(cell_base([f]), (f,), bare=True) for f in FEATURES if f.requires]
    out += [
        Cell(cell_base([a, b]), (a, b))
        for a, b in itertools.combinations(FEATURES, 2)
        if b.name not in a.excludes
    ]
    if only:
        out = [c for c in out if any(n in only for n in c.names)]
    return out


def document(cell):
    doc = base_document(cell.base)
    for f in cell.applied():
        f.apply(doc, cell.base)
    return doc


# -- one cell ------------------------------------------------------------------------------
def run_plan(path, timeout):
    """``liftplan plan PATH --json`` in its own process group: (exit code or None on time-out,
    stdout, stderr, seconds)."""
    command = [sys.executable, "-m", "liftplan.planner.cli", "plan", str(path), "--json"]
    start = time.perf_counter()
    child = subprocess.Popen(
        command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True
    )
    try:
        stdout, stderr = child.communicate(timeout=timeout)
        code = child.returncode
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)  # the child's own group: nothing else
        stdout, stderr = child.communicate()
        code = None
    return code, stdout, stderr, time.perf_counter() - start


def reason_line(stderr, path):
    """The planner's one-line reason: its last ``liftplan:`` line that is not a warning, less
    the ``liftplan: `` prefix and the (temporary) file's name."""
    lines = [ln for ln in stderr.splitlines() if ln.startswith("liftplan") and "warning:" not in ln]
    line = lines[-1] if lines else (stderr.strip().splitlines() or ["(nothing on stderr)"])[-1]
    line = line.removeprefix("liftplan: ").replace(f"{path}: ", "").replace(f"{path.name}: ", "")
    return line.replace(str(path.parent) + os.sep, "")


def fingerprint(out):
    """What a plan chose and its worst value: to tell whether a feature changed the plan."""
    worst = next((out[k] for k in ("worst_utilisation_spread", "worst_spread") if k in out), None)
    return {
        "lugs": sorted(out.get("lugs", {}).values()),
        "cranes": sorted(out.get("cranes", {}).values()),
        "objective": out.get("objective"),
        "worst": None if worst is None else float(f"{worst:.6g}"),
    }


def classify(code, stdout, stderr, path, features, doc):
    """(outcome, reason, detail) of a finished child."""
    if code in (0, 4):
        try:
            out = json.loads(stdout)
        except json.JSONDecodeError:
            return "FAILED", f"exit {code} with unreadable JSON: {stdout[:200]!r}", {}
        missing = {f.name: why for f in features if (why := f.honoured(out, doc)) is not None}
        detail = {
            "failed_checks": sorted({f"{c['name']} {c['subject']}" for c in out["checks"] if not c["ok"]}),
            "plan": fingerprint(out),
            "not_visible": missing,
        }
        if missing:
            return "IGNORED", "; ".join(f"{k}: {v}" for k, v in missing.items()), detail
        return "plan", None, detail
    reason = reason_line(stderr, path)
    if code in (1, 2) and "Traceback" not in stderr:
        return "refused", reason, {}
    return "FAILED", reason, {"stderr_tail": stderr[-2000:]}


def measure(cell, timeout, folder):
    doc = document(cell)
    label = "+".join(cell.names) or "base"
    path = folder / f"{cell.base.name}-{label}{'-bare' if cell.bare else ''}.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    load = os.getloadavg()[0]
    code, stdout, stderr, seconds = run_plan(path, timeout)
    if code is None:
        outcome, reason, detail = "timeout", f"still running after {timeout:g} s (killed)", {}
    else:
        outcome, reason, detail = classify(code, stdout, stderr, path, cell.applied(), doc)
    return {
        "features": cell.names,
        "bare": cell.bare,
        "without": cell.needs if cell.bare else [],
        "applied": [f.name for f in cell.applied()],
        "base": cell.base.name,
        "base_file": f"examples/{cell.base.file}",
        "outcome": outcome,
        "exit": code,
        "seconds": round(seconds, 2),
        "load_average": round(load, 2),  # 1-minute, at the cell's start
        "reason": reason,
        **detail,
    }


# -- the study -----------------------------------------------------------------------------
def machine():
    return {
        "date": datetime.date.today().isoformat(),
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpus": os.cpu_count(),
        "load_average": [round(x, 2) for x in os.getloadavg()],
        "timeout": None,
    }


def run(only, again, timeout, files):
    """Measure the cells (all; ``only``: those with these features; ``again``: those whose
    saved outcome is one of these), merge them into the saved data when a part was measured,
    write studies/out/combinations.json and return its data."""
    saved = OUT / "combinations.json"
    previous = json.loads(saved.read_text()) if (only or again) and saved.is_file() else None
    todo = cells(only)
    if again:
        repeat = {_key(c) for c in (previous or {"cells": []})["cells"] if c["outcome"] in again}
        todo = [c for c in todo if (c.base.name, tuple(c.names), c.bare) in repeat]
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(files) if files else Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        for i, cell in enumerate(todo, 1):
            result = measure(cell, timeout, folder)
            results.append(result)
            print(
                f"[{i}/{len(todo)}] {cell.base.name}: {cell.label or 'base'}: "
                f"{result['outcome']} {result['seconds']:.1f} s {result['reason'] or ''}",
                file=sys.stderr,
                flush=True,
            )
    if previous is not None:
        done = {_key(c) for c in results}
        results = [c for c in previous["cells"] if _key(c) not in done] + results
    add_evidence(results)
    info = previous["machine"] if previous is not None else machine()
    if previous is not None:
        which = f"with {' or '.join(only)}" if only else ""
        which += (
            f"{' and ' if only and again else ''}{'with the outcome ' + ' or '.join(again) if again else ''}"
        )
        info = {**info, "partial_rerun": f"{machine()['date']}, the cells {which}"}
    info = {**info, "timeout": timeout}
    data = {
        "machine": info,
        "bases": {b.name: {"file": f"examples/{b.file}", "note": b.note} for b in BASES.values()},
        "features": {f.name: f.change for f in FEATURES},
        "cells": _ordered(results),
    }
    OUT.mkdir(exist_ok=True)
    (OUT / "combinations.json").write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    return data


def _key(result):
    return result["base"], tuple(result["features"]), result["bare"]


def add_evidence(results):
    """For each feature an IGNORED cell does not show: is the plan the same without it (the
    same base, the other features)? The same plan does not prove the input unused (an exact
    search finds the same optimum whatever its method), a different one proves it used."""
    plans = {_key(c): c.get("plan") for c in results if "plan" in c}
    for cell in results:
        evidence = {}
        for name in cell.get("not_visible", {}):
            if name not in cell["features"]:
                evidence[name] = "it comes with another feature of the cell: not compared"
                continue
            without = tuple(n for n in cell["features"] if n != name)
            reference = plans.get((cell["base"], without, False))
            other = " x ".join(without) or f"the {cell['base']} base alone"
            if reference is None:
                evidence[name] = f"no plan of {other} on this base to compare with"
            elif reference == cell["plan"]:
                evidence[name] = f"the same plan as {other}: no effect seen"
            else:
                evidence[name] = f"a different plan from {other}: it was used, but the plan does not say so"
        if evidence:
            cell["evidence"] = evidence


def _ordered(results):
    order = {name: i for i, name in enumerate(BY_NAME)}
    return sorted(
        results,
        key=lambda c: (len(c["features"]), c["bare"], [order[n] for n in c["features"]], c["base"]),
    )


# -- the summary ---------------------------------------------------------------------------
def label(cell):
    names = " x ".join(cell["features"]) or f"{cell['base']} base"
    return f"{names} without {', '.join(cell['without'])}" if cell["bare"] else names


def note_key(cell):
    """The text of a refused, failed or ignored cell's numbered note."""
    if cell["outcome"] == "IGNORED":
        evidence = cell.get("evidence", {})
        return "; ".join(
            f"`{k}` not shown: {v} ({evidence.get(k, 'not compared')})"
            for k, v in cell["not_visible"].items()
        )
    return cell["reason"]


def short(cell, notes):
    """The matrix entry of a cell; ``notes`` (text -> cells) numbers the notes."""
    outcome = cell["outcome"]
    if outcome == "plan":
        return f"plan {cell['seconds']:.1f} s" + (" (exit 4)" if cell["exit"] == 4 else "")
    if outcome == "timeout":
        return "timeout"
    key = note_key(cell)
    notes.setdefault(key, []).append(cell)
    word = {"refused": "refused", "FAILED": "**FAILED**", "IGNORED": "**IGNORED**"}[outcome]
    return f"{word} [{list(notes).index(key) + 1}]"


def summary(data):
    """studies/out/combinations.md from the measured data (included by docs/combinations.md)."""
    cells = data["cells"]
    matrix = [c for c in cells if c["features"] and not c["bare"]]
    notes = {}
    lines = [*_header(data), *_matrix(data, matrix, notes), ""]
    lines += [_counts(matrix), ""]
    bare = [c for c in cells if c["bare"]]
    if bare:
        lines += ["Features that need another, measured alone without it:", ""]
        lines += [f"- {label(c)}: {short(c, notes)}" for c in bare]
        lines += [""]
    lines += ["Notes (refused and FAILED: the planner's own line on stderr):", ""]
    for number, (text, which) in enumerate(notes.items(), 1):
        where = ", ".join(label(c) for c in which)
        lines.append(f"{number}. {_outcome_word(which[0])} {where}: {_escape(text)}")
    failed = [c for c in cells if c["outcome"] in ("plan", "IGNORED") and c.get("failed_checks")]
    if failed:
        lines += ["", "Plans with a failed check (exit 4):", ""]
        lines += [f"- {label(c)}: {', '.join(c['failed_checks'])}" for c in failed]
    lines += ["", "What each feature changes in the base file:", ""]
    lines += [f"- `{name}`: {change}" for name, change in data["features"].items()]
    lines += ["", "The base of each cell (the diagonal: the feature alone):", ""]
    lines += _bases(data, cells)
    (OUT / "combinations.md").write_text("\n".join(lines) + "\n", encoding="utf-8")


def _matrix(data, matrix, notes):
    """The lower triangle: each pair once, each feature alone on the diagonal; pairs that set
    the same key are marked and not measured."""
    names = list(data["features"])
    by_key = {frozenset(c["features"]): c for c in matrix}
    lines = ["| | " + " | ".join(f"`{n}`" for n in names) + " |", "|---" * (len(names) + 1) + "|"]
    for i, a in enumerate(names):
        row = []
        for b in names[: i + 1]:
            cell = by_key.get(frozenset((a, b)))
            row.append(short(cell, notes) if cell is not None else "same key")
        lines.append(f"| `{a}` | " + " | ".join(row + [""] * (len(names) - i - 1)) + " |")
    return lines


def _outcome_word(cell):
    return {"refused": "refused:", "FAILED": "**FAILED**:", "IGNORED": "**IGNORED**:"}[cell["outcome"]]


def _header(data):
    m = data["machine"]
    baselines = [c for c in data["cells"] if not c["features"]]
    rerun = f" Re-measured {m['partial_rerun']}." if "partial_rerun" in m else ""
    loads = [c["load_average"] for c in data["cells"] if "load_average" in c]
    load = f"{min(loads):.1f} to {max(loads):.1f}" if loads else f"{m['load_average'][0]}"
    return [
        f"Measured {m['date']} with Python {m['python']} on {m['cpus']} cores shared with other work "
        f"(1-minute load average {load} at the cells' starts): times indicative, compare ratios.{rerun} "
        f"Time-out {m['timeout']:g} s per cell. Each cell is one `liftplan plan FILE --json` in its own "
        "process; its time is the whole process, start-up included.",
        "",
        "Legend: `plan 4.1 s`: planned, every feature visible in the plan's JSON (`(exit 4)`: "
        "planned, a check failed, listed below); `refused [n]`: exit 1 (no feasible plan) or 2 (bad "
        "input), note n; `timeout`: still running at the time-out (killed); **FAILED** [n]: internal "
        "error or traceback; **IGNORED** [n]: planned, but a feature's input is not visible in the "
        "plan (note n says whether the plan is the same without it); `same key`: the two set the same "
        "key, not a combination.",
        "",
        "Bases alone: "
        + "; ".join(f"{c['base']} (`{data['bases'][c['base']]['file']}`) {short(c, {})}" for c in baselines)
        + ".",
        "",
    ]


def _counts(matrix):
    counts = {}
    for c in matrix:
        counts[c["outcome"]] = counts.get(c["outcome"], 0) + 1
    return f"{len(matrix)} cells: " + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) + "."


def _bases(data, cells):
    by_base = {}
    for c in cells:
        if c["features"]:
            by_base.setdefault(c["base"], []).append(label(c))
    return [
        f"- {name} (`{data['bases'][name]['file']}`, {data['bases'][name]['note']}): {', '.join(labels)}"
        for name, labels in by_base.items()
    ]


def _escape(text):
    return text.replace("|", "\\|")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--summary", action="store_true", help="only write the .md from the .json")
    parser.add_argument("--only", nargs="*", default=(), choices=list(BY_NAME), help="cells with these")
    parser.add_argument(
        "--again",
        nargs="*",
        default=(),
        choices=OUTCOMES,
        help="re-measure the saved cells with these outcomes",
    )
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="seconds per cell (60)")
    parser.add_argument("--files", metavar="DIR", help="keep the planning files written, in DIR")
    args = parser.parse_args()
    data = (
        json.loads((OUT / "combinations.json").read_text())
        if args.summary
        else run(args.only, args.again, args.timeout, args.files)
    )
    summary(data)


if __name__ == "__main__":
    main()

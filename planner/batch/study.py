"""Batch study files (``liftplan batch STUDY.toml``): which cases to run.

A study names a planning scene file and the parameters to vary. Two kinds:

``plan``
    every case is a full optimisation (:func:`~liftplan.planner.plan.plan`) of the scene
    with the case's values: how the best lugs and boom heights move with the weight, the
    CG, the tolerances, the candidate set or the crane count.
``check``
    the scene is planned once; every case checks that plan (boom heights fixed) against
    a real weight, CG and tolerance box: how robust is the chosen plan.
``montecarlo``
    the scene is planned once; every case is one draw of independent hook-height errors
    (``[montecarlo]``: draws, uniform or normal, per-crane tolerances, seed) on that plan,
    solved on the full elastic model (:mod:`~liftplan.planner.batch.montecarlo`). One row
    per draw: the errors, the tensions, the pose and what they exceed; no ``[sweep]`` or
    ``[sample]``.

Cases are the grid of ``[sweep]`` values (every combination), times ``[sample]`` random
draws of the weight and CG (seeded; the same draws at every grid point). Keys are the
planning file's own dotted names, values in its frame and units::

    [study]
    problem = "tanker_plan.toml"   # relative to this file
    kind = "check"
    output = "tanker_check.csv"    # relative to this file (default: STUDY.csv)

    [sweep]
    "plan.tolerance.heel" = [1.0, 2.0, 3.0]

    [sample]
    count = 1000
    seed = 1
    weight = [0.95, 1.05]          # factor on body.weight, uniform
    cog = [0.5, 0.2, 0.3]          # m, half-widths of a uniform offset of body.cog

Each key is declared with its documentation (``Key``: the convention is in
:mod:`liftplan.model.scene.file`), from which the file reference's tables are generated.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Annotated, Literal

import numpy as np
from pydantic import Field, Strict, ValidationError

from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import Key, Num, Point, Table, Text, load_with, one_line, parse_toml
from liftplan.planner.problem.file import problem_from_dict

Count = Annotated[int, Strict(), Field(ge=1)]
Value = Annotated[float, Strict()] | Annotated[int, Strict()] | str | list

#: Keys a ``check`` study may vary (the plan's lugs and boom heights stay fixed).
CHECK_KEYS = ("body.weight", "body.cog", "plan.tolerance.heel", "plan.tolerance.trim", "plan.min_tension")
#: The sweep key that picks a named candidate subset.
CANDIDATES = "candidates"
MAX_CASES = 10_000_000


class _Study(Table):
    problem: Text = Key(
        doc=(
            "the planning file, relative to the study file; the planning file's own relative paths "
            "(`plan.breakout_scene`) are read from its folder, whatever the working folder"
        ),
        values="string (path)",
        example='problem = "tanker_plan.toml"',
    )
    kind: Literal["plan", "check", "montecarlo"] = Key(
        "plan",
        doc=(
            "`plan`: optimise every case; `check`: plan the file once, then check that plan (lugs and "
            "boom heights fixed) in every case; `montecarlo`: plan the file once, then solve it on "
            "the elastic model under `[montecarlo]` draws of hook-height errors (no `[sweep]`, "
            "`[sample]` or `[candidate_sets]`)"
        ),
        example='kind = "check"',
    )
    name: Text = Key(
        "", doc="a label for the study", absent="the study file's name", example='name = "tanker robustness"'
    )
    output: Text = Key(
        "",
        doc="the CSV table to write, relative to the study file",
        values="string (path)",
        absent="STUDY.csv next to the study file",
        example='output = "tanker_check.csv"',
    )
    grid: Annotated[int, Strict(), Field(ge=1, le=41)] = Key(
        3,
        doc="`check`: attitudes per axis of each tolerance box",
        unit="-",
        values="integer 1 to 41",
        example="grid = 5",
    )
    chunk: Count | None = Key(
        None,
        doc="cases per Dask task",
        unit="-",
        values="integer >= 1",
        absent="5000 for `check` and `montecarlo`, 1 for `plan`",
        example="chunk = 1000",
    )


class _Sample(Table):
    count: Count = Key(doc="draws per grid point", unit="-", values="integer >= 1", example="count = 20000")
    seed: Annotated[int, Strict(), Field(ge=0)] = Key(
        0, doc="the random generator's seed", unit="-", values="integer >= 0", example="seed = 1"
    )
    weight: Annotated[list[Num], Field(min_length=2, max_length=2)] | None = Key(
        None,
        doc="uniform factor on `body.weight`, 0 < low <= high",
        unit="factor",
        values="[low, high]",
        example="weight = [0.95, 1.05]",
    )
    cog: Point | None = Key(
        None,
        doc="uniform offset of `body.cog` (at least one of `weight` and `cog`)",
        unit="m",
        values="[dx, dy, dz] >= 0",
        frame="half-widths, file frame axes",
        example="cog = [1.0, 0.3, 0.5]",
    )


class _MonteCarlo(Table):
    draws: Count = Key(
        10_000, doc="number of draws (rows)", unit="-", values="integer >= 1", example="draws = 100000"
    )
    distribution: Literal["uniform", "normal"] = Key(
        "uniform",
        doc="`uniform`: each error within +-tolerance; `normal`: the tolerance is the standard deviation",
        example='distribution = "normal"',
    )
    seed: Annotated[int, Strict(), Field(ge=0)] = Key(
        0,
        doc=(
            "the generator's seed: the draws are made from it alone, the same however the run is "
            "chunked or resumed"
        ),
        unit="-",
        values="integer >= 0",
        example="seed = 1",
    )
    tolerance: Num | None = Key(
        None,
        doc="every hook's error scale",
        unit="m",
        values="number >= 0",
        absent="the plan's hook tolerances",
        example="tolerance = 0.05",
    )
    tolerances: dict[str, Num] = Key(
        {},
        doc=(
            "per crane, by its name in the planning file (`crane 1` ... for `[crane]` defaults), "
            "overriding `tolerance`; at least one hook's scale must be above 0"
        ),
        unit="m",
        values="table of numbers >= 0",
        example='tolerances = { "crane 2" = 0.05 }',
    )


class _StudyFile(Table):
    study: _Study = Key(doc="the study", example="[study]")
    sweep: dict[str, Annotated[list[Value], Field(min_length=1)]] = Key(
        {},
        doc=(
            "each key is a planning key in quotes (dotted, as in the planning tables above), each "
            "value the array of values to run; `check` studies may vary `body.weight`, `body.cog`, "
            "`plan.tolerance.heel`, `plan.tolerance.trim`, `plan.min_tension`; the key `candidates` "
            'picks `"all"` or a named set of `[candidate_sets]`'
        ),
        unit="the planning key's",
        values="table of arrays",
        frame="planning file's",
        example='"plan.tolerance.heel" = [1.0, 2.0, 3.0]',
    )
    candidate_sets: dict[str, Annotated[list[Text], Field(min_length=1)]] = Key(
        {},
        doc="named subsets of the planning file's candidates, picked by `sweep.candidates`",
        values="table of arrays of strings",
        example='cargo = ["BH3-P", "BH3-S", "BH4-P", "BH4-S"]',
    )
    sample: _Sample | None = Key(
        None, doc="seeded random draws, the same at every grid point", absent="no draws", example="[sample]"
    )
    montecarlo: _MonteCarlo | None = Key(
        None,
        doc=(
            'hook-height error draws on the planned file (only with `kind = "montecarlo"`): each draw '
            "moves every hook off its planned height by an independent error and solves the full "
            "elastic model; the table has one row per draw: `error.L1..Ln` (m), `status` (`ok`; "
            "`unsafe`: a rope over the plan's limit (its chart SWL through the rules' chain: SWL / "
            "DAF, less the rigging, over the contingency) or slack; `failed`: no stable upright "
            "equilibrium), "
            "`reason`, `tension.L1..Ln` (t), `heel`, `trim` (deg), `spread`, `max_tension` (t), "
            "`above_plan_worst`, `above_design_load`, `above_swl` (0 or 1), `slack` (ropes) and "
            "`above_design_tension` (0 or 1). `above_design_tension`: a drawn (static) tension above "
            "the static tension its crane's design hook load was built from, (static hook load - "
            "rigging) / (contingency x CoG factor): like for like. `above_design_load`: a drawn "
            "static tension above the design hook load itself, which carries the contingency and the "
            "DAF on top (lenient; kept for scripts). Blank where no design load was computed "
            '(docs/design-loads.md "Monte-Carlo draws against the design load")'
        ),
        absent='the defaults below, with `kind = "montecarlo"`',
        example="[montecarlo]",
    )


@dataclass(frozen=True)
class MonteCarloSpec:
    """The draws of a ``montecarlo`` study.

    Parameters
    ----------
    draws : int
    distribution : {"uniform", "normal"}
        ``uniform``: each error within +-tolerance; ``normal``: standard deviation = tolerance.
    seed : int
    tolerance : float or None  [m]
        Every hook's error scale; None: the plan's own hook tolerances.
    tolerances : tuple of (str, float)  [m]
        Per crane (by crane name), overriding ``tolerance``.
    """

    draws: int = 10_000
    distribution: str = "uniform"
    seed: int = 0
    tolerance: float | None = None
    tolerances: tuple = ()

    def scale(self, plan):
        """Each planned hook's error scale (label order)  [m]."""
        own = dict(self.tolerances)
        base = (
            plan.lugset.hook_tolerance
            if self.tolerance is None
            else np.full(len(plan.labels), self.tolerance)
        )
        return np.array(
            [own.get(name, value) for name, value in zip(plan.chosen.crane_names, base)], dtype=float
        )


@dataclass(frozen=True)
class Study:
    """A batch study: a base planning scene and the cases to run on it.

    Parameters
    ----------
    name : str
    kind : {"plan", "check"}
    base : dict
        The planning scene file, as parsed TOML (its own frame and units).
    output : pathlib.Path
        The table to write (CSV).
    sweep : tuple of (str, tuple)
        Dotted key and its values; every combination is a case.
    candidate_sets : dict of str to tuple of str
        Named candidate subsets, picked by the sweep key ``"candidates"`` (``"all"``: every
        candidate).
    sample_count : int
        Random draws per grid point (0: none).
    seed : int
    weight_range : tuple of 2 float or None
        Factor range on the weight, uniform.
    cog_widths : tuple of 3 float or None  [m]
        Half-widths of the uniform CG offset, file frame.
    grid : int
        ``check``: attitudes per axis of the tolerance box.
    chunk : int
        Cases per Dask task.
    montecarlo : MonteCarloSpec or None
        The draws of a ``montecarlo`` study.
    cranes : int
        Planned cranes (lugs) of the base scene.
    folder : pathlib.Path or None
        The planning file's folder (absolute): relative paths in it (``plan.breakout_scene``)
        are read from there, whatever the working folder; None: the working folder.
    """

    name: str
    kind: str
    base: dict
    output: Path
    sweep: tuple
    candidate_sets: dict
    sample_count: int = 0
    seed: int = 0
    weight_range: tuple | None = None
    cog_widths: tuple | None = None
    grid: int = 3
    chunk: int = 1
    montecarlo: MonteCarloSpec | None = None
    cranes: int = 4
    folder: Path | None = None

    @property
    def fingerprint(self):
        """Hash of everything that defines the cases (a resumed run must match it)."""
        spec = {
            "kind": self.kind,
            "base": self.base,
            "sweep": self.sweep,
            "sets": self.candidate_sets,
            "sample": [self.sample_count, self.seed, self.weight_range, self.cog_widths],
            "grid": self.grid,
            "montecarlo": self.montecarlo,
        }
        return hashlib.sha256(json.dumps(spec, sort_keys=True, default=str).encode()).hexdigest()[:16]

    @property
    def size(self):
        """Number of cases."""
        if self.montecarlo is not None:
            return self.montecarlo.draws
        grid = int(np.prod([len(values) for _, values in self.sweep], dtype=np.int64))
        return grid * max(self.sample_count, 1)

    @cached_property
    def _keys(self):
        keys = [key for key, _ in self.sweep]
        if self.weight_range is not None and "body.weight" not in keys:
            keys.append("body.weight")
        if self.cog_widths is not None and "body.cog" not in keys:
            keys.append("body.cog")
        return keys

    @cached_property
    def _vectors(self):
        return {
            key
            for key in self._keys
            if key == "body.cog" or any(isinstance(v, list) for k, vs in self.sweep if k == key for v in vs)
        }

    @property
    def labels(self):
        """The planned lug labels L1..Ln."""
        return tuple(f"L{i + 1}" for i in range(self.cranes))

    def columns(self):
        """Parameter columns of the output table (vectors split into .x .y .z; a Monte-Carlo
        draw's hook errors, one per planned lug)."""
        if self.montecarlo is not None:
            return [f"error.{label}" for label in self.labels]
        return [
            f"{key}.{axis}" if key in self._vectors else key
            for key in self._keys
            for axis in ("xyz" if key in self._vectors else "-")
        ]

    def cases(self):
        """Every case, as (index, {dotted key: value}) in a fixed order."""
        if self.montecarlo is not None:  # the draws need the plan: see run.py
            yield from ((i, {}) for i in range(self.montecarlo.draws))
            return
        keys = [key for key, _ in self.sweep]
        draws = self._draws()
        index = 0
        for combo in itertools.product(*(values for _, values in self.sweep)):
            values = dict(zip(keys, combo))
            for draw in draws:
                case = dict(values)
                if draw is not None:
                    factor, offset = draw
                    if factor is not None:
                        case["body.weight"] = factor * float(_get(self.base, "body.weight", case))
                    if offset is not None:
                        cog = np.asarray(_get(self.base, "body.cog", case), dtype=float) + offset
                        case["body.cog"] = cog.tolist()
                yield index, case
                index += 1

    @cached_property
    def grid_reasons(self):
        """Why each sweep grid point is no valid planning scene ("" where it is), in case
        order: case ``i`` is grid point ``i // max(sample_count, 1)``. Each point is checked
        by the planning file's own rules (schema and dataclasses), ~1 ms a point."""
        keys = [key for key, _ in self.sweep]
        out = []
        for combo in itertools.product(*(values for _, values in self.sweep)):
            try:
                self.problem(dict(zip(keys, combo)))
            except InvalidScene as err:
                out.append(str(err).replace("\n", " "))
            else:
                out.append("")
        return out

    def _draws(self):
        if self.sample_count == 0:
            return [None]
        rng = np.random.default_rng(self.seed)
        count = self.sample_count
        factors = rng.uniform(*self.weight_range, count) if self.weight_range is not None else [None] * count
        offsets = (
            rng.uniform(-1.0, 1.0, (count, 3)) * np.asarray(self.cog_widths)
            if self.cog_widths is not None
            else [None] * count
        )
        return list(zip(factors, offsets))

    def row_values(self, case):
        """A case's parameter values in :meth:`columns` order (a Monte-Carlo draw's errors
        come with its result; blank here)."""
        if self.montecarlo is not None:
            return [""] * self.cranes
        out = []
        for key in self._keys:
            value = case.get(key)
            out.extend(value if key in self._vectors else [value])
        return out

    def raw_problem(self, case):
        """The planning file of one case (a copy of the base with the case's values)."""
        raw = copy.deepcopy(self.base)
        for key, value in case.items():
            if key == CANDIDATES:
                raw["candidates"] = self._subset(value)
            else:
                _set(raw, key, value)
        return raw

    def problem(self, case):
        """The :class:`PlanProblem` of one case (``InvalidScene`` if its values are not)."""
        return problem_from_dict(self.raw_problem(case), base=self.folder)

    def _subset(self, name):
        if name == "all":
            return self.base["candidates"]
        if name not in self.candidate_sets:
            raise InvalidScene(
                f"sweep.candidates = {name!r}: expected 'all' or a name in "
                f"[candidate_sets] ({', '.join(self.candidate_sets) or 'none'})"
            )
        keep = self.candidate_sets[name]
        return [c for c in self.base["candidates"] if c.get("name") in keep]


def _get(raw, key, case):
    if key in case:
        return case[key]
    node = raw
    for part in key.split("."):
        node = node[part]
    return node


def _set(raw, key, value):
    *parents, leaf = key.split(".")
    node = raw
    for part in parents:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise InvalidScene(f"sweep.{key!r}: {part} is not a table in the planning file")
    node[leaf] = value


def load_study(path):
    """Read and validate a study file.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    Study

    Raises
    ------
    InvalidScene
        One line naming the file, the key, the value and what is expected; also when the
        first case's planning scene is not valid (a misspelt sweep key, say).
    """
    path = Path(path)
    return load_with(path, lambda text: loads_study(text, path.parent, path.stem))


def loads_study(text, base=Path("."), stem="study"):
    """Validate a study given as TOML text; relative paths are read from ``base``."""
    try:
        data = _StudyFile.model_validate(parse_toml(text))
    except ValidationError as err:
        raise InvalidScene(one_line(err, _StudyFile)) from None
    spec = data.study
    folder = (Path(base) / spec.problem).parent.resolve()  # the planning file's own folder
    raw = _read_problem(base, spec.problem, folder)
    sample = data.sample
    if sample is not None and sample.weight is None and sample.cog is None:
        raise InvalidScene("[sample]: expected weight = [low, high] and/or cog = [dx, dy, dz]")
    if (
        sample is not None
        and sample.weight is not None
        and not (0 < sample.weight[0] <= sample.weight[1] < math.inf)
    ):
        raise InvalidScene(f"sample.weight = {sample.weight}: expected finite factors 0 < low <= high")
    if sample is not None and sample.cog is not None and not all(0 <= w < math.inf for w in sample.cog):
        raise InvalidScene(f"sample.cog = {list(sample.cog)}: expected finite half-widths >= 0 m")
    montecarlo = _montecarlo_spec(data, raw, folder)
    if spec.kind == "check":
        for key in data.sweep:
            if key not in CHECK_KEYS:
                raise InvalidScene(
                    f"sweep.{key!r}: a check study keeps the plan's lugs; expected "
                    f"one of {', '.join(CHECK_KEYS)}"
                )
    study = Study(
        name=spec.name or stem,
        kind=spec.kind,
        base=raw,
        output=base / (spec.output or f"{stem}.csv"),
        sweep=tuple((key, tuple(values)) for key, values in data.sweep.items()),
        candidate_sets={k: tuple(v) for k, v in data.candidate_sets.items()},
        sample_count=sample.count if sample else 0,
        seed=sample.seed if sample else 0,
        weight_range=tuple(sample.weight) if sample and sample.weight else None,
        cog_widths=tuple(sample.cog) if sample and sample.cog else None,
        grid=spec.grid,
        chunk=spec.chunk or (5000 if spec.kind in ("check", "montecarlo") else 1),
        montecarlo=montecarlo,
        cranes=problem_from_dict(raw, base=folder).cranes,
        folder=folder,
    )
    if study.size > MAX_CASES:
        raise InvalidScene(f"study: {study.size} cases, expected at most {MAX_CASES}")
    _check_sweep(study)
    return study


def _montecarlo_spec(data, raw, folder):
    """The ``[montecarlo]`` table of a ``montecarlo`` study (refused with any other kind)."""
    table = data.montecarlo
    if data.study.kind != "montecarlo":
        if table is not None:
            raise InvalidScene(
                f"montecarlo: given with study.kind = {data.study.kind!r}; expected "
                'kind = "montecarlo" (or no [montecarlo] table)'
            )
        return None
    for key in ("sweep", "sample", "candidate_sets"):
        if getattr(data, key):
            raise InvalidScene(
                f"{key}: given with study.kind = 'montecarlo'; expected none (the "
                "cases are the [montecarlo] draws on the one plan)"
            )
    table = table or _MonteCarlo()
    values = [("montecarlo.tolerance", table.tolerance)] + [
        (f"montecarlo.tolerances.{name}", v) for name, v in table.tolerances.items()
    ]
    for key, value in values:
        if value is not None and not 0.0 <= value < math.inf:
            raise InvalidScene(f"{key} = {value!r}: expected a finite hook tolerance >= 0 m")
    problem = problem_from_dict(raw, base=folder)
    names = [c.name for c in problem.fleet]
    for name in table.tolerances:
        if name not in names:
            raise InvalidScene(
                f"montecarlo.tolerances.{name}: no such crane; expected one of {', '.join(names)}"
            )
    own = [problem.hook_tolerance if c.hook_tolerance is None else c.hook_tolerance for c in problem.fleet]
    scales = [
        table.tolerances.get(c.name, v if table.tolerance is None else table.tolerance)
        for c, v in zip(problem.fleet, own)
    ]
    if not any(v > 0.0 for v in scales):
        raise InvalidScene(
            "montecarlo.tolerance: every hook's tolerance is 0 (the plan assumes no "
            "hook error and none is given here); expected tolerance > 0 m"
        )
    return MonteCarloSpec(
        draws=table.draws,
        distribution=table.distribution,
        seed=table.seed,
        tolerance=table.tolerance,
        tolerances=tuple(table.tolerances.items()),
    )


def _read_problem(base, name, folder):
    """The study's planning file as a dict, refused unless it is a valid planning scene
    (its relative paths read from ``folder``, its own folder)."""
    if not name.strip():
        raise InvalidScene("study.problem = '': expected the planning file's path")
    path = base / name
    if not path.exists():
        raise InvalidScene(f"study.problem = {name!r}: no such planning file ({path})")
    try:
        raw = load_with(path, parse_toml)
        problem_from_dict(raw, base=folder)
    except InvalidScene as err:
        raise InvalidScene(f"study.problem = {name!r}: {err}") from None
    return raw


def _check_sweep(study):
    """Refuse a sweep value that no case can use (a string for a number, a CG with two
    components, a NaN weight, a 200 deg tolerance, a crane count of 9): every grid point
    holding it is no valid planning scene. A value valid in some combinations only keeps
    the run; its invalid combinations become ``invalid`` rows with the reason."""
    shape = tuple(len(values) for _, values in study.sweep)
    reasons = study.grid_reasons
    valid = np.array([not r for r in reasons], dtype=bool).reshape(shape)
    for axis, (key, values) in enumerate(study.sweep):
        usable = valid.any(axis=tuple(a for a in range(len(shape)) if a != axis))
        for k in np.flatnonzero(~usable):
            index = [0] * len(shape)
            index[axis] = int(k)
            reason = reasons[int(np.ravel_multi_index(index, shape))]
            raise InvalidScene(f"sweep.{key!r}[{k}] = {values[k]!r}: no case can use it: {reason}")

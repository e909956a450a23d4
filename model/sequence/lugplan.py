"""Planning the lug set of a sequence: the candidates whose worst design lug load is least.

Each lug given ``on`` candidates goes on one of them; two lugs held in one stage never share
a candidate, lugs of different stages may (one strong point serving two hooks in turn). Every
assignment is a :class:`~liftplan.model.sequence.objects.Sequence`, compared by: every check
met (first); the worst design lug load over the whole sequence, of all lugs (the rules' chain
on each stage's continuous maxima, :func:`~liftplan.model.sequence.sweep.design_chain`); then
the worst of the lugs placed (fixed lugs often carry the worst load whatever the choice); then
the sum of the placed lugs' worst design loads.

The search is exact, by bounds: the same chain on the maxima of the user's grid alone is a
lower bound of these design loads (each continuous maximum is at least its grid maximum, and
the chain only multiplies loads by factors of one or more; the hook loads it takes are the
body's weight, the most a support carries, since the DAF of light lifts falls as the hook load
rises), and a check that fails on the grid fails on the whole range. Assignments are swept in
the order of their bounds (those known to fail last); once an assignment with every check met
is at or below the next bound, no assignment left can beat it. A stage depends only on the
candidates of the lugs it holds, so each stage is solved once per such combination.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

from liftplan.model.errors import EquilibriumNotFound, InvalidScene, PlanInfeasible
from liftplan.model.sequence.maxima import Peak, Sampler
from liftplan.model.sequence.sweep import SequenceResult, design_chain, run_stage, stage_model

#: Most assignments enumerated (the product of the lugs' candidate counts).
MOST_OPTIONS = 100_000


@dataclass(frozen=True)
class LugOption:
    """One assignment of candidates to the lugs to place.

    Parameters
    ----------
    lugs : dict of str to str
        Lug -> candidate.
    bound : float  [t]
        Worst design lug load on the user's grid (a lower bound).
    worst : float or None  [t]
        Worst design lug load over the continuous sweep (None: pruned by its bound).
    where : str
        The lug and stage of ``worst``.
    ok : bool or None
        Every check of the sweep met (None: not swept).
    """

    lugs: dict
    bound: float
    worst: float | None = None
    where: str = ""
    ok: bool | None = None

    def to_json(self):
        return {
            "lugs": dict(self.lugs),
            "bound": self.bound,
            "worst": self.worst,
            "where": self.where,
            "ok": self.ok,
        }


@dataclass(frozen=True)
class LugPlan:
    """The planned lug set and its sequence swept.

    Parameters
    ----------
    best : LugOption
    result : SequenceResult
        The sweep of the chosen assignment.
    ranking : tuple of LugOption
        Every swept assignment, best first.
    options, swept, refused : int
        Assignments enumerated, swept continuously, refused (a sling that cannot reach, a move
        whose ropes cannot hold the body on the grid).
    seconds : float
    """

    best: LugOption
    result: object
    ranking: tuple
    options: int
    swept: int
    refused: int
    seconds: float

    def to_json(self):
        return {
            "lugs": dict(self.best.lugs),
            "worst_design_lug_load": self.best.worst,
            "where": self.best.where,
            "all_checks_met": self.best.ok,
            "options": self.options,
            "swept": self.swept,
            "pruned": self.options - self.refused - self.swept,
            "refused": self.refused,
            "ranking": [o.to_json() for o in self.ranking],
            "seconds": self.seconds,
        }


def worst_design_load(chains, placed=()):
    """Over ``{stage: DesignLoadChain}``: (largest lug design load [t], "LUG (stage)", (largest
    of the lugs in ``placed``, sum over ``placed`` of each one's largest) [t])."""
    worst, where, mine = 0.0, "", {}
    for stage, chain in chains.items():
        for crane in chain.results:
            for lug in crane.lugs:
                if lug.design_load > worst:
                    worst, where = lug.design_load, f"{lug.lug} ({stage})"
                if lug.lug in placed:
                    mine[lug.lug] = max(mine.get(lug.lug, 0.0), lug.design_load)
    return worst, where, (max(mine.values(), default=0.0), sum(mine.values()))


def grid_stage(sequence, stage):
    """One stage on the user's grid alone: (its design chain, whether a check already fails).

    The chain is a lower bound of the continuous sweep's (see the module docstring); a check
    failed on the grid fails on the continuous range too.
    """
    model = stage_model(sequence, stage)
    sampler = Sampler(model)
    names = model.names()
    maxima, held = {}, True
    for angle in stage.angles:
        state, values = sampler(angle)
        held = held and state.held
        for name in names:
            if name not in maxima or values[name] > maxima[name].value:
                maxima[name] = Peak(values[name], float(angle))
    # every hook load at W, the most any support carries: the table's DAF falls as the static
    # hook load rises (0027/ND Table 5-1, 100 t and under), so the least DAF keeps this a bound
    for name in names:
        if name.startswith("hook:"):
            maxima[name] = Peak(sequence.body.weight, maxima[name].angle)
    chain = design_chain(sequence, stage, model, maxima, sampler)
    fails = not held
    for crane in chain.results:
        for lug in crane.lugs:
            spec = sequence.lug(lug.lug)
            factor = lug.product * sequence.rules.consequence_factor
            across = (
                maxima[f"lug_out:{lug.lug}"].value * factor
                + sequence.rules.lateral_fraction * lug.design_load
            )
            if spec.capacity is not None and lug.design_load > spec.capacity:
                fails = True
            if spec.capacity_out_of_plane is not None and across > spec.capacity_out_of_plane:
                fails = True
    return chain, fails


def assignments(choice):
    """Every assignment of candidates to the open lugs that no stage holds twice."""
    names = [name for name, _ in choice.open]
    together = []  # pairs of open lugs held in one stage
    for stage in choice.parts["stages"]:
        held = _held(choice, stage)
        together += [(a, b) for a, b in itertools.combinations(names, 2) if a in held and b in held]
    count = 1
    for _, options in choice.open:
        count *= len(options)
    if count > MOST_OPTIONS:
        raise InvalidScene(
            f"lugs.on: {count} assignments of candidates; expected at most {MOST_OPTIONS} (fewer candidates)"
        )
    for combo in itertools.product(*(options for _, options in choice.open)):
        chosen = dict(zip(names, combo))
        if all(chosen[a] != chosen[b] for a, b in together):
            yield chosen


def _depends(choice, stages, index):
    """The lugs a stage's states depend on: its own, and a move stage's those of the stages it
    is chained from (it starts where the stage before left the body)."""
    lugs = _held(choice, stages[index])
    if stages[index].kind == "move" and index > 0:
        lugs |= _depends(choice, stages, index - 1)
    return lugs


def _held(choice, stage):
    """The lugs a stage's cranes hold."""
    return {lug for key in stage.cranes for c in choice.parts["cranes"] if _key(c) == key for lug in c.lugs}


#: Design loads are compared to this  [t]: the grid's and the sweep's chains at the same state
#: differ by rounding, and a tie must stay a tie.
RANK_TOL = 1e-9


def _rank(*loads):
    return tuple(round(v / RANK_TOL) * RANK_TOL for v in loads)


def _key(crane):
    return crane.name if crane.name is not None else crane.lug


def plan_lugs(choice, top=10):
    """The assignment with the least worst design lug load (every check met first).

    Options are compared by: every check met; the worst design lug load of all lugs; then that
    of the lugs placed. A stage depends only on the candidates of the lugs it holds, so each
    stage is solved once per such combination, on the grid and swept.

    Parameters
    ----------
    choice : LugChoice
    top : int
        Swept assignments kept in the ranking.

    Returns
    -------
    LugPlan

    Raises
    ------
    PlanInfeasible
        No assignment gives a valid sequence.
    """
    started = time.perf_counter()
    placed = {name for name, _ in choice.open}
    stages = choice.parts["stages"]
    held = {stage.where: sorted(_depends(choice, stages, k) & placed) for k, stage in enumerate(stages)}
    grid, swept_stages = {}, {}
    options, refused = [], 0
    for chosen in assignments(choice):
        try:
            seq = choice.sequence(chosen)
        except InvalidScene:  # a sling that cannot reach these candidates, three in one plane
            refused += 1
            continue
        chains, fails = {}, False
        for stage in seq.stages:
            key = (stage.where, tuple(chosen[n] for n in held[stage.where]))
            if key not in grid:
                try:
                    grid[key] = grid_stage(seq, stage)
                except EquilibriumNotFound:  # a move whose ropes cannot hold the body there
                    grid[key] = None
            if grid[key] is None:
                break
            chains[stage.where], failed = grid[key]
            fails = fails or failed
        if len(chains) < len(seq.stages):
            refused += 1
            continue
        worst, _, mine = worst_design_load(chains, placed)
        options.append(((fails, *_rank(worst, *mine)), chosen, seq))
    if not options:
        raise PlanInfeasible(
            f"lugs.on: none of the {refused} assignments of candidates gives a valid sequence"
        )
    options.sort(key=lambda item: item[0])
    swept, best = [], None
    for bound, chosen, seq in options:
        if best is not None and best[0].ok and (bound[0] or bound[1:] >= best[2]):
            break
        stages = []
        for stage in seq.stages:
            key = (stage.where, tuple(chosen[n] for n in held[stage.where]))
            if key not in swept_stages:
                swept_stages[key] = run_stage(seq, stage)
            stages.append(swept_stages[key])
        result = SequenceResult(sequence=seq, stages=tuple(stages), seconds=0.0)
        worst, where, mine = worst_design_load({s.stage.where: s.design for s in stages}, placed)
        ok = all(c.ok for c in result.checks)
        option = LugOption(chosen, bound[1], worst, where, ok)
        swept.append(option)
        rank = _rank(worst, *mine)
        if best is None or (not ok, *rank) < (not best[0].ok, *best[2]):
            best = (option, result, rank)
    ranking = sorted(swept, key=lambda o: (not o.ok, o.worst))[:top]
    return LugPlan(
        best=best[0],
        result=best[1],
        ranking=tuple(ranking),
        options=len(options) + refused,
        swept=len(swept),
        refused=refused,
        seconds=time.perf_counter() - started,
    )

"""A lift sequence: the body, its lugs and cranes, and the stages that turn or move it.

Frozen dataclasses in the ``z-up`` frame. A :class:`Stage` turns the body about one of its
horizontal axes from one angle to another, held by the cranes it names (and, for an upend,
by a pivot on the ground), or moves boom tips (``kind = "move"``, each crane's :class:`Move`)
with the body on its elastic ropes. :class:`Sequence` checks what needs the whole picture:
names, which crane holds which lug, that no turning stage has its supports in one vertical
plane, that every crane of a stage on four or more supports gives its rope's stiffness, and
that every crane of a move stage hangs on an elastic rope from its boom tip.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import Rules
from liftplan.model.scene.objects import Body, Crane, Lug, finite, name_list, point

KINDS = ("upend", "turnover", "move")
AXES = ("x", "y")
#: Most angles a stage may report (its range over its step): a finer grid is a typo.
MOST_STEPS = 10_000
#: Fewest supports (cranes, and the pivot) of a turning stage: one cannot hold an angle.
#: Two or three vertical forces are fixed by the three equations of a body on vertical ropes
#: (vertical force, two moments); from four on (:data:`ELASTIC_SUPPORTS`) the ropes' stiffness
#: shares the load (:mod:`liftplan.model.sequence.statics`).
SUPPORTS = 2
#: Supports from which a turning stage is statically indeterminate: its cranes need
#: ``rope_length`` and ``EA``.
ELASTIC_SUPPORTS = 4
#: Fewest supports of a move stage: the elastic model on vertical ropes needs three taut ropes,
#: or two and a pivot, to hold a body (two leave it free to roll about the line between them).
MOVE_CRANES = 3
#: A move stage's reported grid when ``steps`` is not given.
MOVE_STEPS = 10


@dataclass(frozen=True)
class Move:
    """One crane's boom tip moved linearly over a ``kind = "move"`` stage.

    Parameters
    ----------
    crane : str
        The crane's key.
    hoist : float  [m]
        Rise of the tip from the stage's start to its end (+ up); added to ``to`` when both
        are given.
    to : tuple of 3 float or None  [m]
        World position of the tip at the stage's end (file frame); None: the tip moves only
        by ``hoist``.
    """

    crane: str
    hoist: float = 0.0
    to: tuple[float, float, float] | None = None

    def __post_init__(self):
        where = f"moves[{self.crane}]"
        object.__setattr__(self, "hoist", finite(f"{where}.hoist", self.hoist))
        if self.to is not None:
            object.__setattr__(self, "to", point(f"{where}.to", self.to))

    def end(self, start):
        """The tip's position at the stage's end, from its position ``start``  [m]."""
        base = np.array(self.to if self.to is not None else start, dtype=float)
        return base + np.array([0.0, 0.0, self.hoist])


def crane_key(crane):
    """The key a crane's results are reported under: its name, else its lug."""
    return crane.name if crane.name is not None else crane.lug


@dataclass(frozen=True)
class Stage:
    """One operation: the body turned about a body axis through a range of angles.

    Parameters
    ----------
    kind : {"upend", "turnover", "move"}
        ``"upend"``: the head crane(s) lift one end while the other rests on the ground at
        ``pivot`` or hangs from a tailing crane; ``"turnover"``: the body hangs from two or
        more cranes and turns in the air; ``"move"``: boom tips move (``moves``) and the body
        hangs on its elastic ropes (:mod:`liftplan.model.sequence.move`).
    axis : {"x", "y"}
        The body axis it turns about. For ``"y"`` the angle is how far the body's +x end is
        raised above the horizontal; for ``"x"``, how far its +y side is raised.
    start, stop : float or None  [deg]
        First and last angle (either order); equal: the stage holds that one angle (a lift or
        a set-down with the body at that angle). ``stop`` is None in a move stage.
    step : float  [deg]
        The reported grid; the maxima are searched between its points too.
    cranes : tuple of str
        The cranes that hold the body in this stage (their keys); the others are released.
    pivot : tuple of 3 float or None  [m]
        Body point resting on the ground (``upend``, or a ``move`` on vertical ropes); the
        body turns about it.
    friction : float or None  [-]
        Friction coefficient at the pivot.
    plumb : bool
        Each hook follows its lug (or its sling's apex) to keep the rope vertical.
    name : str
    moves : tuple of Move
        ``kind = "move"``: the cranes whose boom tips move over the stage (the others' stay).
    steps : int
        ``kind = "move"``: the reported grid of the stage parameter 0..1 (default
        :data:`MOVE_STEPS`; ``step`` is then 1 / steps).
    """

    kind: str
    axis: str
    start: float
    stop: float | None
    step: float
    cranes: tuple[str, ...]
    pivot: tuple[float, float, float] | None = None
    friction: float | None = None
    plumb: bool = True
    name: str = ""
    moves: tuple[Move, ...] = ()
    steps: int | None = None

    def __post_init__(self):
        where = f"stages[{self.name}]" if self.name else "sequence"
        if self.kind not in KINDS:
            raise InvalidScene(f"{where}.kind = {self.kind!r}: expected one of {', '.join(KINDS)}")
        object.__setattr__(self, "cranes", tuple(self.cranes))
        object.__setattr__(self, "moves", tuple(self.moves))
        if self.kind == "move":
            self._check_move(where)
            return
        for key, value in (("moves", self.moves or None), ("steps", self.steps)):
            if value is not None:
                raise InvalidScene(f'{where}.{key}: given in a {self.kind} stage; expected kind = "move"')
        if self.stop is None:
            raise InvalidScene(f"{where}.to: missing; expected the last angle (deg)")
        if self.axis not in AXES:
            raise InvalidScene(
                f"{where}.axis = {self.axis!r}: expected one of {', '.join(AXES)} (a horizontal body "
                "axis; turning about z is a slew, not a turnover)"
            )
        start, stop = finite(f"{where}.from", self.start), finite(f"{where}.to", self.stop)
        step = finite(f"{where}.step", self.step)
        if not step > 0.0:
            raise InvalidScene(f"{where}.step = {self.step!r}: expected a step > 0 deg")
        if abs(stop - start) / step > MOST_STEPS:
            raise InvalidScene(
                f"{where}.step = {step:g}: {abs(stop - start) / step:.0f} steps from {start:g} to "
                f"{stop:g} deg; expected at most {MOST_STEPS}"
            )
        for key, value in (("from", start), ("to", stop)):
            if abs(value) > 360.0:
                raise InvalidScene(f"{where}.{key} = {value:g}: expected an angle within +-360 deg")
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "stop", stop)
        object.__setattr__(self, "step", step)
        self._check_pivot(where)
        if self.plumb is not True:
            raise InvalidScene(
                f"{where}.plumb = {self.plumb!r}: only plumb hooks are modelled (each hook follows "
                "to keep its rope vertical); expected true"
            )
        if self.kind == "turnover" and self.pivot is not None:
            raise InvalidScene(
                f'{where}.pivot: a turnover hangs in the air; expected kind = "upend" for a body '
                "resting on a pivot"
            )
        supports = len(self.cranes) + (self.pivot is not None)
        if supports < SUPPORTS:
            held = f"{len(self.cranes)} crane(s)" + (" and the pivot" if self.pivot is not None else "")
            raise InvalidScene(
                f"{where}: held by {held}; expected two or more supports (cranes and the pivot): "
                "one cannot hold an angle"
            )

    def _check_pivot(self, where):
        if self.pivot is not None:
            object.__setattr__(self, "pivot", point(f"{where}.pivot", self.pivot))
        if self.friction is not None:
            mu = finite(f"{where}.friction", self.friction)
            if mu < 0.0:
                raise InvalidScene(f"{where}.friction = {self.friction!r}: expected a number >= 0")
            if self.pivot is None:
                raise InvalidScene(f"{where}.friction: given without a pivot; expected pivot = [x, y, z]")
            object.__setattr__(self, "friction", mu)

    def _check_move(self, where):
        """Refuse what a move stage does not model, each with its reason."""
        if self.stop is not None:
            raise InvalidScene(
                f"{where}.to: a move stage holds no turning angle (the body's pose follows from the "
                "hooks); expected each crane's end position in moves = [{crane, hoist, to}]"
            )
        self._check_pivot(where)
        if self.pivot is not None and any(m.to is not None for m in self.moves):
            raise InvalidScene(
                f"{where}.moves.to: a tip moved in plan inclines its rope and loads the pivot sideways; "
                "a move stage on a pivot models vertical ropes only (the pivot's friction and sliding "
                "are not modelled); expected hoist only"
            )
        if self.steps is None:
            object.__setattr__(self, "steps", MOVE_STEPS)
        if (
            isinstance(self.steps, bool)
            or not isinstance(self.steps, int)
            or not 1 <= self.steps <= MOST_STEPS
        ):
            raise InvalidScene(f"{where}.steps = {self.steps!r}: expected an integer from 1 to {MOST_STEPS}")
        if len(self.cranes) + (self.pivot is not None) < MOVE_CRANES:
            raise InvalidScene(
                f"{where}: held by {len(self.cranes)} crane(s)"
                + (" and the pivot" if self.pivot is not None else "")
                + f"; a move stage solves the body on elastic ropes, which needs {MOVE_CRANES} or more "
                "supports (cranes, and a pivot)"
            )
        if not self.moves:
            raise InvalidScene(f"{where}.moves: missing; expected one or more {{crane, hoist, to}}")
        named = [m.crane for m in self.moves]
        for key in named:
            if key not in self.cranes:
                raise InvalidScene(
                    f"{where}.moves.crane = {key!r}: not a crane of the stage; expected one of "
                    f"{name_list(self.cranes)}"
                )
            if named.count(key) > 1:
                raise InvalidScene(f"{where}.moves.crane = {key!r}: moved twice; expected each crane once")
        object.__setattr__(self, "step", 1.0 / self.steps)

    @property
    def where(self):
        """The stage's key in messages and results."""
        return self.name or "sequence"

    @property
    def angles(self):
        """The reported grid  [deg]: from ``start`` by ``step`` towards ``stop``, ``stop`` included;
        for a move stage, its parameter 0 to 1 in ``steps`` steps  [-]."""
        if self.kind == "move":
            return np.linspace(0.0, 1.0, self.steps + 1)
        span = self.stop - self.start
        if span == 0.0:
            return np.array([self.start])
        count = int(math.floor(abs(span) / self.step + 1e-9))
        grid = self.start + math.copysign(self.step, span) * np.arange(count + 1)
        if abs(grid[-1] - self.stop) > 1e-9 * max(1.0, abs(self.stop)):
            grid = np.append(grid, self.stop)
        else:
            grid[-1] = self.stop
        return grid

    @property
    def axis_vector(self):
        """The turning axis, a body unit vector."""
        return np.eye(3)[AXES.index(self.axis)]


@dataclass(frozen=True)
class Sequence:
    """A body turned by cranes through one or more stages, in the ``z-up`` frame.

    Parameters
    ----------
    body : Body
    lugs : tuple of Lug
    cranes : tuple of Crane
        Each on one lug (a vertical rope) or on a 2-leg sling (``sling``, legs of fixed
        length); each crane named by :func:`crane_key`.
    stages : tuple of Stage
    rules : Rules
        The design-load chain's settings, applied to each stage's maxima.
    name : str
    frame : str
        The file's frame; coordinates are reported back in it.
    """

    body: Body
    lugs: tuple[Lug, ...]
    cranes: tuple[Crane, ...]
    stages: tuple[Stage, ...]
    rules: Rules = field(default_factory=Rules)
    name: str = ""
    frame: str = "z-up"

    def __post_init__(self):
        lugs, cranes, stages = tuple(self.lugs), tuple(self.cranes), tuple(self.stages)
        object.__setattr__(self, "lugs", lugs)
        object.__setattr__(self, "cranes", cranes)
        object.__setattr__(self, "stages", stages)
        names = [lug.name for lug in lugs]
        if len(set(names)) != len(names):
            dup = next(n for n in names if names.count(n) > 1)
            raise InvalidScene(f"lugs.name = {dup!r}: duplicate, expected unique lug names")
        keys = []
        for crane in cranes:
            key = crane_key(crane)
            if key in keys:
                raise InvalidScene(f"cranes.name = {key!r}: names two cranes; expected unique crane names")
            keys.append(key)
            _check_crane(crane, names)
            if crane.sling is not None:
                check_sling_reach(crane, {lug.name: lug for lug in lugs})
        if not stages:
            raise InvalidScene("sequence: no stages; expected a [sequence] table or [[stages]]")
        by_name = {lug.name: lug for lug in lugs}
        for stage in stages:
            unknown = [c for c in stage.cranes if c not in keys]
            if unknown:
                raise InvalidScene(
                    f"{stage.where}.cranes = {unknown[0]!r}: no such crane, expected one of {name_list(keys)}"
                )
            if len(set(stage.cranes)) != len(stage.cranes):
                raise InvalidScene(f"{stage.where}.cranes: a crane named twice; expected each once")
            held = {}
            for key in stage.cranes:
                for lug in self.crane(key).lugs:
                    if lug in held:
                        raise InvalidScene(
                            f"{stage.where}: lug {lug!r} held by cranes {held[lug]} and {key} at once; "
                            "expected each lug on one crane in a stage"
                        )
                    held[lug] = key
            if stage.kind == "move":
                for key in stage.cranes:
                    check_move_crane(stage, self.crane(key), opens=stage is stages[0])
                continue
            if len(stage.cranes) + (stage.pivot is not None) >= ELASTIC_SUPPORTS:
                for key in stage.cranes:
                    check_elastic_crane(stage, self.crane(key))
            points = [np.mean([by_name[g].at for g in self.crane(k).lugs], axis=0) for k in stage.cranes]
            check_supports_plane(stage, points + ([np.array(stage.pivot)] if stage.pivot is not None else []))
        if not isinstance(self.rules, Rules):
            raise InvalidScene(f"rules = {self.rules!r}: expected a Rules")

    def crane(self, key):
        """The crane reported under ``key``."""
        for crane in self.cranes:
            if crane_key(crane) == key:
                return crane
        raise InvalidScene(f"crane {key!r}: no such crane")

    def lug(self, name):
        """The lug named ``name``."""
        for lug in self.lugs:
            if lug.name == name:
                return lug
        raise InvalidScene(f"lug {name!r}: no such lug")

    @property
    def crane_keys(self):
        return tuple(crane_key(c) for c in self.cranes)


def _check_crane(crane, names):
    where = f"cranes[{crane_key(crane)}]"
    for lug in crane.lugs:
        if lug not in names:
            raise InvalidScene(f"{where}: lug {lug!r} unknown, expected one of {name_list(names)}")
    if crane.sling is None:
        return
    sling = crane.sling
    if len(sling.legs) != 2 or sling.spreader is not None or sling.equalised:
        raise InvalidScene(
            f"{where}.sling: {len(sling.legs)} legs"
            + (", a spreader" if sling.spreader is not None else "")
            + (", equalised" if sling.equalised else "")
            + "; a sequence models 2-leg slings of fixed leg lengths (the hook's place is then the "
            "apex of the legs' triangle); expected two legs, no spreader, not equalised"
        )


def check_move_crane(stage, crane, opens=True):
    """Refuse a crane a move stage cannot hang on an elastic rope from its boom tip (``opens``:
    the stage opens the sequence, so its tips start where the file puts them)."""
    where = f"{stage.where}: cranes[{crane_key(crane)}]"
    if stage.pivot is not None and (crane.sling is not None or (opens and crane.tip is not None)):
        raise InvalidScene(
            f"{where}.{'sling' if crane.sling is not None else 'tip'}: on a pivot a move stage models "
            "vertical ropes only (an inclined rope or sling leg loads the pivot sideways; its friction "
            "and sliding are not modelled); expected one rope per lug under a boom_height"
        )
    if crane.sling is not None and any(leg.EA is None for leg in crane.sling.legs):
        raise InvalidScene(
            f"{where}.sling: a leg without EA or diameter; a move stage solves the sling's legs as "
            "elastic lines (the rigging model)"
        )
    missing = [k for k in ("rope_length", "EA") if getattr(crane, k) is None]
    if opens and crane.boom_height is None and crane.tip is None:
        missing.append("boom_height or tip")
    if missing:
        raise InvalidScene(
            f"{where}: {', '.join(missing)} missing; a move stage starts from each crane's boom tip "
            "and solves the body on its elastic ropes"
        )


def check_elastic_crane(stage, crane):
    """Refuse a crane of a turning stage on four or more supports that gives no rope stiffness."""
    missing = [k for k in ("rope_length", "EA") if getattr(crane, k) is None]
    if missing:
        raise InvalidScene(
            f"{stage.where}: cranes[{crane_key(crane)}]: {', '.join(missing)} missing; a stage on four "
            "or more supports shares the load by each rope's stiffness EA / rope_length"
        )


def check_sling_reach(crane, lugs):
    """Refuse a 2-leg sling whose legs cannot meet above its two lugs (``lugs``: name -> Lug)."""
    (a, b), (l1, l2) = crane.lugs, (leg.length for leg in crane.sling.legs)
    gap = math.dist(lugs[a].at, lugs[b].at)
    if not (abs(l1 - l2) < gap < l1 + l2):
        raise InvalidScene(
            f"cranes[{crane_key(crane)}].sling: legs {l1:g} m and {l2:g} m on lugs {gap:.4g} m apart "
            "cannot meet at a hook above both; expected |l1 - l2| < spacing < l1 + l2"
        )


#: Crane keys a scene file uses that a sequence does not: the hooks follow their lugs, so the
#: boom height, the rope's length and stiffness and a fixed tip position play no part.
UNUSED_CRANE_KEYS = ("boom_height", "rope_length", "EA", "tip")


def sequence_warnings(sequence):
    """One line per crane key a sequence reads but does not use (the hooks follow the lugs).

    Returns
    -------
    list of str
    """
    out = []
    first = sequence.stages[0]
    # a move that opens the sequence starts from the tips the file gives; a later one from
    # where the stage before left them
    moved = set(first.cranes) if first.kind == "move" else set()
    chained = {key for stage in sequence.stages[1:] if stage.kind == "move" for key in stage.cranes}
    shared = {  # a stage on four or more supports shares the load by the ropes' stiffness
        key
        for stage in sequence.stages
        if len(stage.cranes) + (stage.pivot is not None) >= ELASTIC_SUPPORTS
        for key in stage.cranes
    }
    for crane in sequence.cranes:
        if crane_key(crane) in moved:
            continue  # a move stage hangs it from its boom tip on its elastic rope: all used
        elastic = crane_key(crane) in shared or crane_key(crane) in chained
        unused = UNUSED_CRANE_KEYS if not elastic else ("boom_height", "tip")
        given = [key for key in unused if getattr(crane, key) is not None]
        if given and elastic:
            out.append(
                f"cranes[{crane_key(crane)}]: {', '.join(given)} not used by a sequence (its tip follows "
                "its lug in a turn, and a move after another stage starts where that stage left it)"
            )
        elif given:
            out.append(
                f"cranes[{crane_key(crane)}]: {', '.join(given)} not used by a sequence (each hook "
                "follows its lug or sling apex to keep its rope vertical; only swl is checked)"
            )
    return out


def check_supports_plane(stage, points):
    """Refuse three supports in one vertical plane at every angle of the turn.

    Parameters
    ----------
    stage : Stage
    points : list of array (3,)  [m]
        Each support's body point (a lug, a sling's lug midpoint, the pivot).
    """
    if len(points) < 3:
        return
    pts = np.asarray(points, dtype=float)
    across = AXES.index(stage.axis)  # the turning axis: its coordinate is the plan's other one
    along = 1 - across  # the horizontal body axis that turns (x for a turn about y)
    ones = np.ones(len(pts))
    size = max(float(np.ptp(pts, axis=0).max()), 1.0)

    def flat(column):  # the points on one line of (column, across): the smallest singular value
        rows = np.vstack([ones, pts[:, column] / size, pts[:, across] / size]).T
        return np.linalg.svd(rows, compute_uv=False)[-1] < 1e-9

    if flat(along) and flat(2):
        raise InvalidScene(
            f"{stage.where}: its {len(pts)} supports are in one vertical plane at every angle; the split "
            "between them is statically indeterminate; expected two of them (release the others) or "
            "one out of that plane"
        )


@dataclass(frozen=True)
class LugChoice:
    """A sequence whose lugs given ``on`` are to be placed on candidates.

    Parameters
    ----------
    parts : dict
        The :class:`Sequence`'s other fields (body, cranes, stages, rules, name, frame).
    fixed : tuple of Lug
        Lugs with their positions.
    open : tuple of (str, tuple of str)
        Each lug to place and the candidates it may go on.
    candidates : dict of str to Lug
        The candidates (as lugs named by the candidate: position, capacities, normal).
    """

    parts: dict
    fixed: tuple
    open: tuple
    candidates: dict

    def __post_init__(self):
        for name, options in self.open:
            if not options:
                raise InvalidScene(f"lugs[{name}].on = []: expected one or more candidates")
            unknown = [c for c in options if c not in self.candidates]
            if unknown:
                raise InvalidScene(
                    f"lugs[{name}].on = {unknown[0]!r}: no such candidate, expected one of "
                    f"{name_list(self.candidates)}"
                )

    def sequence(self, chosen):
        """The :class:`Sequence` with each open lug on its chosen candidate.

        Parameters
        ----------
        chosen : dict of str to str
            Open lug -> candidate.
        """
        placed = []
        for name, _ in self.open:
            spot = self.candidates[chosen[name]]
            placed.append(
                Lug(
                    name=name,
                    at=spot.at,
                    capacity=spot.capacity,
                    capacity_out_of_plane=spot.capacity_out_of_plane,
                    normal=spot.normal,
                )
            )
        return Sequence(lugs=self.fixed + tuple(placed), **self.parts)

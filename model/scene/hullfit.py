"""A parametric ship hull, and its fit to published particulars.

The form (:class:`HullForm`; body frame ``z-up``, origin on the design waterline at x = 0,
keel at z = -draft, deck at z = depth - draft):

* **Sections**: a box section with a round bilge of radius ``bilge`` (the midship section
  of a full ship: flat bottom, vertical sides), the same at every station, scaled in
  breadth by the waterline fining below.
* **Waterlines**: a parallel middle body between x = aft + run and x = fwd - entrance,
  fined towards the ends as b(u) = 1 - u^p (u from 0 where the parallel body ends to 1 at
  the end; p = ``run_power`` aft, ``entrance_power`` forward: p = 2 is a parabolic
  waterline, larger p a fuller one). Wall-sided above the waterline.
* **Profile**: the run (the stern's end and the aft fining with it) moves forward by
  ``cutup`` x s^2 at depth fraction s below the waterline: a stern cut away under a full
  waterline, which puts the centre of buoyancy forward of the centre of flotation, as on
  a full ship. The stem is vertical.

:func:`hull_triangles` meshes it as a closed, outward-wound triangle mesh (a few thousand
triangles) with a vertex level at the design waterline, so the particulars the fit sees
are those of the mesh itself; :func:`write_stl` writes it for ``[hull] mesh``.
:func:`fitted_hull` fits the free form parameters by least squares (Levenberg-Marquardt
in numpy, finite-difference Jacobian) to :class:`Particulars`: waterline length, beam,
volume, centre of buoyancy, waterplane area, its centre, I_T and I_L at the design draft.
The draft and depth are always held; the beam is held unless ``free_beam``.

A box is the form's limit (no bilge, no fining, no cutup): :meth:`HullForm.box`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.extras import require

# mesh resolution: points along each fined end, along the parallel body, levels in the
# bilge and between the bilge and the waterline (about 3 000 triangles)
END_POINTS = 18
MIDDLE_POINTS = 8
BILGE_LEVELS = 5
SIDE_LEVELS = 6
# the fit's stopping test: relative change of the weighted squared residual
FIT_TOL = 1e-12
FIT_MAX_ITER = 200
# a fined end shorter than this fraction of the length is meshed square (a transom): its
# points would otherwise merge when the mesh is written in single precision (STL)
SQUARE_END = 1e-4


def _positive(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{name} = {value!r}: expected a number > 0") from None
    if not (math.isfinite(value) and value > 0.0):
        raise InvalidScene(f"{name} = {value!r}: expected a finite number > 0")
    return value


def _finite(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{name} = {value!r}: expected a number") from None
    if not math.isfinite(value):
        raise InvalidScene(f"{name} = {value!r}: expected a finite number")
    return value


@dataclass(frozen=True)
class HullForm:
    """The parametric hull (see the module text).

    Parameters
    ----------
    beam : float  [m]   greatest breadth B
    draft : float  [m]   design draft: keel at z = -draft
    depth : float  [m]   keel to deck: deck at z = depth - draft (> draft)
    aft, fwd : float  [m]   x of the waterline's ends (aft < 0 < fwd need not hold)
    run, entrance : float  [m]   lengths of the fined ends (0: a square end); run +
        entrance <= fwd - aft
    run_power, entrance_power : float  [-]   exponents p of the fined waterlines (>= 1)
    bilge : float  [m]   bilge radius, 0 <= bilge <= min(beam / 2, draft)
    cutup : float  [m]   how far forward the run (the stern's end and the aft fining) lies
        at the keel; 0 <= cutup <= the parallel body's length
    """

    beam: float
    draft: float
    depth: float
    aft: float
    fwd: float
    run: float = 0.0
    entrance: float = 0.0
    run_power: float = 2.0
    entrance_power: float = 2.0
    bilge: float = 0.0
    cutup: float = 0.0

    def __post_init__(self):
        for name in ("beam", "draft", "depth"):
            object.__setattr__(self, name, _positive(f"hull form {name}", getattr(self, name)))
        for name in ("aft", "fwd", "run", "entrance", "run_power", "entrance_power", "bilge", "cutup"):
            object.__setattr__(self, name, _finite(f"hull form {name}", getattr(self, name)))
        if not self.depth > self.draft:
            raise InvalidScene(
                f"hull form depth = {self.depth:g} m: expected more than the draft "
                f"{self.draft:g} m (the deck above the waterline)"
            )
        length = self.fwd - self.aft
        if not length > 0.0:
            raise InvalidScene(f"hull form fwd = {self.fwd:g} m: expected forward of aft = {self.aft:g} m")
        for name in ("run", "entrance", "bilge", "cutup"):
            if getattr(self, name) < 0.0:
                raise InvalidScene(f"hull form {name} = {getattr(self, name):g} m: expected >= 0 m")
        if self.run + self.entrance > length:
            raise InvalidScene(
                f"hull form run + entrance = {self.run + self.entrance:g} m: expected at most "
                f"the waterline length {length:g} m"
            )
        for name in ("run_power", "entrance_power"):
            if getattr(self, name) < 1.0:
                raise InvalidScene(
                    f"hull form {name} = {getattr(self, name):g}: expected >= 1 (1: straight "
                    "waterlines to a point, 2: parabolic)"
                )
        if self.bilge > min(0.5 * self.beam, self.draft):
            raise InvalidScene(
                f"hull form bilge = {self.bilge:g} m: expected at most half the beam "
                f"{0.5 * self.beam:g} m and the draft {self.draft:g} m"
            )
        if self.run + self.cutup + self.entrance > length:
            raise InvalidScene(
                f"hull form cutup = {self.cutup:g} m: expected at most the parallel body's "
                f"length {length - self.run - self.entrance:g} m (the run stays aft of "
                "the entrance at the keel)"
            )

    @classmethod
    def box(cls, length, beam, draft, depth):
        """The box limit: x in [-L/2, L/2], no fining, no bilge  [m]."""
        return cls(beam=beam, draft=draft, depth=depth, aft=-0.5 * length, fwd=0.5 * length)

    @property
    def length(self):
        """Waterline length fwd - aft  [m]."""
        return self.fwd - self.aft


def _spacing(count):
    """count + 1 points in [0, 1], closer towards 1 (the fined end)."""
    return np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, count + 1))


def _levels(form, top):
    """Vertex heights z from the keel to ``top``, with one at the waterline (z = 0)."""
    t, r = form.draft, form.bilge
    z = [-t]
    if r > 0.0:
        angle = np.linspace(0.0, 0.5 * np.pi, BILGE_LEVELS + 1)[1:]
        z += list(-t + r - r * np.cos(angle))
    if z[-1] < 0.0:
        z += list(np.linspace(z[-1], 0.0, SIDE_LEVELS + 1)[1:])
    if top > 0.0:
        z.append(top)
    return np.array(z)


def _section(form, z):
    """Half-breadth of the midship section at height z  [m]."""
    b, r = 0.5 * form.beam, form.bilge
    below = -form.draft + r - z
    if r > 0.0 and below > 0.0:
        return b - r + math.sqrt(max(r * r - below * below, 0.0))
    return b


def _ends(form):
    """Run and entrance as meshed: below SQUARE_END of the length, square (0)  [m]."""
    short = SQUARE_END * form.length
    return (form.run if form.run >= short else 0.0), (form.entrance if form.entrance >= short else 0.0)


def _level_curve(form, z):
    """Port half of the waterline at height z: x and y of each point, stern end to stem."""
    depth_fraction = min(max(-z / form.draft, 0.0), 1.0)
    shift = form.cutup * depth_fraction**2  # the run moves forward bodily with depth
    run, entrance = _ends(form)
    stern, start, end = form.aft + shift, form.aft + run + shift, form.fwd - entrance
    half = _section(form, z)
    xs, ys = [], []
    if run > 0.0:
        u = _spacing(END_POINTS)[::-1]  # 1 at the stern's end -> 0 at the parallel body
        xs.append(start - u * (start - stern))
        ys.append(half * (1.0 - u**form.run_power))
    middle = np.linspace(start, end, MIDDLE_POINTS + 1)
    xs.append(middle[1:] if run > 0.0 else middle)
    ys.append(np.full(len(xs[-1]), half))
    if entrance > 0.0:
        u = _spacing(END_POINTS)[1:]
        xs.append(end + u * entrance)
        ys.append(half * (1.0 - u**form.entrance_power))
    return np.concatenate(xs), np.concatenate(ys)


def hull_triangles(form, top=None):
    """The closed, outward-wound triangle mesh of a :class:`HullForm`.

    Parameters
    ----------
    form : HullForm
    top : float, optional  [m]
        Cut the hull at this height (default the deck, z = depth - draft); ``top = 0``
        gives the part under the design waterline, closed by the waterplane.

    Returns
    -------
    numpy.ndarray, shape (m, 3, 3)  [m]
        Body frame; vertices counter-clockwise seen from outside. Ends that come to a
        point (fined) share their centre-line vertices between the sides; a square end
        (run or entrance 0) is closed by a flat transom.
    """
    top = form.depth - form.draft if top is None else top
    levels = _levels(form, top)
    rows = [_level_curve(form, z) for z in levels]
    x = np.array([r[0] for r in rows])
    y = np.array([r[1] for r in rows])
    z = np.repeat(levels[:, None], x.shape[1], axis=1)
    port = np.stack([x, y, z], axis=-1)  # (levels, points, 3)
    star = port * [1.0, -1.0, 1.0] + 0.0  # + 0.0: no -0.0 on the centre line
    tris = []

    def quad(a, b, c, d):
        # a -> b -> c -> d counter-clockwise seen from outside
        tris.append((a, b, c))
        tris.append((a, c, d))

    n_lev, n_pt = x.shape
    for j in range(n_lev - 1):
        for i in range(n_pt - 1):
            # port side (+y): outward normal +y; along +x then up is clockwise seen from +y
            quad(port[j, i], port[j + 1, i], port[j + 1, i + 1], port[j, i + 1])
            quad(star[j, i], star[j, i + 1], star[j + 1, i + 1], star[j + 1, i])
    for i in range(n_pt - 1):
        # bottom (normal -z) and deck (normal +z), across the centre line
        quad(port[0, i], port[0, i + 1], star[0, i + 1], star[0, i])
        quad(port[-1, i], star[-1, i], star[-1, i + 1], port[-1, i + 1])
    for j in range(n_lev - 1):
        for k, sign in ((0, -1.0), (n_pt - 1, 1.0)):
            if y[j, k] > 0.0 or y[j + 1, k] > 0.0:  # a flat end (transom or square bow)
                a, b, c, d = port[j, k], port[j + 1, k], star[j + 1, k], star[j, k]
                if sign > 0:
                    quad(a, b, c, d)
                else:
                    quad(a, d, c, b)
    out = np.array(tris, dtype=float)
    # drop the triangles with no area (the pointed ends' shared centre-line vertices)
    area = np.linalg.norm(np.cross(out[:, 1] - out[:, 0], out[:, 2] - out[:, 0]), axis=1)
    return out[area > 1e-12 * form.length**2]


@dataclass(frozen=True)
class Particulars:
    """Hydrostatic particulars at the design draft, upright (body frame; origin on the
    waterline, z up). Any may be None (left out of the fit).

    Parameters
    ----------
    length : float  [m]   waterline length
    beam : float  [m]   greatest breadth
    draft : float  [m]
    depth : float  [m]   keel to deck
    volume : float  [m3]   displaced volume
    lcb, vcb : float  [m]   centre of buoyancy x and z
    waterplane_area : float  [m2]
    lcf : float  [m]   centre of the waterplane area, x
    i_t, i_l : float  [m4]   waterplane second moments about axes through its centre
    """

    length: float | None = None
    beam: float | None = None
    draft: float | None = None
    depth: float | None = None
    volume: float | None = None
    lcb: float | None = None
    vcb: float | None = None
    waterplane_area: float | None = None
    lcf: float | None = None
    i_t: float | None = None
    i_l: float | None = None

    def __post_init__(self):
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            if f.name in ("lcb", "vcb", "lcf"):
                object.__setattr__(self, f.name, _finite(f"particulars.{f.name}", value))
            else:
                object.__setattr__(self, f.name, _positive(f"particulars.{f.name}", value))

    def known(self):
        """The given particulars, name -> value."""
        return {
            f.name: getattr(self, f.name)
            for f in dataclasses.fields(self)
            if getattr(self, f.name) is not None
        }


def particulars(form):
    """The :class:`Particulars` of a form's mesh at its design draft (numpy, exact for the
    mesh: closed-mesh sums under the waterline and Green's theorem on the waterplane)."""
    under = hull_triangles(form, top=0.0)
    a, b, c = under[:, 0], under[:, 1], under[:, 2]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    volume = float(vol.sum())
    centre = (vol[:, None] * (a + b + c) / 4.0).sum(axis=0) / volume
    x, y = _level_curve(form, 0.0)
    # the waterplane polygon, counter-clockwise seen from above: starboard stern -> stem, port back
    px = np.concatenate([x, x[::-1]])
    py = np.concatenate([-y, y[::-1]])
    qx, qy = np.roll(px, -1), np.roll(py, -1)
    cross = px * qy - qx * py
    area = cross.sum() / 2.0
    xf = ((px + qx) * cross).sum() / (6.0 * area)
    ixx = ((px * px + px * qx + qx * qx) * cross).sum() / 12.0  # int x^2 dA
    iyy = ((py * py + py * qy + qy * qy) * cross).sum() / 12.0  # int y^2 dA
    return Particulars(
        length=form.length,
        beam=form.beam,
        draft=form.draft,
        depth=form.depth,
        volume=volume,
        lcb=float(centre[0]),
        vcb=float(centre[2]),
        waterplane_area=float(area),
        lcf=float(xf),
        i_t=float(iyy),
        i_l=float(ixx - area * xf * xf),
    )


def _scales(target):
    """What each particular's residual is divided by: itself, or the length (lcb, lcf) or
    the draft (vcb) for positions."""
    return {
        "lcb": target.length,
        "lcf": target.length,
        "vcb": target.draft,
    }


def residuals(form, target):
    """Relative residual of each given particular: (form's - target) / scale  [-].

    Parameters
    ----------
    form : HullForm
    target : Particulars

    Returns
    -------
    dict of str to float
    """
    got = particulars(form)
    scales = _scales(target)
    return {
        name: (getattr(got, name) - value) / (scales.get(name) or abs(value))
        for name, value in target.known().items()
        if name not in ("draft", "depth")
    }


# free parameters of the fit, each mapped from an unbounded number
def _unpack(theta, target, beam):
    length = target.length
    span = length * math.exp(theta[1])
    aft = -0.5 * span + length * theta[0]
    run_frac, ent_frac = _logistic(theta[2]), _logistic(theta[3])
    run, entrance = run_frac * 0.5 * span, ent_frac * 0.5 * span
    beam = beam if beam is not None else math.exp(theta[8]) * target.beam
    bilge = _logistic(theta[6]) * min(0.5 * beam, target.draft)
    return HullForm(
        beam=beam,
        draft=target.draft,
        depth=target.depth,
        aft=aft,
        fwd=aft + span,
        run=run,
        entrance=entrance,
        run_power=1.0 + math.exp(theta[4]),
        entrance_power=1.0 + math.exp(theta[5]),
        bilge=bilge,
        cutup=_logistic(theta[7]) * (span - run - entrance),
    )


def _logistic(v):
    return 1.0 / (1.0 + math.exp(-v))


@dataclass(frozen=True)
class HullFit:
    """A fitted hull.

    Parameters
    ----------
    form : HullForm
    target : Particulars
    achieved : Particulars
        The fitted mesh's own particulars.
    residuals : dict of str to float  [-]
        (achieved - target) / scale per given particular (scale: the particular itself;
        the length for lcb and lcf, the draft for vcb).
    iterations : int
    converged : bool
        The least-squares iteration met its stopping test (it may still leave residuals
        where the particulars contradict each other or the form).
    """

    form: HullForm
    target: Particulars
    achieved: Particulars
    residuals: dict
    iterations: int
    converged: bool

    def triangles(self):
        """The fitted mesh (:func:`hull_triangles`)."""
        return hull_triangles(self.form)


def fitted_hull(target, free_beam=False, weights=None):
    """Fit the :class:`HullForm` to published particulars by least squares.

    Parameters
    ----------
    target : Particulars
        Needs ``length``, ``beam``, ``draft``, ``depth`` and ``volume``; the others enter
        the fit when given.
    free_beam : bool
        Fit the beam too (its residual is then one of the squares); by default the form's
        beam is the given one exactly.
    weights : dict of str to float, optional
        Weight of each particular's relative residual (default 1 each).

    Returns
    -------
    HullFit

    Raises
    ------
    InvalidScene
        A needed particular is missing, or a weight is not a number >= 0.
    """
    if not isinstance(target, Particulars):
        raise InvalidScene(f"target = {target!r}: expected Particulars")
    for name in ("length", "beam", "draft", "depth", "volume"):
        if getattr(target, name) is None:
            raise InvalidScene(f"particulars.{name}: missing; expected it for the fit (m or m3)")
    block = target.volume / (target.length * target.beam * target.draft)
    if not block < 1.0:
        raise InvalidScene(
            f"particulars.volume = {target.volume:g} m3: more than the box L x B x T "
            f"({target.length * target.beam * target.draft:g} m3); expected a block "
            "coefficient below 1"
        )
    weights = dict(weights or {})
    for name, value in weights.items():
        if name not in target.known():
            raise InvalidScene(
                f"weights[{name!r}]: not a given particular; expected one of {', '.join(target.known())}"
            )
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0.0):
            raise InvalidScene(f"weights[{name!r}] = {value!r}: expected a number >= 0")
    beam = None if free_beam else target.beam
    names = [
        n for n in residuals(HullForm.box(target.length, target.beam, target.draft, target.depth), target)
    ]
    w = np.array([weights.get(n, 1.0) for n in names])

    def vector(theta):
        res = residuals(_unpack(theta, target, beam), target)
        return w * np.array([res[n] for n in names])

    # start: the box's length, ends fined over a sixth each, a bilge of a tenth of the draft
    theta = np.array([0.0, 0.0, -1.0, -1.0, 0.0, 0.0, -2.0, -1.0, 0.0])
    if beam is not None:
        theta = theta[:8]
    theta, iterations, converged = _levenberg_marquardt(vector, theta)
    form = _unpack(theta, target, beam)
    return HullFit(
        form=form,
        target=target,
        achieved=particulars(form),
        residuals=residuals(form, target),
        iterations=iterations,
        converged=converged,
    )


def _levenberg_marquardt(fun, theta):
    """Minimise |fun(theta)|^2: Levenberg-Marquardt, forward-difference Jacobian."""
    r = fun(theta)
    cost = float(r @ r)
    damping = 1e-3
    for iteration in range(1, FIT_MAX_ITER + 1):
        jac = np.empty((len(r), len(theta)))
        for k in range(len(theta)):
            step = 1e-7 * max(1.0, abs(theta[k]))
            shifted = theta.copy()
            shifted[k] += step
            jac[:, k] = (fun(shifted) - r) / step
        grad = jac.T @ r
        normal = jac.T @ jac
        while True:
            try:
                delta = np.linalg.solve(normal + damping * np.diag(np.diag(normal) + 1e-12), -grad)
                trial = theta + delta
                r_trial = fun(trial)
                cost_trial = float(r_trial @ r_trial)
            except (InvalidScene, OverflowError, np.linalg.LinAlgError):
                cost_trial = math.inf
            if cost_trial < cost:
                break
            damping *= 10.0
            if damping > 1e12:
                return theta, iteration, True  # no step lowers the cost: a (local) minimum
        drop = (cost - cost_trial) / max(cost, 1e-300)
        theta, r, cost = trial, r_trial, cost_trial
        damping = max(damping / 10.0, 1e-12)
        if drop < FIT_TOL or cost < 1e-28:
            return theta, iteration, True
    return theta, FIT_MAX_ITER, False


def write_stl(triangles, path, binary=True):
    """Write a closed mesh as STL (binary by default) with trimesh.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    path : str or pathlib.Path
    """
    trimesh = require("mesh", "trimesh", what=f"writing {str(path)!r}")
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(np.asarray(triangles, dtype=float)))
    mesh.export(str(path), file_type="stl" if binary else "stl_ascii")

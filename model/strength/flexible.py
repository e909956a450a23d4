"""The flexible hull: the body as an elastic beam on the elastic ropes.

With ``[hull] EI`` (and optionally ``GJ``) the ``elastic`` model's Newton system gains the
hull girder's deflections as unknowns (:class:`liftplan.model.strength.flexible_model.FlexibleRopeModel`,
elements from :mod:`.beam`): the ropes' tensions then follow the hull's compliance as well as
their own. :func:`flexible_state` solves it from a start pose; :func:`choose_hull` is the
least-model rule of :func:`liftplan.model.solve.solve`: the rigid hull unless flexibility
changes a tension by more than :data:`TENSION_CHANGE`, measured by solving both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.statics.acceptance import RESIDUAL_TOL, schur_positive_definite
from liftplan.model.strength.beam import ELEMENTS, girder_mesh
from liftplan.model.strength.flexible_model import flexible_model
from liftplan.model.strength.piecewise import Extreme

#: Deflections beyond this fraction of the hull's length leave small-deflection beam theory
#: (equilibrium on the undeformed geometry, plane sections): said in the result's reason.
#: A hull girder's service deflection is ~1/1000 of its length.
SMALL_DEFLECTION = 0.01

#: ``solve`` keeps the rigid hull when flexibility changes no tension by more than this
#: fraction of the rigid tension (the issue's 1 %).
TENSION_CHANGE = 0.01


@dataclass(frozen=True)
class FlexibleHull:
    """What the flexible hull did in one solve.

    Parameters
    ----------
    used : str
        ``"flexible"`` or ``"rigid"``: the hull whose tensions the result carries.
    reason : str
        Why (one clause, with the measured change).
    x : numpy.ndarray  [m]
        Beam nodes along the body's x.
    deflection : numpy.ndarray  [m]
        Deflection at the nodes from the chord through the hull's ends, > 0 up (body z).
    twist : numpy.ndarray or None  [deg]
        Twist of each section about the body's x (> 0 as heel), None when rigid in torsion.
    rigid_tensions, flexible_tensions : dict of str to float  [t]
    max_change : float  [-]
        Largest |T_flexible - T_rigid| / T_rigid over the ropes.
    max_change_rope : str
    max_deflection : Extreme  [m]
    small_deflection : bool
        The largest deflection is within :data:`SMALL_DEFLECTION` of the length (the beam
        theory's range).
    rigid_ground_reaction, flexible_ground_reaction : float or None  [t]
        Grounded in water: the ground reaction of each hull (None otherwise).
    buoyancy : tuple of Piecewise or None
        In water: buoyancy per length [t/m] and its first moment about body z = 0 [t m/m] of
        the deflected hull (:func:`.girder.hull_girder` takes them when the flexible hull is
        used).
    """

    used: str
    reason: str
    x: np.ndarray
    deflection: np.ndarray
    twist: np.ndarray | None
    rigid_tensions: dict
    flexible_tensions: dict
    max_change: float
    max_change_rope: str
    max_deflection: Extreme
    small_deflection: bool = True
    rigid_ground_reaction: float | None = None
    flexible_ground_reaction: float | None = None
    buoyancy: tuple | None = None

    def to_json(self):
        """The ``"flexible_hull"`` block of ``solve --json`` (m, deg, t)."""
        return {
            "used": self.used,
            "reason": self.reason,
            "threshold": TENSION_CHANGE,
            # a change from zero (slack rope, or no ground reaction, in the rigid hull) has no
            # ratio: null, so the JSON stays strict (the reason says it in words)
            "max_tension_change": self.max_change if np.isfinite(self.max_change) else None,
            "max_tension_change_rope": self.max_change_rope,
            "rigid_tensions": dict(self.rigid_tensions),
            "flexible_tensions": dict(self.flexible_tensions),
            "deflection": {"x": self.x.tolist(), "w": self.deflection.tolist()},
            "twist": None if self.twist is None else {"x": self.x.tolist(), "deg": self.twist.tolist()},
            "max_deflection": self.max_deflection.to_json(),
            "small_deflection": self.small_deflection,
            "rigid_ground_reaction": self.rigid_ground_reaction,
            "flexible_ground_reaction": self.flexible_ground_reaction,
        }

    def lines(self):
        """Console lines: which hull, the change, the deflection."""
        peak = self.max_deflection
        out = [
            f"hull: {self.used} ({self.reason})",
            f"hull deflection from the chord through its ends: {1000 * peak.signed:+.1f} mm at "
            f"x = {peak.x:.1f} m ({'sagging' if peak.signed < 0 else 'hogging'})",
        ]
        if self.flexible_ground_reaction is not None:
            out.append(
                f"ground reaction: {self.flexible_ground_reaction:.2f} t flexible, "
                f"{self.rigid_ground_reaction:.2f} t rigid"
            )
        if self.twist is not None:
            k = int(np.argmax(np.abs(self.twist)))
            out.append(f"hull twist: {self.twist[k]:+.4f} deg at x = {self.x[k]:.1f} m")
        return out


@dataclass(frozen=True)
class FlexibleState:
    """A solved flexible state (arrays; :func:`liftplan.model.solve.solve` builds the result).

    Parameters
    ----------
    x : numpy.ndarray, shape (3,)  [m, rad, rad]
        Lift height, heel and trim of the chord.
    beam : numpy.ndarray  [m, rad]
        Free beam unknowns (:meth:`.beam.GirderMesh.full`).
    tensions, stretch : numpy.ndarray  [t, m]
    statics : numpy.ndarray, shape (3,)  [t, t m, t m]
        A T - b.
    beam_residual : float  [-]
        Largest beam equilibrium residual over W (moments over W L).
    stable : bool
        The energy Hessian's Schur complement on the pose is positive definite.
    mesh : GirderMesh
    """

    x: np.ndarray
    beam: np.ndarray
    tensions: np.ndarray
    stretch: np.ndarray
    statics: np.ndarray
    beam_residual: float
    stable: bool
    mesh: object

    @property
    def accepted(self):
        """Beam equilibrium within the tolerance, stable (the statics are judged by solve)."""
        return bool(self.beam_residual <= RESIDUAL_TOL and self.stable)


def beam_parameters(mesh, n):
    """The flat beam parameter vector of :class:`~liftplan.model.strength.flexible_model.BeamLayout`."""
    parts = [np.transpose(mesh.bending, (0, 2, 1)).ravel()]  # each 4 x 4 column-major
    if mesh.torsion is not None:
        parts.append(mesh.torsion)
    parts.append(mesh.weight)
    parts.append(mesh.selection().ravel(order="F"))
    return np.concatenate(parts)


def flexible_state(scene, p, x_start, elements=ELEMENTS):
    """Solve the flexible hull on its elastic ropes from a start pose.

    Parameters
    ----------
    scene : Scene
        With ``girder`` and ``body.weight_curve``.
    p : numpy.ndarray
        The rope model's parameters (:func:`liftplan.model.statics.vertical.pack_params`, ``elastic``).
    x_start : array_like, shape (3,)  [m, rad, rad]
        Start pose (the rigid hull's).
    elements : int
        At least this many beam elements over the length.

    Returns
    -------
    FlexibleState
    """
    mesh = girder_mesh(scene, elements)
    model = flexible_model(scene.n, mesh.m, mesh.torsion is not None)
    q = beam_parameters(mesh, scene.n)
    z0 = np.concatenate([np.asarray(x_start, dtype=float), np.zeros(model.beam.free)])
    z = np.asarray(model.solver(z0, p, q)).ravel()
    tensions, stretch, statics, residual, hess = (np.asarray(v) for v in model.evaluate(z, p, q))
    residual = residual.ravel()
    beam_residual = float(np.max(np.abs(residual[3:]))) if residual.size > 3 else 0.0
    if not np.isfinite(beam_residual):
        beam_residual = np.inf
    return FlexibleState(
        x=z[:3],
        beam=z[3:],
        tensions=tensions.ravel(),
        stretch=stretch.ravel(),
        statics=statics.ravel(),
        beam_residual=beam_residual,
        stable=schur_positive_definite(hess, 3),
        mesh=mesh,
    )


def hull_report(scene, mesh, state, rigid, used, forced, ground=None, buoyancy=None, note=""):
    """The :class:`FlexibleHull` of a solve: the change flexibility makes, and which hull.

    Parameters
    ----------
    scene : Scene
    mesh : GirderMesh
    state : FlexibleState
    rigid : numpy.ndarray  [t]
        The rigid hull's tensions, in lug order.
    used : {"flexible", "rigid"}
    forced : bool
        ``analysis.hull`` chose it (not the 1 % rule).
    ground : tuple of 2 float, optional  [t]
        Grounded: the rigid and the flexible hull's ground reaction; its change counts as a
        tension's.
    buoyancy : tuple of Piecewise, optional
        In water: the deflected hull's buoyancy curves (:attr:`FlexibleHull.buoyancy`).
    note : str
        Appended to the reason.
    """
    names = list(scene.lug_names)
    change = tension_change(rigid, state.tensions, scene.body.weight)
    if ground is not None:
        names.append("the ground reaction")
        change = np.append(change, tension_change([ground[0]], [ground[1]], scene.body.weight))
    if not names:  # afloat without ropes: nothing the rule measures
        names, change = ["nothing (no rope, no ground contact)"], np.zeros(1)
    k = int(np.argmax(change))
    flexible_values = list(state.tensions) + ([] if ground is None else [ground[1]])
    by = f"by {_percent(change[k])}" if np.isfinite(change[k]) else f"from 0 t to {flexible_values[k]:.4g} t"
    w, _, twist = mesh.full(state.beam)
    peak = int(np.argmax(np.abs(w)))
    span = float(mesh.x[-1] - mesh.x[0])
    small = bool(abs(w[peak]) <= SMALL_DEFLECTION * span)
    if forced:
        reason = f'analysis.hull = "{used}"; flexibility changes {names[k]} {by}'
    elif used == "flexible":
        reason = (
            f"flexibility changes {names[k]} {by}, more than "
            f"{_percent(TENSION_CHANGE)}: the flexible hull is used"
        )
    else:
        what = "tension or ground reaction" if ground is not None else "tension"
        reason = (
            f"flexibility changes no {what} by more than {_percent(TENSION_CHANGE)} (at most "
            f"{_percent(change[k])}, {names[k]}): the rigid hull is used"
        )
    if note:
        reason += f"; {note}"
    if not small:
        reason += (
            f"; the deflection {abs(w[peak]):.3g} m exceeds {SMALL_DEFLECTION:g} x the length: "
            "beyond small-deflection beam theory, check the stiffness"
        )
    return FlexibleHull(
        used=used,
        reason=reason,
        small_deflection=small,
        x=mesh.x.copy(),
        deflection=w,
        twist=np.degrees(twist) if mesh.torsion is not None else None,
        rigid_tensions=dict(zip(scene.lug_names, map(float, rigid))),
        flexible_tensions=dict(zip(scene.lug_names, map(float, state.tensions))),
        max_change=float(change[k]),
        max_change_rope=names[k],
        max_deflection=Extreme(float(abs(w[peak])), float(mesh.x[peak]), float(w[peak])),
        rigid_ground_reaction=None if ground is None else float(ground[0]),
        flexible_ground_reaction=None if ground is None else float(ground[1]),
        buoyancy=buoyancy,
    )


def _percent(fraction):
    return f"{100 * fraction:.3g} %"


def tension_change(rigid, flexible, weight):
    """|T_flexible - T_rigid| / T_rigid per rope  [-].

    A rope slack in the rigid hull (T_rigid = 0) counts its whole flexible tension; changes
    below 1e-12 W are round-off and count as none."""
    rigid, flexible = np.asarray(rigid, dtype=float), np.asarray(flexible, dtype=float)
    diff = np.abs(flexible - rigid)
    diff = np.where(diff <= 1e-12 * weight, 0.0, diff)
    return np.divide(diff, rigid, out=np.where(diff > 0.0, np.inf, 0.0), where=rigid > 0.0)


@dataclass(frozen=True)
class RigidHullNote:
    """Why a scene with a hull stiffness was solved with the hull rigid (no flexible solve).

    Parameters
    ----------
    reason : str
    """

    reason: str
    used: str = "rigid"

    def to_json(self):
        return {"used": self.used, "reason": self.reason}

    def lines(self):
        return [f"hull: {self.used} ({self.reason})"]

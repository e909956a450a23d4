"""The same scene in MoorPy (NREL's quasi-static mooring solver), the outside peer.

Ropes become MoorPy lines of negligible weight (1e-9 t/m, so their catenary is straight);
the body is a free body with heave, roll and pitch DOFs. Crane tips are put vertically above
the lugs' positions at the pose given, so the ropes are vertical there, as our model
assumes; MoorPy then finds the equilibrium on its own from a disturbed start. Units: t for
forces (MoorPy's N), m, with g = 9.80665 so that MoorPy's weight m g equals W.
"""

import math

import numpy as np

from liftplan.model import rotation_matrix

G = 9.80665
ROPE_WEIGHT = 1e-9  # t/m


def moorpy_solve(scene, heel, trim, lift, start_offset=(0.05, 0.002, -0.002)):
    """Solve in MoorPy; returns (tensions at the lugs [t], lug world heights [m]).

    The crane tips are put above the lugs at the pose given, written in MoorPy's own
    angles: MoorPy's attitude is Rz(yaw) Ry(pitch) Rx(roll) with yaw held (its DOFs here are
    heave, roll, pitch), ours Rx(heel) Ry(trim). The two differ by a turn about the
    vertical, which changes no tension of vertical ropes, but moves the lugs away from
    under fixed tips: the pose is therefore turned to MoorPy's yaw 0 first (a difference
    of ~1e-3 W in the tensions at 20 deg heel and trim otherwise). MoorPy starts from its
    roll and pitch there plus ``start_offset`` (heave m, roll rad, pitch rad).
    """
    import moorpy as mp

    rot = rotation_matrix(heel, trim)
    yaw = math.atan2(rot[1, 0], rot[0, 0])
    turn = np.array(
        [[math.cos(yaw), math.sin(yaw), 0.0], [-math.sin(yaw), math.cos(yaw), 0.0], [0.0, 0.0, 1.0]]
    )
    rot = turn @ rot  # Ry(pitch) Rx(roll)
    roll, pitch = math.atan2(rot[2, 1], rot[2, 2]), -math.asin(rot[2, 0])
    lugs = scene.lug_points()
    world = lugs @ rot.T + np.array([0.0, 0.0, lift])
    system = mp.System(depth=1000.0, rho=0.0, g=G)
    body = system.addBody(
        0,
        np.array([0.0, 0.0, lift + start_offset[0], roll + start_offset[1], pitch + start_offset[2], 0.0]),
        m=scene.body.weight / G,
        v=0.0,
        rCG=np.array(scene.body.cog),
        DOFs=[2, 3, 4],
    )
    for i, crane in enumerate(scene.cranes):
        add_rope(system, i, crane, lugs[i], [world[i, 0], world[i, 1], crane.boom_height])
    system.initialize()
    if not system.solveEquilibrium(tol=1e-10, maxIter=500):
        raise RuntimeError("MoorPy did not converge")
    tensions = np.array([line.TA for line in system.lineList])
    heights = np.array([body.r6[2] + (rotation_of(body.r6) @ p)[2] for p in lugs])
    return tensions, heights


def add_rope(system, i, crane, lug_point, tip_point):
    """A weightless straight rope from a fixed tip (world) to a lug on body 1 (body frame)."""
    tip = system.addPoint(1, np.asarray(tip_point, dtype=float))
    lug = system.addPoint(1, np.asarray(lug_point, dtype=float), body=1)
    rope = dict(
        name=f"rope{i}",
        d_vol=0.01,
        w=ROPE_WEIGHT,
        m=ROPE_WEIGHT / G,
        EA=crane.EA,
        material="wire",
        d_nom=0.01,
        MBL=1e9,
        cost=0.0,
    )
    system.addLine(crane.rope_length, rope, pointA=lug.number, pointB=tip.number)


def rotation_of(r6):
    from moorpy.helpers import rotationMatrix

    return rotationMatrix(*r6[3:])


def moorpy_solve_6dof(scene, tips, start):
    """Six-DOF MoorPy solve with rope tips at world points.

    Parameters
    ----------
    tips : array (n, 3)  [m]
    start : array (6,)  (x, y, z [m], then MoorPy's roll, pitch, yaw [rad])

    Returns
    -------
    tensions [t], lug world positions (n, 3) [m]
    """
    import moorpy as mp

    lugs = scene.lug_points()
    system = mp.System(depth=1000.0, rho=0.0, g=G)
    body = system.addBody(
        0,
        np.asarray(start, dtype=float),
        m=scene.body.weight / G,
        v=0.0,
        rCG=np.array(scene.body.cog),
        DOFs=[0, 1, 2, 3, 4, 5],
    )
    for i, crane in enumerate(scene.cranes):
        add_rope(system, i, crane, lugs[i], tips[i])
    system.initialize()
    if not system.solveEquilibrium(tol=1e-10, maxIter=1000):
        raise RuntimeError("MoorPy did not converge")
    tensions = np.array([line.TA for line in system.lineList])
    world = np.array([body.r6[:3] + rotation_of(body.r6) @ p for p in lugs])
    return tensions, world


def moorpy_solve_rigging(scene, tips, hooks, start):
    """A body on sling sets in MoorPy: each crane's hook is a free point (type 0) hung from
    its tip by the hoist rope and joined to its lugs by the legs (no spreader bars: MoorPy's
    lines carry no compression).

    Parameters
    ----------
    tips : dict crane name -> (3,)  [m]
        World tip positions.
    hooks : dict crane name -> (3,)  [m]
        Start positions of the hooks (world).
    start : array (6,)
        Body start (x, y, z [m], MoorPy's roll, pitch, yaw [rad]).

    Returns
    -------
    hook loads {crane: t}, leg tensions {"CRANE/LUG": t}, hook positions {crane: (3,)}
    """
    import moorpy as mp

    lugs = dict(zip(scene.lug_names, scene.lug_points()))
    system = mp.System(depth=1000.0, rho=0.0, g=G)
    body = system.addBody(
        0,
        np.asarray(start, dtype=float),
        m=scene.body.weight / G,
        v=0.0,
        rCG=np.array(scene.body.cog),
        DOFs=[0, 1, 2, 3, 4, 5],
    )
    points, lines = {}, {}
    for crane in scene.cranes:
        tip = system.addPoint(1, np.asarray(tips[crane.name], dtype=float))
        hook = system.addPoint(0, np.asarray(hooks[crane.name], dtype=float))
        points[crane.name] = hook
        lines[crane.name] = _line(system, crane.rope_length, crane.EA, hook, tip)
        for leg in crane.sling.legs:
            lug = system.addPoint(1, lugs[leg.lug], body=1)
            lines[f"{crane.name}/{leg.lug}"] = _line(system, leg.length, leg.stiffness, lug, hook)
    system.initialize()
    if not system.solveEquilibrium(tol=1e-10, maxIter=2000):
        raise RuntimeError("MoorPy did not converge")
    del body
    tension = {key: line.TA for key, line in lines.items()}
    hook_loads = {c.name: tension.pop(c.name) for c in scene.cranes}
    return hook_loads, tension, {name: np.array(p.r) for name, p in points.items()}


def _line(system, length, ea, point_a, point_b):
    """A weightless straight line from point_a to point_b; returns the MoorPy line."""
    kind = dict(
        name=f"line{len(system.lineList)}",
        d_vol=0.01,
        w=ROPE_WEIGHT,
        m=ROPE_WEIGHT / G,
        EA=ea,
        material="wire",
        d_nom=0.01,
        MBL=1e9,
        cost=0.0,
    )
    system.addLine(length, kind, pointA=point_a.number, pointB=point_b.number)
    return system.lineList[-1]


def moorpy_angles(rot):
    """MoorPy's (roll, pitch, yaw) [rad] of an attitude matrix: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return (math.atan2(rot[2, 1], rot[2, 2]), -math.asin(rot[2, 0]), math.atan2(rot[1, 0], rot[0, 0]))

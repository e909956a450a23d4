"""The 3D view from Python: the figure of a plan, a solved scene or a load curve.

Example (in a notebook the figure shows itself)::

    from liftplan.model import load_scene, solve
    from liftplan.planner import view_figure, write_view

    scene = load_scene("examples/block_two_slings.toml")
    eq = solve(scene)
    fig = view_figure(eq, scene)          # a plotly Figure
    write_view(eq, "slings.html", scene)  # the stand-alone page (or .glb)
"""

from __future__ import annotations

from pathlib import Path

from liftplan.model.errors import InvalidScene
from liftplan.model.lift import LoadCurve
from liftplan.model.results import Equilibrium
from liftplan.planner.output.view.command import VIEW_TYPES, write
from liftplan.planner.output.view.figure import lift_figure
from liftplan.planner.output.view.states import lift_view, plan_view, scene_view


def view_of(result, scene=None):
    """The :class:`~liftplan.planner.output.view.geometry.LiftView` of a result.

    Parameters
    ----------
    result : LiftPlan, Equilibrium or LoadCurve
        A plan (its level state and worst case), a solved scene, or a load curve (its start,
        events, largest load and end).
    scene : Scene, optional
        The scene an Equilibrium or a LoadCurve is of (a plan carries its own).

    Returns
    -------
    LiftView
    """
    if isinstance(result, (Equilibrium, LoadCurve)):
        if scene is None:
            raise InvalidScene(f"view of a {type(result).__name__}: expected its scene too (scene=...)")
        return scene_view(scene, result) if isinstance(result, Equilibrium) else lift_view(scene, result)
    if hasattr(result, "kind") and hasattr(result, "problem"):
        return plan_view(result)
    raise InvalidScene(f"view of {type(result).__name__}: expected a plan, an Equilibrium or a LoadCurve")


def view_figure(result, scene=None):
    """The 3D view of a plan, a solved scene or a load curve as a plotly Figure.

    Parameters
    ----------
    result : LiftPlan, Equilibrium or LoadCurve
    scene : Scene, optional
        With an Equilibrium or a LoadCurve: the scene it is of.

    Returns
    -------
    plotly.graph_objects.Figure
        One group of traces per state and a slider between them (more than one state), plan
        and elevation buttons, a label toggle; ``fig.show()`` or a notebook cell displays it.
    """
    return lift_figure(view_of(result, scene))


def write_view(result, path, scene=None):
    """Write the 3D view of ``result`` as a stand-alone offline page (``.html``) or glTF (``.glb``).

    Parameters
    ----------
    result : LiftPlan, Equilibrium or LoadCurve
    path : str or os.PathLike
    scene : Scene, optional

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(path)
    if path.suffix.lower() not in VIEW_TYPES:
        raise InvalidScene(
            f"{path}: unknown file type {path.suffix or '(none)'!r}; expected one of .html, .glb"
        )
    write(view_of(result, scene), path)
    return path

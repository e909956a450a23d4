"""The 3D view as still images for print (matplotlib): one state from two viewpoints.

The same :class:`~.geometry.LiftView` as the interactive page, drawn with matplotlib's 3D axes
(the PDF cannot run the page's script): from above aft on the starboard quarter, and an
elevation from the side; the ropes in the page's colours, on the same colour bar.
"""

from __future__ import annotations

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from liftplan.planner.output.view.geometry import AXIS_TITLES, UP_AXIS, to_file_frame

#: The two viewpoints: (title, elevation, azimuth) [deg] of matplotlib's camera, for z-up.
VIEWPOINTS = (("3D view", 25.0, -135.0), ("elevation from the side (x to the right)", 0.0, -90.0))
#: Colour map of the ropes (matplotlib's name of plotly's "Turbo").
COLOUR_MAP = "turbo"


def _draw(ax, view, state, norm, cmap, elev, azim):
    frame = view.frame

    def f(points):
        return to_file_frame(np.asarray(points, dtype=float).reshape(-1, 3), frame)

    body = f(state.world(view.body.reshape(-1, 3))).reshape(-1, 3, 3)
    ax.add_collection3d(
        Poly3DCollection(body, facecolor="#9aa6b2", edgecolor="#7a8692", linewidths=0.1, alpha=0.45)
    )
    lower, upper = view.bounds()
    if view.water_level is not None:
        ax.add_collection3d(
            Poly3DCollection([f(_rectangle(view.water_level, lower, upper))], facecolor="#3a7bd5", alpha=0.15)
        )
    if view.seabed is not None:
        ax.add_collection3d(
            Poly3DCollection([f(_rectangle(view.seabed, lower, upper))], facecolor="#8b6d3f", alpha=0.2)
        )
    values = view.colour_values(state)
    segments = [f([r.lower, r.upper]) for r in state.ropes]
    colours = [cmap(norm(r.tension if v is None else v)) for r, v in zip(state.ropes, values)]
    ax.add_collection3d(Line3DCollection(segments, colors=colours, linewidths=1.6))
    names = list(view.lugs)
    lugs = f(state.world([view.lugs[n] for n in names]))
    chosen = np.array([n in view.labels for n in names])
    if (~chosen).any():
        ax.scatter(*lugs[~chosen].T, s=2, c="#555", depthshade=False)
    ax.scatter(*lugs[chosen].T, s=6, c="black", marker="s", depthshade=False)
    tips = list((state.tips or {}).items())
    centres = {c.name: c.centre for c in view.cranes}
    if tips:
        points = f([t for _, t in tips])
        ax.scatter(*points.T, s=10, c="#b5651d", marker="D", depthshade=False)
        booms = [f([(*centres[n], 0.0), t]) for n, t in tips if centres.get(n) is not None]
        if booms:
            ax.add_collection3d(Line3DCollection(booms, colors="#555", linewidths=2.0))
    if state.spreaders:
        ax.add_collection3d(
            Line3DCollection([f([a, b]) for _, a, b in state.spreaders], colors="#333", linewidths=2.5)
        )
    ax.scatter(*f(state.world([state.cog])).T, s=30, c="red", marker="+", depthshade=False)
    corners = f(np.array([lower, upper]))
    low, high = corners.min(axis=0), corners.max(axis=0)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_zlim(low[2], high[2])
    titles = AXIS_TITLES[frame]
    ax.set_xlabel(titles[0], labelpad=1, fontsize=6)
    ax.set_ylabel(titles[1], labelpad=1, fontsize=6)
    ax.set_zlabel(titles[2], labelpad=1, fontsize=6)
    ax.tick_params(labelsize=6, pad=0)
    # ticks by each axis's length: a long hull's short axes do not crowd their labels
    extent = np.ptp(f(np.array(view.bounds())), axis=0)
    for axis, length in zip((ax.xaxis, ax.yaxis, ax.zaxis), extent):
        axis.set_major_locator(MaxNLocator(max(2, int(6 * length / max(extent.max(), 1e-9)))))
    # with y vertical (choi) matplotlib's azimuth is turned a quarter from z-up's
    turn = 90.0 if frame == "choi" else 0.0
    ax.view_init(elev=elev, azim=azim + turn, vertical_axis="xyz"[UP_AXIS[frame]])
    # true to scale (set once the vertical axis is: before it, matplotlib took a y-up
    # file's aspect in the wrong order)
    ax.set_box_aspect(np.maximum(high - low, 1e-3 * float(np.max(high - low))), zoom=0.9)
    if elev == 0.0:  # an elevation: the axis towards the viewer has no ticks to read
        depth = ax.yaxis if frame == "z-up" else ax.zaxis
        depth.set_ticklabels([])
        depth.label.set_visible(False)


def _rectangle(height, lower, upper):
    (x0, y0), (x1, y1) = lower[:2], upper[:2]
    return np.array([[x0, y0, height], [x1, y0, height], [x1, y1, height], [x0, y1, height]])


def _elevation(ax, view, state, norm, cmap):
    """The side elevation on plain 2-D axes (x along, the file's up axis up), true to scale:
    the body's faces, ropes in their colours, booms, lugs, the CG, water and seabed."""
    frame = view.frame
    up = UP_AXIS[frame]

    def f(points):
        p = to_file_frame(np.asarray(points, dtype=float).reshape(-1, 3), frame)
        return p[:, [0, up]]

    body = f(state.world(view.body.reshape(-1, 3))).reshape(-1, 3, 2)
    ax.add_collection(PolyCollection(body, facecolor="#9aa6b2", edgecolor="none", alpha=0.25))
    lower, upper = view.bounds()
    span = f(np.array([lower, upper]))
    for level, colour in ((view.water_level, "#3a7bd5"), (view.seabed, "#8b6d3f")):
        if level is not None:
            height = f([[0.0, 0.0, level]])[0, 1]
            ax.axhline(height, color=colour, linewidth=0.8, alpha=0.7)
    values = view.colour_values(state)
    colours = [cmap(norm(r.tension if v is None else v)) for r, v in zip(state.ropes, values)]
    ax.add_collection(
        LineCollection([f([r.lower, r.upper]) for r in state.ropes], colors=colours, linewidths=1.4)
    )
    tips = list((state.tips or {}).items())
    centres = {c.name: c.centre for c in view.cranes}
    booms = [f([(*centres[n], 0.0), t]) for n, t in tips if centres.get(n) is not None]
    if booms:
        ax.add_collection(LineCollection(booms, colors="#555", linewidths=1.6))
    if tips:
        ax.scatter(*f([t for _, t in tips]).T, s=10, c="#b5651d", marker="D", zorder=3)
    if state.spreaders:
        ax.add_collection(
            LineCollection([f([a, b]) for _, a, b in state.spreaders], colors="#333", linewidths=2.2)
        )
    lugs = f(state.world([view.lugs[n] for n in view.labels if n in view.lugs]))
    ax.scatter(*lugs.T, s=8, c="black", marker="s", zorder=3)
    ax.scatter(*f(state.world([state.cog])).T, s=40, c="red", marker="+", zorder=4)
    ax.set_xlim(span[:, 0].min(), span[:, 0].max())
    ax.set_ylim(span[:, 1].min(), span[:, 1].max())
    ax.set_aspect("equal")
    titles = AXIS_TITLES[frame]
    ax.set_xlabel(titles[0], fontsize=7)
    ax.set_ylabel(titles[up], fontsize=7)
    ax.tick_params(labelsize=6)
    ax.grid(linewidth=0.3, alpha=0.5)


def stills(view, state=0, width_mm=170.0):
    """Two still views of one state of ``view``, one above the other, with the ropes' colour
    bar: a 3D view from above aft on the starboard quarter, and the side elevation to scale.

    Parameters
    ----------
    view : LiftView
    state : int
        Which state (0: the level one).
    width_mm : float
        The figure's width [mm] (the report's text width).

    Returns
    -------
    matplotlib.figure.Figure
    """
    shown = view.states[state]
    low, high = view.colour_range()
    norm, cmap = Normalize(low, high), colormaps[COLOUR_MAP]
    width = width_mm / 25.4
    # one above the other, each the text's width (side by side a long hull's elevation was a
    # strip too thin to read); the elevation on 2-D axes, to scale
    fig = Figure(figsize=(width, 0.85 * width))
    top = fig.add_axes((0.0, 0.4, 0.88, 0.54), projection="3d")
    _, elev, azim = VIEWPOINTS[0]
    _draw(top, view, shown, norm, cmap, elev, azim)
    side = fig.add_axes((0.08, 0.06, 0.78, 0.27))
    _elevation(side, view, shown, norm, cmap)
    side.set_title(VIEWPOINTS[1][0], fontsize=7)
    bar = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), cax=fig.add_axes((0.91, 0.1, 0.015, 0.75)))
    bar.set_label(view.colour_title, fontsize=7)
    bar.ax.tick_params(labelsize=6)
    fig.suptitle(f"{view.title}: {shown.name}", fontsize=8)
    return fig

"""The 3D view as a plotly figure: every state's traces, a slider between them, view buttons.

Each state is a group of traces (body, candidates, chosen lugs with their labels, ropes
coloured on one colour bar, hooks and boom tips, booms, spreader bars, the CG and its
envelope); the slider shows one group and hides the others (``restyle`` of ``visible``: the
page is not reloaded). The water surface, the seabed and the cranes' slew centres are drawn
once. Buttons turn the camera to a plan view, an elevation from the side and one from the end,
and the lug labels on and off (off by default past :data:`LABELS_SHOWN` lugs, where they
would pile up; the hover label names every lug, rope and crane).
"""

from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from liftplan.planner.output.view.geometry import AXIS_TITLES, UP_AXIS, to_file_frame

#: Lug labels are drawn by default up to this many chosen lugs (the button shows them always).
LABELS_SHOWN = 16
#: The colour scale of rope tension / utilisation (low blue, high red).
COLOUR_SCALE = "Turbo"
#: The camera's distance in the plan and elevation views (plotly's units: the scene's half size).
DISTANCE = 2.5
#: The longest side of the scene, plotly's units (its orthographic zoom): what fits the plot
#: in every view, the 3D view's diagonal included.
ZOOM = 1.6


def _xyz(points, frame):
    p = to_file_frame(np.asarray(points, dtype=float).reshape(-1, 3), frame)
    return p[:, 0], p[:, 1], p[:, 2]


def _segments(pairs, frame):
    """x, y, z of line segments, a None between each (one trace draws them all)."""
    xs, ys, zs = [], [], []
    for a, b in pairs:
        x, y, z = _xyz([a, b], frame)
        xs += [*x, None]
        ys += [*y, None]
        zs += [*z, None]
    return xs, ys, zs


def _mesh(triangles, frame, **kwargs):
    tris = np.asarray(triangles, dtype=float).reshape(-1, 3)
    x, y, z = _xyz(tris, frame)
    k = np.arange(len(tris)).reshape(-1, 3)
    return go.Mesh3d(x=x, y=y, z=z, i=k[:, 0], j=k[:, 1], k=k[:, 2], **kwargs)


def _plane(height, lower, upper, frame, name, colour):
    """A horizontal rectangle at world ``height`` over the plan extent [lower, upper]."""
    (x0, y0), (x1, y1) = lower[:2], upper[:2]
    corners = np.array([[x0, y0, height], [x1, y0, height], [x1, y1, height], [x0, y1, height]])
    tris = corners[[[0, 1, 2], [0, 2, 3]]]
    return _mesh(tris, frame, name=name, color=colour, opacity=0.25, hoverinfo="name", showlegend=True)


def _box_edges(lower, upper):
    lo, hi = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    corners = np.array(
        [[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    )
    edges = []
    for a in range(8):
        for b in range(a + 1, 8):
            if bin(a ^ b).count("1") == 1:
                edges.append((corners[a], corners[b]))
    return edges


def state_traces(view, state, visible, low, high, labels_on):
    """The traces of one state (list) and the index in it of its lug-label trace."""
    frame = view.frame
    traces = [
        _mesh(
            state.world(view.body.reshape(-1, 3)).reshape(-1, 3, 3),
            frame,
            name="body",
            color="#9aa6b2",
            opacity=0.35,
            flatshading=True,
            hoverinfo="name",
            visible=visible,
        )
    ]
    names = list(view.lugs)
    world = dict(zip(names, state.world([view.lugs[n] for n in names])))
    spare = [n for n in names if n not in view.labels]
    if spare:
        x, y, z = _xyz([world[n] for n in spare], frame)
        traces.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="markers",
                name="candidates",
                marker={"size": 2.5, "color": "#555"},
                hovertext=spare,
                hoverinfo="text",
                visible=visible,
            )
        )
    chosen = [n for n in names if n in view.labels]
    text = [view.labels[n] if view.labels[n] == n else f"{view.labels[n]} {n}" for n in chosen]
    x, y, z = _xyz([world[n] for n in chosen], frame)
    label_index = len(traces)
    traces.append(
        go.Scatter3d(
            x=x,
            y=y,
            z=z,
            mode="markers+text" if labels_on else "markers",
            name="lugs (chosen)",
            marker={"size": 4, "color": "black", "symbol": "square"},
            text=text,
            textposition="top center",
            textfont={"size": 10},
            hovertext=text,
            hoverinfo="text",
            visible=visible,
        )
    )
    values = view.colour_values(state)
    x, y, z = _segments([(r.lower, r.upper) for r in state.ropes], frame)
    colours, hover = [], []
    for rope, value in zip(state.ropes, values):
        shown = rope.tension if value is None else value
        colours += [shown, shown, shown]
        use = "" if rope.utilisation is None else f", utilisation {rope.utilisation:.3f}"
        words = f"{rope.key} ({rope.role}): {rope.tension:.2f} t{use}"
        hover += [words, words, None]
    traces.append(
        go.Scatter3d(
            x=x,
            y=y,
            z=z,
            mode="lines",
            name=f"ropes ({view.colour_title})",
            line={
                "width": 6,
                "color": colours,
                "colorscale": COLOUR_SCALE,
                "cmin": low,
                "cmax": high,
                "showscale": True,
                "colorbar": {"title": {"text": view.colour_title}, "len": 0.6},
            },
            hovertext=hover,
            hoverinfo="text",
            visible=visible,
        )
    )
    tips = state.tips or {}
    centres = {c.name: c.centre for c in view.cranes}
    if tips:
        x, y, z = _xyz(list(tips.values()), frame)
        traces.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="markers",
                name="boom tips / hooks",
                marker={"size": 4, "color": "#b5651d", "symbol": "diamond"},
                hovertext=[f"crane {n}" for n in tips],
                hoverinfo="text",
                visible=visible,
            )
        )
        booms = [((*centres[n], 0.0), tip) for n, tip in tips.items() if centres.get(n) is not None]
        if booms:
            x, y, z = _segments(booms, frame)
            traces.append(
                go.Scatter3d(
                    x=x,
                    y=y,
                    z=z,
                    mode="lines",
                    name="booms",
                    line={"width": 8, "color": "#555"},
                    hoverinfo="name",
                    visible=visible,
                )
            )
    hooks = [r.lower for r in state.ropes if r.role == "hoist"]
    if hooks:
        x, y, z = _xyz(hooks, frame)
        traces.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="markers",
                name="hooks",
                marker={"size": 5, "color": "#b5651d"},
                hovertext=[r.key for r in state.ropes if r.role == "hoist"],
                hoverinfo="text",
                visible=visible,
            )
        )
    if state.spreaders:
        x, y, z = _segments([(a, b) for _, a, b in state.spreaders], frame)
        traces.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="lines",
                name="spreader bars",
                line={"width": 10, "color": "#333"},
                hoverinfo="name",
                visible=visible,
            )
        )
    x, y, z = _xyz(state.world([state.cog]), frame)
    traces.append(
        go.Scatter3d(
            x=x,
            y=y,
            z=z,
            mode="markers",
            name="CG",
            marker={"size": 6, "color": "red", "symbol": "cross"},
            hovertext=["CG"],
            hoverinfo="text",
            visible=visible,
        )
    )
    if view.cog_box is not None:
        edges = [tuple(state.world([a, b])) for a, b in _box_edges(*view.cog_box)]
        x, y, z = _segments(edges, frame)
        traces.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="lines",
                name="CG envelope",
                line={"width": 2, "color": "red"},
                hoverinfo="name",
                visible=visible,
            )
        )
    return traces, label_index


def _camera(frame, direction):
    """A camera looking along ``direction`` ("plan", "side", "end", "3d") in the file's frame."""
    up = UP_AXIS[frame]
    eye = np.zeros(3)
    if direction == "plan":
        eye[up] = DISTANCE
        upvec = np.zeros(3)
        upvec[1 if up == 2 else 2] = 1.0 if up == 2 else -1.0  # plan: +y (port) up the screen
    else:
        upvec = np.zeros(3)
        upvec[up] = 1.0
        horizontal = 1 if up == 2 else 2  # the file's transverse axis
        if direction == "side":
            eye[horizontal] = -DISTANCE if up == 2 else DISTANCE  # from starboard
        elif direction == "end":
            eye[0] = -DISTANCE  # from aft
        else:
            eye[0], eye[horizontal], eye[up] = -1.7, (-1.7 if up == 2 else 1.7), 1.1
    # orthographic: in a plan view a tall rope does not lean out in perspective (and plotly
    # does not switch projections on a relayout: every view has the same one)
    projection = "orthographic"
    return {
        "eye": dict(zip("xyz", eye.tolist())),
        "up": dict(zip("xyz", upvec.tolist())),
        "center": {"x": 0, "y": 0, "z": 0},
        "projection": {"type": projection},
    }


def _aspect(low, high, zoom):
    """The scene's aspect ratio: true proportions, its longest side ``zoom`` (plotly's
    orthographic camera scales the picture by the aspect ratio, not by its distance)."""
    sides = np.asarray(high, dtype=float) - np.asarray(low, dtype=float)
    sides = np.maximum(sides, 1e-3 * float(sides.max())) / float(sides.max())
    return dict(zip("xyz", (zoom * sides).tolist()))


def lift_figure(view):
    """The plotly Figure of a :class:`~.geometry.LiftView` (shown in a notebook as it is).

    Returns
    -------
    plotly.graph_objects.Figure
    """
    frame = view.frame
    low, high = view.colour_range()
    lower, upper = view.bounds()
    pad = 0.1 * float(np.max(upper - lower))
    lower, upper = lower - pad, upper + pad
    corners = to_file_frame(np.array([lower, upper]), frame)
    shown_low, shown_high = corners.min(axis=0), corners.max(axis=0)
    fixed = []
    if view.water_level is not None:
        fixed.append(_plane(view.water_level, lower, upper, frame, "water level", "#3a7bd5"))
    if view.seabed is not None:
        fixed.append(_plane(view.seabed, lower, upper, frame, "seabed", "#8b6d3f"))
    slews = [c for c in view.cranes if c.centre is not None]
    if slews:
        x, y, z = _xyz([(*c.centre, 0.0) for c in slews], frame)
        fixed.append(
            go.Scatter3d(
                x=x,
                y=y,
                z=z,
                mode="markers",
                name="slew centres",
                marker={"size": 6, "color": "#e0a800", "symbol": "circle-open"},
                hovertext=[f"{c.name} slew centre" for c in slews],
                hoverinfo="text",
            )
        )
    labels_on = len(view.labels) <= LABELS_SHOWN
    groups, label_traces = [], []
    data = list(fixed)
    for k, state in enumerate(view.states):
        traces, label_index = state_traces(view, state, k == 0, low, high, labels_on)
        label_traces.append(len(data) + label_index)
        groups.append(range(len(data), len(data) + len(traces)))
        data += traces
    for trace in data[len(fixed) :]:
        trace.showlegend = False
    fig = go.Figure(data=data)
    titles = AXIS_TITLES[frame]
    fig.update_layout(
        title={"text": f"{view.title}<br><sub>{view.states[0].name}; body: {view.body_source}</sub>"},
        scene={
            **{
                f"{axis}axis": {"title": {"text": title}, "range": [float(lo), float(hi)]}
                for axis, title, lo, hi in zip("xyz", titles, shown_low, shown_high)
            },
            "aspectmode": "manual",
            "aspectratio": _aspect(shown_low, shown_high, ZOOM),
            "camera": _camera(frame, "3d"),
        },
        margin={"l": 0, "r": 0, "t": 60, "b": 50},
        legend={"x": 0.0, "y": 1.0},
        height=720,
        uirevision="liftplan",
        updatemenus=[
            {
                "type": "buttons",
                "direction": "right",
                "x": 0.0,
                "y": 0.0,
                "xanchor": "left",
                "yanchor": "top",
                "buttons": [
                    {
                        "label": label,
                        "method": "relayout",
                        # the camera only: a relayout of the aspect ratio too resets its up
                        # vector (plotly), turning a choi plan view upside down
                        "args": [{"scene.camera": _camera(frame, d)}],
                    }
                    for label, d in (
                        ("3D", "3d"),
                        ("plan view", "plan"),
                        ("elevation (side)", "side"),
                        ("elevation (end)", "end"),
                    )
                ],
            },
            {
                "type": "buttons",
                "direction": "right",
                "x": 1.0,
                "y": 0.0,
                "xanchor": "right",
                "yanchor": "top",
                "buttons": [
                    {
                        "label": "labels on",
                        "method": "restyle",
                        "args": [{"mode": "markers+text"}, label_traces],
                    },
                    {"label": "labels off", "method": "restyle", "args": [{"mode": "markers"}, label_traces]},
                ],
            },
        ],
    )
    if len(view.states) > 1:
        steps = []
        for k, state in enumerate(view.states):
            visible = [True] * len(fixed) + [False] * (len(data) - len(fixed))
            for i in groups[k]:
                visible[i] = True
            steps.append(
                {
                    "label": f"{k + 1}",
                    "method": "update",
                    "args": [
                        {"visible": visible},
                        {"title.text": f"{view.title}<br><sub>{state.name}; body: {view.body_source}</sub>"},
                    ],
                }
            )
        fig.update_layout(
            sliders=[
                {
                    "active": 0,
                    "currentvalue": {"prefix": "state "},
                    "pad": {"t": 50},
                    "steps": steps,
                }
            ]
        )
    return fig

"""``liftplan view FILE`` and the ``--view FILE`` option of ``solve``, ``plan`` and ``lift``.

Start-up: this module imports only the standard library and the path rule at the top (the
command line builds its parser from it on every run); plotly, the solvers and the planner are
imported when a view is drawn.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from liftplan.model.errors import InvalidScene
from liftplan.planner.output.paths import make_parent, output_file, replaced

#: What a view can be written as: a stand-alone HTML page, or binary glTF.
VIEW_TYPES = (".html", ".glb")


def add_parser(commands):
    """The ``view`` sub-command's parser, added to ``commands`` (argparse sub-parsers)."""
    cmd = commands.add_parser(
        "view", help="3D view of a scene, a planning file or a plan JSON, as one offline HTML page"
    )
    cmd.add_argument(
        "file",
        help="scene file (solved), planning file (planned: level and worst case) or plan.json "
        "written by plan --report (with plan_scene.toml beside it)",
    )
    cmd.add_argument(
        "--output",
        metavar="OUT",
        help="the file to write, .html (stand-alone page) or .glb (glTF); default: FILE's name "
        "with _view.html, in the current folder",
    )
    cmd.add_argument(
        "--lift", action="store_true", help="a scene file: the lift's load-curve states, as liftplan lift"
    )
    cmd.add_argument(
        "--no-open",
        action="store_true",
        help="do not open the page in a browser (opened only where a display is)",
    )
    return cmd


def add_view_option(parser):
    """``--view FILE`` on ``solve``, ``plan`` and ``lift``."""
    parser.add_argument(
        "--view",
        metavar="FILE",
        help="also write the 3D view, .html (stand-alone offline page) or .glb (glTF)",
    )


def checked(path, option="--view"):
    """The view file to write, checked before any computation (None when not asked for)."""
    return None if path is None else output_file(path, option, VIEW_TYPES)


def save_view(path, build, option="--view"):
    """Build the view (``build()`` -> LiftView) and write it to ``path``; the reason it could
    not be written, or None."""
    view = build()
    try:
        make_parent(path)
        with replaced(path) as temporary:  # whole or not at all
            write(view, temporary, path.suffix.lower())
    except OSError as err:  # a full disk, a folder removed meanwhile: the result still prints
        return f"{option} {path}: cannot write ({err.strerror or err})"
    print(f"liftplan: wrote {path}", file=sys.stderr)
    return None


def write(view, path, suffix=None):
    """Write ``view`` to ``path`` as HTML or glTF (by ``suffix``, default the path's)."""
    suffix = (suffix or Path(path).suffix).lower()
    if suffix == ".glb":
        from liftplan.planner.output.view.gltf import glb_bytes  # start-up: trimesh only here

        Path(path).write_bytes(glb_bytes(view))
    else:
        from liftplan.planner.output.view.page import page  # start-up: plotly only here

        Path(path).write_text(page(view), encoding="utf-8")


def run(args):
    """``liftplan view``: write the page (or glTF), open it where a display is; exit code."""
    source = Path(args.file)
    if not source.is_file():
        raise InvalidScene(f"{source}: no such file; expected a scene, a planning file or a plan JSON")
    out = checked(args.output or f"{source.stem}_view.html", "--output")
    if args.lift and source.suffix.lower() == ".json":
        raise InvalidScene(f"--lift with {source}: expected a scene file with [hull], [water] and cranes")
    # start-up: the solvers, the planner and plotly only when the command runs
    from liftplan.planner.output.view.load import load_view

    unwritten = save_view(out, lambda: load_view(source, lift=args.lift), "--output")
    if unwritten is not None:
        print(f"liftplan: error: {unwritten}", file=sys.stderr)
        return 2
    if not args.no_open and out.suffix.lower() == ".html" and has_display():
        import webbrowser

        webbrowser.open(out.resolve().as_uri())
    return 0


def has_display():
    """Whether a desktop can show a browser: macOS, Windows, or an X11 / Wayland display."""
    return sys.platform in ("darwin", "win32") or bool(
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    )

"""What ``liftplan view FILE`` draws: a scene file solved (or its load curve), a planning file
planned, or a plan JSON's ``plan_scene.toml`` solved."""

from __future__ import annotations

import dataclasses
import json
import tomllib
from pathlib import Path

from liftplan.model.errors import InvalidScene
from liftplan.model.lift import load_curve
from liftplan.model.scene.file import load_scene
from liftplan.model.solve import solve
from liftplan.planner.output.view import states
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem

#: The TOML tables that make a file a planning file rather than a scene.
PLANNING_TABLES = ("candidates", "plan")


def load_view(source, lift=False):
    """The LiftView of a scene file (solved, or its load curve with ``lift``), a planning file
    (planned) or a plan JSON (its ``plan_scene.toml`` solved)."""
    source = Path(source)
    if source.suffix.lower() == ".json":
        return _plan_json_view(source)
    if _is_planning(source):
        if lift:
            raise InvalidScene(f"--lift with {source}: a planning file; expected a scene file")
        return states.plan_view(plan(load_problem(source)))
    scene = load_scene(source)
    if lift:
        return states.lift_view(scene, load_curve(scene))
    return states.scene_view(scene, solve(scene))


def _is_planning(source):
    try:
        with open(source, "rb") as handle:
            data = tomllib.load(handle)
    except (OSError, tomllib.TOMLDecodeError):
        return False  # the scene reader says what is wrong with it
    return any(key in data for key in PLANNING_TABLES)


def _plan_json_view(source):
    """A plan JSON's level state: the ``plan_scene.toml`` written beside it solved, each rope
    keyed by the plan's lug label (``L1``, ...) as the JSON keys its tensions."""
    scene_file = source.with_name("plan_scene.toml")
    try:
        data = json.loads(source.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise InvalidScene(f"{source}: cannot read as JSON ({err}); expected a plan JSON") from None
    if not isinstance(data, dict) or not isinstance(data.get("lugs"), dict):
        raise InvalidScene(
            f'{source}: no "lugs" object; expected a plan JSON (liftplan plan --json or --report)'
        )
    if not scene_file.is_file():
        raise InvalidScene(
            f"{source}: no plan_scene.toml beside it; expected the folder liftplan plan --report wrote "
            "(a plan JSON alone holds no geometry: view the planning file instead)"
        )
    scene = load_scene(scene_file)
    view = states.scene_view(scene, solve(scene), title=f"{scene.name or 'plan'} ({source.name})")
    labels = {str(name): label for label, name in data["lugs"].items()}
    state = view.states[0]
    ropes = tuple(
        dataclasses.replace(r, key=labels[r.lug]) if r.lug in labels and r.role in ("rope", "leg") else r
        for r in state.ropes
    )
    level = dataclasses.replace(state, name="level (plan_scene.toml solved)", ropes=ropes)
    return dataclasses.replace(view, states=(level,), labels={n: labels.get(n, n) for n in view.lugs})

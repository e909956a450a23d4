"""Move stages of a lift sequence (issue 26): boom tips moved, the body on its elastic ropes.

Closed forms (equal hoists keep equal shares; three ropes are determinate whatever the hook
heights; four ropes shift load as the rope stiffness says), each state the same as
``liftplan solve`` of the same scene, a slack rope with its parameter range, and the maxima
against a 10 times finer grid.
"""

import dataclasses

import numpy as np
import pytest

from liftplan.model.errors import InvalidScene
from liftplan.model.sequence import loads_sequence, run_sequence
from liftplan.model.sequence.file import loads_lug_choice
from liftplan.model.sequence.lugplan import plan_lugs
from liftplan.model.sequence.move import MoveModel
from liftplan.model.sequence.objects import sequence_warnings
from liftplan.model.solve import solve

W = 100.0
EA, L0, H = 20000.0, 20.0, 21.05  # rope stiffness k = EA / l0 = 1000 t/m
CORNERS = {"A": (5.0, 3.0), "B": (-5.0, 3.0), "C": (-5.0, -3.0), "D": (5.0, -3.0)}


def move_text(moves, lugs="ABCD", cog=(0.0, 0.0, 0.0), tips=None, steps=4):
    """A box whose lugs are at the corners in the plane of its CG, one crane per lug."""
    text = f"[body]\nweight = {W}\ncog = {list(cog)}\n"
    for name in lugs:
        x, y = CORNERS[name]
        text += f'\n[[lugs]]\nname = "{name}"\nat = [{x}, {y}, 0.0]\n'
    for name in lugs:
        where = f"tip = {list(tips[name])}" if tips else f"boom_height = {H}"
        text += f'\n[[cranes]]\nname = "{name}"\nlug = "{name}"\nEA = {EA}\nrope_length = {L0}\n{where}\n'
    return text + f'\n[sequence]\nkind = "move"\nsteps = {steps}\nmoves = [{", ".join(moves)}]\n'


def model_of(text):
    seq = loads_sequence(text)
    return seq, MoveModel(seq, seq.stages[0])


def raised(model, s, hoists):
    """The stage's scene at its start with the boom heights raised by hand, solved."""
    scene = model.scene
    for lug, rise in hoists.items():
        scene = scene.with_crane(lug, boom_height=H + s * rise)
    return solve(scene)


def test_hoisting_every_hook_equally_keeps_equal_shares():
    _, model = model_of(move_text([f'{{crane = "{k}", hoist = 2.0}}' for k in "ABCD"]))
    for s in np.linspace(0.0, 1.0, 5):
        state, _ = model(s)
        for key in "ABCD":
            assert state.hook_loads[key] == pytest.approx(W / 4, abs=1e-9 * W)
        assert state.heel == pytest.approx(0.0, abs=1e-9)
        assert state.trim == pytest.approx(0.0, abs=1e-9)


def test_three_ropes_are_determinate_whatever_one_hook_does():
    """Three vertical ropes on lugs in the CG's plane: the statics alone give the tensions, and
    the body's tilt scales every plan lever alike, so hoisting one hook changes nothing."""
    cog = (1.0, 0.5, 0.0)
    _, model = model_of(move_text(['{crane = "A", hoist = 0.3}'], lugs="ABD", cog=cog))
    pts = np.array([CORNERS[k] for k in "ABD"])
    statics = np.linalg.solve(np.vstack([np.ones(3), pts.T]), W * np.array([1.0, cog[0], cog[1]]))
    for s in np.linspace(0.0, 1.0, 5):
        state, _ = model(s)
        for key, tension in zip("ABD", statics):
            assert state.hook_loads[key] == pytest.approx(tension, abs=1e-9 * W)
    assert abs(model(1.0)[0].trim) > 0.5  # the body did tilt


def test_four_ropes_shift_load_as_their_stiffness_says():
    """Raising one hook of four by d on a rectangle: to first order the diagonal pair it is on
    gains k d / 4 each and the other pair loses as much (k = EA / l0); exactly, every state is
    liftplan solve of the same scene."""
    rise = 0.02
    _, model = model_of(move_text([f'{{crane = "A", hoist = {rise}}}']))
    for s in np.linspace(0.0, 1.0, 5):
        state, _ = model(s)
        eq = raised(model, s, {"A": rise})
        for key in "ABCD":
            assert state.hook_loads[key] == pytest.approx(eq.tensions[key], abs=1e-9 * W)
        assert state.heel == pytest.approx(eq.pose.heel, abs=1e-9)
        shift = EA / L0 * s * rise / 4
        for key, sign in zip("ABCD", (1, -1, 1, -1)):
            assert state.hook_loads[key] == pytest.approx(W / 4 + sign * shift, abs=2e-3 * W)
    assert model(1.0)[0].hook_loads["A"] - W / 4 > 4.9  # the shift is there, 5 t


def test_a_rope_that_goes_slack_is_reported_with_its_range_and_the_rest_hold_the_body():
    """Lowering the least loaded hook: its rope goes slack where its tension reaches 0, and
    from there the other three carry the body by statics alone."""
    cog = (1.0, 0.5, 0.0)
    text = move_text(['{crane = "C", hoist = -0.1}'], cog=cog, steps=4)
    seq, model = model_of(text)
    result = run_sequence(seq)
    (span,) = result.stages[0].slack
    assert span.what == "C" and span.stop == 1.0
    edge = span.start
    assert 0.5 < edge < 0.75  # the linear estimate: 15.83 t / (k 0.1 m / 4) = 0.633
    assert model(edge - 1e-6)[0].hook_loads["C"] > 0.0
    assert model(edge + 1e-6)[0].slack == ("C",)
    pts = np.array([CORNERS[k] for k in "ABD"])
    statics = np.linalg.solve(np.vstack([np.ones(3), pts.T]), W * np.array([1.0, cog[0], cog[1]]))
    for s in (0.8, 1.0):
        state, _ = model(s)
        assert state.hook_loads["C"] == 0.0
        for key, tension in zip("ABD", statics):
            assert state.hook_loads[key] == pytest.approx(tension, abs=1e-9 * W)
    json = result.to_json()
    assert json["slack"][0]["from_param"] == pytest.approx(edge)
    assert json["slack"][0]["from"] is None


def test_maxima_are_never_below_a_ten_times_finer_grid():
    """A tip moved in plan (the inclined model) and one lowered till its rope is slack: every
    load's continuous maximum is at least its maximum on a grid 10 times finer."""
    tips = {k: (x, y, H) for k, (x, y) in CORNERS.items()}
    text = move_text(
        ['{crane = "A", to = [6.0, 3.5, 21.05]}', '{crane = "C", hoist = -0.1}'],
        cog=(1.0, 0.5, 0.0),
        tips=tips,
        steps=5,
    )
    seq, model = model_of(text)
    stage = run_sequence(seq).stages[0]
    assert stage.slack and model.inclined
    fine = [model(s)[1] for s in np.linspace(0.0, 1.0, 51)]
    for name, peak in stage.maxima.items():
        assert peak.value >= max(v[name] for v in fine) - 1e-12, name
        assert 0.0 <= peak.angle <= 1.0


def test_a_tip_moved_in_plan_is_the_inclined_solve_of_the_same_scene():
    tips = {k: (x, y, H) for k, (x, y) in CORNERS.items()}
    _, model = model_of(move_text(['{crane = "A", to = [6.0, 3.0, 21.0], hoist = 0.05}'], tips=tips))
    state, _ = model(0.5)
    tip = (5.5, 3.0, 21.025 + 0.025)
    scene = model.scene.with_crane("A", tip=tip)
    eq = solve(scene)
    assert eq.model == "inclined"
    assert state.hooks["A"] == pytest.approx(tip, abs=1e-12)
    for key in "ABCD":
        assert state.hook_loads[key] == pytest.approx(eq.tensions[key], abs=1e-9 * W)
    # the inclined pull reaches the lug out of its plate (normal: the default y axis)
    force = np.array(eq.rope_forces["A"].force)
    assert state.lug_loads["A"].load == pytest.approx(np.linalg.norm(force), abs=1e-9 * W)


def test_move_stage_runs_the_rules_chain_and_its_checks():
    text = move_text(['{crane = "A", hoist = 0.02}']).replace(
        f'lug = "A"\nEA = {EA}', f'lug = "A"\nswl = 20.0\nEA = {EA}'
    )
    result = run_sequence(loads_sequence(text))
    (check,) = [c for c in result.checks if c.name == "design_hook_load"]
    assert not check.ok  # 30 t and more on a crane of 20 t
    assert result.stages[0].design.results


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (
            lambda t: t.replace('kind = "move"', 'kind = "move"\npivot = [0.0, 0.0, 0.0]').replace(
                "hoist = 0.02", "to = [5.0, 3.5, 21.0]"
            ),
            "a move stage on a pivot models vertical ropes only",
        ),
        (
            lambda t: t.replace('kind = "move"', 'kind = "move"\nfriction = 0.3'),
            "friction: given without a pivot",
        ),
        (lambda t: t.replace('kind = "move"', 'kind = "move"\nto = 90.0'), "no turning angle"),
        (lambda t: t.replace("moves = [", 'moves = [{crane = "X"}, '), "not a crane of the stage"),
        (lambda t: t.replace("moves = [", 'moves = [{crane = "A", hoist = 1.0}, '), "moved twice"),
        (lambda t: t[: t.index("moves = [")], "moves: missing"),
        (lambda t: t.replace("steps = 4", "steps = 0"), "steps"),
        (lambda t: t.replace("steps = 4", "steps = 4\nstep = 5.0"), "step: a move stage turns no angle"),
        (lambda t: t.replace("steps = 4", "steps = 4\nfrom = 0.0"), "from: a move stage"),
        (lambda t: t.replace(f"rope_length = {L0}\n", "", 1), "rope_length"),
        (lambda t: t.replace('kind = "move"', 'kind = "move"\ncranes = ["A", "B"]'), "3 or more"),
    ],
)
def test_what_a_move_stage_does_not_model_is_refused_with_its_reason(change, expected):
    text = change(move_text(['{crane = "A", hoist = 0.02}']))
    with pytest.raises(InvalidScene, match=expected):
        loads_sequence(text)


def test_move_keys_in_a_turning_stage_are_refused():
    text = move_text(['{crane = "A"}']).replace('kind = "move"', 'kind = "turnover"\nto = 10.0')
    with pytest.raises(InvalidScene, match='moves: given in a turnover stage; expected kind = "move"'):
        loads_sequence(text)


def test_the_cranes_of_a_move_stage_raise_no_unused_key_warning():
    seq = loads_sequence(move_text(['{crane = "A", hoist = 0.02}']))
    assert sequence_warnings(seq) == []
    assert dataclasses.is_dataclass(seq.stages[0].moves[0])


def test_the_lug_planner_places_a_lug_of_a_move_stage_by_its_elastic_share():
    """Lug A on one of two candidates: at the corner, or nearer the CG (where the rope takes a
    larger share of the body, beyond the lug's capacity); the planner solves the move for each
    on the grid and picks the one whose every check is met (the other's grid bound already
    fails, so it is not swept)."""
    text = move_text(['{crane = "A", hoist = 0.02}']).replace(
        'name = "A"\nat = [5.0, 3.0, 0.0]', 'name = "A"\non = ["corner", "inner"]'
    )
    text += (
        '\n[[candidates]]\nname = "corner"\nat = [5.0, 3.0, 0.0]\ncapacity = 70.0\n'
        '\n[[candidates]]\nname = "inner"\nat = [4.0, 2.0, 0.0]\ncapacity = 70.0\n'
    )
    plan = plan_lugs(loads_lug_choice(text))
    assert plan.best.lugs == {"A": "corner"} and plan.best.ok
    assert (plan.options, plan.swept, plan.refused) == (2, 1, 0)
    assert plan.best.worst < 70.0
    # the chosen sweep is the move on the corner lug, state by state liftplan solve
    seq = plan.result.sequence
    assert seq.lug("A").at == (5.0, 3.0, 0.0)
    model = MoveModel(seq, seq.stages[0])
    eq = raised(model, 1.0, {"A": 0.02})
    assert plan.result.stages[0].states[-1].hook_loads["A"] == pytest.approx(eq.tensions["A"], abs=1e-9 * W)

"""Turning stages on four or more supports (issue 26): the redundant share closed by the ropes'
stiffness (the level share), against the two-rope closed form, ``liftplan solve`` of the same
scene, the three-rope statics once a rope is slack, and a rigid pivot."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.scene.file import loads_scene
from liftplan.model.scene.objects import Body, Crane, Lug, Scene
from liftplan.model.sequence import loads_sequence, run_sequence
from liftplan.model.sequence.objects import sequence_warnings
from liftplan.model.sequence.sweep import StageModel, stage_model
from liftplan.model.solve import solve

W = 100.0
L0 = 20.0
#: Lugs of a block that is not symmetric: the ends at different heights, off its centre line.
LUGS = {"A": (10.0, 4.0, 3.0), "B": (-9.0, 5.0, 2.5), "C": (-10.0, -4.0, 3.0), "D": (9.0, -3.0, 2.0)}
EA = {"A": 20000.0, "B": 30000.0, "C": 15000.0, "D": 25000.0}
COG = (0.8, 0.3, 0.0)


def four_text(lugs=LUGS, ea=EA, cog=COG, to=60.0, step=10.0, extra=""):
    """A turnover about y on one vertical rope per lug, each crane named as its lug."""
    text = f"[body]\nweight = {W}\ncog = {list(cog)}\n"
    for name, at in lugs.items():
        text += f'\n[[lugs]]\nname = "{name}"\nat = {list(at)}\n'
    for name in lugs:
        text += f'\n[[cranes]]\nname = "{name}"\nlug = "{name}"\nEA = {ea[name]}\nrope_length = {L0}\n'
    return (
        text + f'\n[sequence]\nkind = "turnover"\naxis = "y"\nfrom = 0.0\nto = {to}\nstep = {step}\n{extra}'
    )


def model_of(text):
    seq = loads_sequence(text)
    return StageModel(seq, seq.stages[0])


def plan_at(angle, points, cog=COG):
    """Plan positions of body points turned by ``angle`` (deg) about y through the CG, +x up."""
    t = math.radians(angle)
    return [((x - cog[0]) * math.cos(t) - (z - cog[2]) * math.sin(t), y - cog[1]) for x, y, z in points]


def level_share_by_hand(angle, names, cog=COG):
    """Every rope taut: T = K A^T c with A K A^T c = W (1, g) (the least elastic energy)."""
    plan = plan_at(angle, [LUGS[n] for n in names], cog)
    a = np.array([[1.0, x, y] for x, y in plan]).T
    k = np.diag([EA[n] / L0 for n in names])
    c = np.linalg.solve(a @ k @ a.T, W * np.array([1.0, 0.0, 0.0]))
    return dict(zip(names, k @ a.T @ c))


def test_a_symmetric_four_rope_turnover_is_the_two_rope_closed_form_split_in_halves():
    """Four equal ropes on the top face of a uniform prism (length L, lugs h above the CG, two
    at each end): each rope carries half of the two-rope share, W (1/2 +- h/L tan theta) / 2,
    up to atan(L / 2h), where the lower pair goes slack and the angle is no longer held."""
    length, h = 20.0, 1.0
    lugs = {"A": (10.0, 3.0, h), "B": (10.0, -3.0, h), "C": (-10.0, 3.0, h), "D": (-10.0, -3.0, h)}
    text = four_text(lugs, {n: 20000.0 for n in lugs}, (0.0, 0.0, 0.0), to=84.5, step=84.5 / 9)
    model = model_of(text)
    for angle in np.arange(0.0, 84.0, 3.5):
        state, _ = model(angle)
        share = 0.5 + h / length * math.tan(math.radians(angle))
        assert state.held and state.tilt == 0.0
        for name in "AB":
            assert state.hook_loads[name] == pytest.approx(W * share / 2, abs=1e-9 * W)
        for name in "CD":
            assert state.hook_loads[name] == pytest.approx(W * (1 - share) / 2, abs=1e-9 * W)
    result = run_sequence(loads_sequence(text)).stages[0]
    edge = math.degrees(math.atan(length / (2 * h)))
    slack = {r.what: r for r in result.slack}
    for name in "CD":
        assert slack[name].start == pytest.approx(edge, abs=1e-6)
    assert result.not_held[0].start == pytest.approx(edge, abs=1e-6)


@pytest.mark.parametrize("angle", [0.0, 25.0, 50.0, 65.0])
def test_every_state_is_liftplan_solve_of_the_same_scene(angle):
    """Unequal ropes, lugs at four heights, the CG off centre: the lugs where the turn puts
    them, each boom tip at its lug's height + l0 + T / k, solved by the elastic model: the
    same tensions (1e-9 W) with the body level (the stage's pose is an equilibrium)."""
    state = model_of(four_text())(angle)[0]
    scene = Scene(
        body=Body(weight=W, cog=COG),
        lugs=tuple(Lug(name=n, at=state.hooks[n]) for n in LUGS),
        cranes=tuple(
            Crane(
                lug=n,
                EA=EA[n],
                rope_length=L0,
                boom_height=state.hooks[n][2] + L0 + state.hook_loads[n] * L0 / EA[n],
            )
            for n in LUGS
        ),
    )
    eq = solve(scene)
    assert eq.model == "elastic"
    for name in LUGS:
        assert eq.tensions[name] == pytest.approx(state.hook_loads[name], abs=1e-9 * W)
    assert abs(eq.pose.heel) < 1e-9 and abs(eq.pose.trim) < 1e-9
    assert state.hook_loads == pytest.approx(level_share_by_hand(angle, "ABCD"), abs=1e-9 * W)


def test_a_slack_rope_is_bracketed_and_the_other_three_carry_the_body_by_statics():
    """C's tension in the level share of all four reaches 0 at an angle found by hand (brentq);
    the sweep reports C slack from there (1e-6 deg), and past it A, B, D carry the body as the
    three equations say."""
    edge = brentq(lambda a: level_share_by_hand(a, "ABCD")["C"], 60.0, 75.0, xtol=1e-12)
    result = run_sequence(loads_sequence(four_text(to=73.0, step=4.0))).stages[0]
    slack = {r.what: r for r in result.slack}
    assert set(slack) == {"C"}
    assert slack["C"].start == pytest.approx(edge, abs=1e-6)
    assert slack["C"].stop == pytest.approx(73.0)
    model = model_of(four_text())
    for angle in (edge + 0.3, 72.5):
        state = model(angle)[0]
        plan = plan_at(angle, [LUGS[n] for n in "ABD"])
        statics = np.linalg.solve(np.array([[1.0, x, y] for x, y in plan]).T, [W, 0.0, 0.0])
        assert state.slack == ("C",)
        assert state.hook_loads["C"] == 0.0
        for name, tension in zip("ABD", statics):
            assert state.hook_loads[name] == pytest.approx(tension, abs=1e-9 * W)
    before = model(edge - 1e-4)[0]
    assert before.slack == () and 0.0 < before.hook_loads["C"] < 1e-3 * W


def test_a_pivot_with_three_cranes_is_rigid_and_pushes_only():
    """An upend on a pivot with three cranes: moments about the pivot balance, the ropes'
    stretches T / k are one plane through zero at the pivot (the ground does not give), and
    the reaction is the rest of the weight, >= 0."""
    lugs = {"A": (20.0, 3.0, 1.0), "B": (20.0, -3.0, 1.0), "C": (10.0, 0.5, 1.2)}
    text = four_text(lugs, EA, (9.0, 0.2, 0.5), to=80.0).replace(
        'kind = "turnover"', 'kind = "upend"\npivot = [0.0, 0.0, 0.0]'
    )
    model = model_of(text)
    for angle in (0.0, 30.0, 60.0):
        state = model(angle)[0]
        plan = plan_at(angle, list(lugs.values()) + [(0.0, 0.0, 0.0), (9.0, 0.2, 0.5)], (0, 0, 0))
        pivot, g = np.array(plan[3]), np.array(plan[4])
        ropes = np.array(plan[:3]) - pivot
        tensions = np.array([state.hook_loads[n] for n in lugs])
        assert tensions @ ropes == pytest.approx(W * (g - pivot), abs=1e-9 * W)
        assert state.ground_reaction == pytest.approx(W - tensions.sum(), abs=1e-9 * W)
        assert state.ground_reaction > 0.0
        stretch = tensions * L0 / np.array([EA[n] for n in lugs])
        plane = np.linalg.lstsq(ropes, stretch, rcond=None)[0]
        assert ropes @ plane == pytest.approx(stretch, abs=1e-12)


def test_the_continuous_maxima_of_four_ropes_are_never_below_a_ten_times_finer_grid():
    text = four_text(to=72.0, step=6.0)
    result = run_sequence(loads_sequence(text)).stages[0]
    model = model_of(text)
    fine = [model(a)[1] for a in np.arange(0.0, 72.0001, 0.6)]
    for name, peak in result.maxima.items():
        assert peak.value >= max(v[name] for v in fine) - 1e-12
    assert {c.name for c in result.checks} >= {"angle_held"}
    assert result.design.results  # the rules' chain ran on these maxima


def test_four_supports_need_each_ropes_stiffness():
    text = four_text().replace("EA = 15000.0\n", "")
    with pytest.raises(InvalidScene, match=r"cranes\[C\]: EA missing; a stage on four"):
        loads_sequence(text)


def test_four_supports_in_one_vertical_plane_are_refused():
    lugs = {
        n: (x, 0.0, z) for n, x, z in (("A", 10.0, 1.0), ("B", 4.0, 0.0), ("C", -4.0, 2.0), ("D", -10.0, 1.0))
    }
    with pytest.raises(InvalidScene, match="4 supports are in one vertical plane"):
        loads_sequence(four_text(lugs, {n: 20000.0 for n in lugs}, (0.0, 0.0, 0.0)))


def test_rope_length_and_ea_are_used_on_four_supports_not_warned():
    warnings = sequence_warnings(loads_sequence(four_text()))
    assert warnings == []


# -- a move stage chained from the stage before ------------------------------------------------


def staged_text(*stages, lugs=LUGS, ea=EA):
    """The block of :func:`four_text` with its ``[[stages]]`` given as TOML bodies."""
    head = four_text(lugs, ea).split("\n[sequence]")[0]
    return head + "".join(f"\n[[stages]]\n{body}\n" for body in stages)


TURN = 'name = "turn"\nkind = "turnover"\naxis = "y"\nfrom = 0.0\nto = 30.0\nstep = 10.0'
MOVE = 'name = "hoist"\nkind = "move"\nsteps = 4\nmoves = [{crane = "A", hoist = 0.05}]'


def test_a_move_starts_where_the_turnover_left_the_body_and_the_tips():
    """Turnover to 30 deg on four ropes, then crane A hoists: the move's first state is the
    turnover's last (the loads to 1e-9 W, the body level against where it was left, each tip
    above its hook at its stretched rope length, the body's origin where the turn put it)."""
    seq = loads_sequence(staged_text(TURN, MOVE))
    result = run_sequence(seq)
    last, first = result.stages[0].states[-1], result.stages[1].states[0]
    assert last.angle == 30.0 and first.angle == 0.0
    for key in LUGS:
        assert first.hook_loads[key] == pytest.approx(last.hook_loads[key], abs=1e-9 * W)
        for part in ("load", "in_plane", "out_of_plane"):
            assert getattr(first.lug_loads[key], part) == pytest.approx(
                getattr(last.lug_loads[key], part), abs=1e-9 * W
            )
        stretched = L0 * (1.0 + last.hook_loads[key] / EA[key])
        assert first.hooks[key] == pytest.approx(np.add(last.hooks[key], (0.0, 0.0, stretched)), abs=1e-12)
    assert abs(first.heel) < 1e-9 and abs(first.trim) < 1e-9
    t = math.radians(30.0)
    rot = np.array([[math.cos(t), 0.0, -math.sin(t)], [0.0, 1.0, 0.0], [math.sin(t), 0.0, math.cos(t)]])
    assert first.origin == pytest.approx(np.array(COG) - rot @ np.array(COG), abs=1e-9)
    # and the move goes on from there: A's hook takes up load as it rises
    assert result.stages[1].states[-1].hook_loads["A"] > first.hook_loads["A"] + 1.0


def test_a_move_after_a_move_starts_from_its_end():
    second = MOVE.replace('"hoist"', '"lower"').replace("hoist = 0.05", "hoist = -0.05")
    result = run_sequence(loads_sequence(staged_text(TURN, MOVE, second)))
    end, start = result.stages[1].states[-1], result.stages[2].states[0]
    for key in LUGS:
        assert start.hook_loads[key] == pytest.approx(end.hook_loads[key], abs=1e-9 * W)
        assert start.hooks[key] == pytest.approx(end.hooks[key], abs=1e-12)
    assert start.origin == pytest.approx(end.origin, abs=1e-9)
    # lowered back by as much, the hooks are where the turnover left them
    back = result.stages[2].states[-1]
    for key in LUGS:
        assert back.hook_loads[key] == pytest.approx(
            result.stages[0].states[-1].hook_loads[key], abs=1e-9 * W
        )


def test_a_crane_that_joins_at_the_move_comes_taut_carrying_nothing():
    """Three cranes turn the block; B joins at the move, its rope just taut above its lug: at
    s = 0 it carries nothing and the others carry what they did (the three equations)."""
    turn = TURN + '\ncranes = ["A", "C", "D"]'
    result = run_sequence(loads_sequence(staged_text(turn, MOVE)))
    last, first = result.stages[0].states[-1], result.stages[1].states[0]
    assert first.hook_loads["B"] == pytest.approx(0.0, abs=1e-9 * W)
    for key in "ACD":
        assert last.hook_loads[key] > 0.0
        assert first.hook_loads[key] == pytest.approx(last.hook_loads[key], abs=1e-9 * W)


def test_a_move_after_an_angle_that_is_not_held_is_refused():
    turn = TURN.replace("to = 30.0", "to = 88.0").replace("step = 10.0", "step = 44.0")
    seq = loads_sequence(staged_text(turn, MOVE))
    with pytest.raises(EquilibriumNotFound, match="turn ends at 88 deg, an angle it cannot hold"):
        stage_model(seq, seq.stages[1])


# -- slings in a move stage ----------------------------------------------------------------------

SLUNG_LUGS = {"A1": (10.0, 3.0), "A2": (10.0, -3.0), "B": (-10.0, 3.0), "C": (-10.0, -3.0)}
SLUNG = (
    "[body]\nweight = 100.0\ncog = [0.5, 0.2, 0.0]\n"
    + "".join(f'\n[[lugs]]\nname = "{name}"\nat = [{x}, {y}, 0.0]\n' for name, (x, y) in SLUNG_LUGS.items())
    + """
[ropes]
EA = 20000.0

[[cranes]]
name = "A"
rope_length = 20.0
boom_height = HA
sling = { legs = [{ lug = "A1", length = 8.0, EA = LEG }, { lug = "A2", length = 8.5, EA = LEG }] }

[[cranes]]
name = "B"
lug = "B"
rope_length = 20.0
boom_height = 21.0

[[cranes]]
name = "C"
lug = "C"
rope_length = 20.0
boom_height = 21.0
"""
)


def slung(stages, ha=29.95, leg=40000.0):
    return SLUNG.replace("HA", str(ha)).replace("LEG", str(leg)) + stages


def test_a_sling_in_a_move_stage_is_the_rigging_solve_of_the_same_scene():
    """Crane A on a 2-leg sling hoists 0.3 m: every state is liftplan solve (the rigging model,
    elastic legs) of the scene with A's boom that much higher; each lug's load is its leg's
    tension, the legs are reported as sling tensions and their maxima found."""
    text = slung('[sequence]\nkind = "move"\nsteps = 2\nmoves = [{crane = "A", hoist = 0.3}]\n')
    result = run_sequence(loads_sequence(text)).stages[0]
    for state in result.states:
        eq = solve(loads_scene(SLUNG.replace("HA", str(29.95 + 0.3 * state.angle)).replace("LEG", "40000.0")))
        assert eq.model == "rigging"
        for key in "ABC":
            assert state.hook_loads[key] == pytest.approx(eq.tensions[key], abs=1e-9 * W)
        for lug in ("A1", "A2"):
            assert state.sling_tensions[f"A/{lug}"] == pytest.approx(
                eq.rigging.legs[f"A/{lug}"], abs=1e-9 * W
            )
            assert state.lug_loads[lug].load == pytest.approx(state.sling_tensions[f"A/{lug}"], abs=1e-9 * W)
    assert result.maxima["leg:A/A2"].value >= max(s.sling_tensions["A/A2"] for s in result.states)


def test_a_move_after_a_turn_on_a_sling_starts_at_the_turns_last_state():
    """The turn's legs are of fixed length, the move's stretch: with legs 1e4 times stiffer than
    the ropes the move's first state is the turn's last to 1e-5 W. In the 3D view the move's
    first body has the turn's last rotation (not the file's pose), and the sling crane is drawn
    as a hoist rope up to its tip and two legs from its hook."""
    from liftplan.planner.sequence.view import sequence_view  # the view lives in the planner

    stages = (
        '[[stages]]\nname = "turn"\nkind = "turnover"\naxis = "x"\nfrom = 0.0\nto = 12.0\nstep = 6.0\n'
        '[[stages]]\nname = "hoist"\nkind = "move"\nsteps = 2\nmoves = [{crane = "B", hoist = 0.02}]\n'
    )
    result = run_sequence(loads_sequence(slung(stages, leg=2e8)))
    last, first = result.stages[0].states[-1], result.stages[1].states[0]
    for key in "ABC":
        assert first.hook_loads[key] == pytest.approx(last.hook_loads[key], abs=1e-5 * W)
    for leg in ("A/A1", "A/A2"):
        assert first.sling_tensions[leg] == pytest.approx(last.sling_tensions[leg], abs=1e-5 * W)
    view = sequence_view(result)
    names = [s.name for s in view.states]
    turned, moved = view.states[names.index("turn: 12 deg")], view.states[names.index("hoist: s = 0")]
    assert np.array(moved.rotation) == pytest.approx(np.array(turned.rotation), abs=1e-6)
    assert np.array(moved.origin) == pytest.approx(np.array(turned.origin), abs=1e-6)
    assert sorted(r.role for r in moved.ropes if r.key.startswith("A")) == ["hoist", "leg", "leg"]


# -- a move stage on a pivot ---------------------------------------------------------------------

K = 1000.0  # EA / l0 of every rope below  [t/m]
PIVOTED = {"A": (10.0, 3.0, 0.0), "B": (-10.0, 3.0, 0.0), "C": (10.0, -3.0, 0.0)}
GROUND = (-10.0, -3.0, 0.0)  # the fourth corner rests on the ground
PIVOT_COG = (0.5, 0.2, 0.0)


def pivot_text(moves, heights, pivot=True):
    text = f"[body]\nweight = {W}\ncog = {list(PIVOT_COG)}\n"
    for name, at in PIVOTED.items():
        text += f'\n[[lugs]]\nname = "{name}"\nat = {list(at)}\n'
    for name in PIVOTED:
        text += (
            f'\n[[cranes]]\nname = "{name}"\nlug = "{name}"\nEA = {K * L0}\nrope_length = {L0}\n'
            f"boom_height = {heights[name]}\n"
        )
    where = f"pivot = {list(GROUND)}\n" if pivot else ""
    return text + f'\n[sequence]\nkind = "move"\nsteps = 4\n{where}moves = [{", ".join(moves)}]\n'


def attitude_by_hand(heel, trim):
    h, t = math.radians(heel), math.radians(trim)
    rx = np.array([[1, 0, 0], [0, math.cos(h), -math.sin(h)], [0, math.sin(h), math.cos(h)]])
    ry = np.array([[math.cos(t), 0, math.sin(t)], [0, 1, 0], [-math.sin(t), 0, math.cos(t)]])
    return rx @ ry


def test_a_move_on_a_pivot_is_an_equilibrium_of_the_ropes_and_the_ground():
    """Three ropes and a corner on the ground (statically indeterminate): A hoists 0.3 m. At
    every state, the body turned about the pivot by the reported heel and trim gives each rope
    its reported tension (k times its stretch), the moments about the pivot balance, and the
    ground carries the rest of the weight, pushing."""
    heights = {"A": 20.02, "B": 20.04, "C": 20.03}
    result = run_sequence(loads_sequence(pivot_text(['{crane = "A", hoist = 0.3}'], heights))).stages[0]
    pivot = np.array(GROUND)
    for state in result.states:
        rot = attitude_by_hand(state.heel, state.trim)
        tips = dict(heights, A=heights["A"] + 0.3 * state.angle)
        levers, tensions = [], []
        for name, at in PIVOTED.items():
            r = rot @ (np.array(at) - pivot)
            stretch = tips[name] - (pivot[2] + r[2]) - L0
            assert state.hook_loads[name] == pytest.approx(K * max(stretch, 0.0), abs=1e-9 * W)
            levers.append(r[:2])
            tensions.append(state.hook_loads[name])
        g = (rot @ (np.array(PIVOT_COG) - pivot))[:2]
        assert np.array(tensions) @ np.array(levers) == pytest.approx(W * g, abs=1e-9 * W)
        assert state.ground_reaction == pytest.approx(W - sum(tensions), abs=1e-9 * W)
        assert state.ground_reaction > 0.0 and "pivot" not in state.slack
    assert result.maxima["ground"].value == pytest.approx(max(s.ground_reaction for s in result.states))
    assert result.states[-1].hook_loads["A"] > result.states[0].hook_loads["A"] + 10.0


def test_hoisting_every_rope_lifts_the_body_off_its_pivot_where_the_hand_calculation_says():
    """Hanging free, three ropes carry the body by the statics alone, so hoisting all three by d
    raises it rigidly by d: the pivot point leaves the ground at d* = (ground) - (its height
    hanging free at d = 0), found by liftplan solve. The sweep's "pivot" slack range starts
    there (1e-6 of the stage), and from there the states are those of the body without pivot."""
    heights = {"A": 20.0, "B": 20.0, "C": 20.0}
    moves = [f'{{crane = "{k}", hoist = 0.1}}' for k in PIVOTED]
    free = run_sequence(loads_sequence(pivot_text(moves, heights, pivot=False))).stages[0]
    first = free.states[0]
    rot = attitude_by_hand(first.heel, first.trim)
    below = GROUND[2] - (np.array(first.origin) + rot @ np.array(GROUND))[2]
    assert 0.0 < below < 0.1
    result = run_sequence(loads_sequence(pivot_text(moves, heights))).stages[0]
    (lifted,) = [r for r in result.slack if r.what == "pivot"]
    assert lifted.start == pytest.approx(below / 0.1, abs=1e-6)
    assert lifted.stop == 1.0
    for on, off in zip(result.states, free.states):
        if on.angle > lifted.start:
            assert on.ground_reaction == 0.0 and "pivot" in on.slack
            for key in PIVOTED:
                assert on.hook_loads[key] == pytest.approx(off.hook_loads[key], abs=1e-9 * W)
        else:
            assert on.ground_reaction > 0.0

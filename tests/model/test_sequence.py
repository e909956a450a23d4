"""Lift sequences (issue 26): closed forms of turnover and upending at held angles, slack ropes
with their angle ranges, and the continuous maxima against finer grids."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from liftplan.model.errors import InvalidScene
from liftplan.model.sequence import loads_sequence, run_sequence
from liftplan.model.sequence.maxima import Sampler, adaptive_samples, continuous_maxima
from liftplan.model.sequence.sweep import StageModel

W = 100.0


def sequence_text(lugs, cranes, operation, cog=(0.0, 0.0, 0.0), weight=W, extra=""):
    """A sequence file from lug and crane tables and the [sequence] keys."""
    text = f"[body]\nweight = {weight}\ncog = {list(cog)}\n"
    for name, at, more in lugs:
        text += f'\n[[lugs]]\nname = "{name}"\nat = {list(at)}\n{more}\n'
    for crane in cranes:
        text += f"\n[[cranes]]\n{crane}\n"
    return text + f"\n[sequence]\n{operation}\n{extra}"


def model_of(text, stage=0):
    seq = loads_sequence(text)
    return StageModel(seq, seq.stages[stage])


# -- closed forms ------------------------------------------------------------------------------


def test_prism_turned_by_two_vertical_ropes_on_end_lugs_matches_the_lever_rule():
    """A uniform prism (length L, CG at its centre) on two vertical ropes at lugs on its top
    face at the ends, h above the CG: turned by theta about y, the +x lug's share is
    W (1/2 + h/L tan theta) (horizontal lever arms L/2 cos theta +- h sin theta)."""
    length, h = 20.0, 1.0
    text = sequence_text(
        [("A", (10.0, 0.0, 1.0), ""), ("B", (-10.0, 0.0, 1.0), "")],
        ['name = "East"\nlug = "A"', 'name = "West"\nlug = "B"'],
        'kind = "turnover"\naxis = "y"\nfrom = 0.0\nto = 80.0\nstep = 5.0',
    )
    model = model_of(text)
    for angle in np.arange(0.0, 80.001, 2.5):
        state, _ = model(angle)
        share = 0.5 + h / length * math.tan(math.radians(angle))
        assert state.held
        assert state.hook_loads["East"] == pytest.approx(W * share, abs=1e-9 * W)
        assert state.hook_loads["West"] == pytest.approx(W * (1 - share), abs=1e-9 * W)
        # a vertical rope on a lug whose plate is in the plane of the turn: all in plane
        assert state.lug_loads["A"].out_of_plane == pytest.approx(0.0, abs=1e-12)
        assert state.lug_loads["A"].in_plane == pytest.approx(W * share, abs=1e-9 * W)


def test_turning_about_x_is_turning_about_y_with_the_body_turned_a_quarter():
    """The prism of the lever-rule test laid along y and turned about x (its +y end raised):
    the same shares, W (1/2 + h/L tan theta) on the raised end."""
    text = sequence_text(
        [("A", (0.0, 10.0, 1.0), ""), ("B", (0.0, -10.0, 1.0), "")],
        ['name = "Port"\nlug = "A"', 'name = "Stbd"\nlug = "B"'],
        'kind = "turnover"\naxis = "x"\nfrom = 0.0\nto = 80.0\nstep = 5.0',
    )
    model = model_of(text)
    for angle in (0.0, 30.0, 75.0):
        share = 0.5 + 1.0 / 20.0 * math.tan(math.radians(angle))
        state = model(angle)[0]
        assert state.hook_loads["Port"] == pytest.approx(W * share, abs=1e-9 * W)
        assert state.lug_loads["A"].out_of_plane == pytest.approx(0.0, abs=1e-12)


def test_a_vertical_rope_turns_out_of_the_plane_of_a_lug_across_the_turn():
    """A lug plate with normal x: the rope, vertical in the world, is at theta to the body's
    z axis, so sin(theta) of its load is out of the plate's plane."""
    text = sequence_text(
        [("A", (10.0, 0.0, 0.0), "normal = [1.0, 0.0, 0.0]"), ("B", (-10.0, 0.0, 0.0), "")],
        ['lug = "A"', 'lug = "B"'],
        'kind = "turnover"\nfrom = 0.0\nto = 60.0\nstep = 10.0',
    )
    model = model_of(text)
    for angle in (0.0, 17.0, 45.0, 60.0):
        load = model(angle)[0].lug_loads["A"]
        s, c = math.sin(math.radians(angle)), math.cos(math.radians(angle))
        assert load.load == pytest.approx(W / 2, abs=1e-9 * W)
        assert load.out_of_plane == pytest.approx(W / 2 * s, abs=1e-9 * W)
        assert load.in_plane == pytest.approx(W / 2 * c, abs=1e-9 * W)


def test_tailing_upend_on_a_frictionless_pivot_matches_hand_statics():
    """Pivot P, head lug H, CG G in the x-z plane: moments about the pivot give the head
    crane's share x'_G / x'_H with x' = (x - x_P) cos(theta) - (z - z_P) sin(theta)."""
    pivot, head, cog = (0.0, 0.0, -1.0), (38.0, 0.0, 0.5), (18.0, 0.0, 0.0)
    text = sequence_text(
        [("H", head, "")],
        ['name = "Head"\nlug = "H"'],
        f'kind = "upend"\nfrom = 0.0\nto = 80.0\nstep = 10.0\npivot = {list(pivot)}',
        cog=cog,
    )
    model = model_of(text)

    def arm(p, angle):
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        return (p[0] - pivot[0]) * c - (p[2] - pivot[2]) * s

    for angle in np.arange(0.0, 80.001, 4.0):
        state, _ = model(angle)
        head_share = W * arm(cog, angle) / arm(head, angle)
        assert state.hook_loads["Head"] == pytest.approx(head_share, abs=1e-9 * W)
        assert state.ground_reaction == pytest.approx(W - head_share, abs=1e-9 * W)


def test_a_centre_of_gravity_off_the_line_of_two_supports_tilts_the_body_into_their_plane():
    """Upend on a pivot with the CG 0.5 m to port of the pivot-head line: the body rolls about
    that line (tilt across the turning axis) until the CG is in the supports' vertical plane,
    and the two forces are the lever rule along it."""
    text = sequence_text(
        [("H", (38.0, 0.0, 0.0), "")],
        ['name = "Head"\nlug = "H"'],
        'kind = "upend"\nfrom = 0.0\nto = 70.0\nstep = 10.0\npivot = [0.0, 0.0, -1.0]',
        cog=(18.0, 0.5, 0.0),
    )
    model = model_of(text)
    for angle in (0.0, 35.0, 70.0):
        held = model.statics.state(angle)
        pivot = np.array([0.0, 0.0, -1.0])
        cog = pivot + held.rotation @ (np.array([18.0, 0.5, 0.0]) - pivot)
        hook = held.hooks["Head"]
        line, off = hook[:2] - pivot[:2], cog[:2] - pivot[:2]
        assert abs(line[0] * off[1] - line[1] * off[0]) < 1e-9 * 38.0
        assert abs(held.tilt) > 0.1
        share = float(np.dot(off, line) / np.dot(line, line))
        assert held.forces["Head"] == pytest.approx(W * share, abs=1e-9 * W)
        assert held.forces["pivot"] == pytest.approx(W * (1 - share), abs=1e-9 * W)


def as2550(tail):
    """The AS 2550 tailing geometry: a uniform load of length L = 40 m (CG at L/2 on its
    axis), the head lug on the axis at the top end, the foot's lug (or pivot) at the bottom
    end k L above the axis on the side that is up at the start, with k = (0.22 / 0.28) cot 76
    deg = 0.1959: the head share (L/2 cos t + k L sin t) / (L cos t + k L sin t) is then 1/2 at
    0 deg, 0.72 at 76 deg and 1 at 90 deg."""
    k = 0.22 / 0.28 / math.tan(math.radians(76.0))
    foot = (0.0, 0.0, k * 40.0)
    if tail == "crane":
        return sequence_text(
            [("H", (40.0, 0.0, 0.0), ""), ("T", foot, "")],
            ['name = "Head"\nlug = "H"', 'name = "Tail"\nlug = "T"'],
            'kind = "upend"\nfrom = 0.0\nto = 90.0\nstep = 2.0',
            cog=(20.0, 0.0, 0.0),
        )
    return sequence_text(
        [("H", (40.0, 0.0, 0.0), "")],
        ['name = "Head"\nlug = "H"'],
        f'kind = "upend"\nfrom = 0.0\nto = 90.0\nstep = 2.0\npivot = {list(foot)}',
        cog=(20.0, 0.0, 0.0),
    )


@pytest.mark.parametrize("tail", ["crane", "pivot"])
def test_as2550_tailing_figures_50_72_100_percent(tail):
    model = model_of(as2550(tail))
    for angle, share in ((0.0, 0.50), (76.0, 0.72), (90.0, 1.00)):
        assert model(angle)[0].hook_loads["Head"] == pytest.approx(share * W, abs=1e-9 * W)


def test_three_ropes_share_the_weight_by_the_three_equations_until_one_goes_slack():
    """Three vertical ropes not in one vertical plane: at psi = 0 the vertical force and the
    two moments give the three tensions (written here with the lugs' horizontal coordinates
    x' = x cos t - z sin t, y' = y); past the angle where A's tension reaches 0 it is slack,
    and B1 and B2 carry the body, tilted so the CG is in their vertical plane."""
    lugs = {"A": (10.0, 0.0, 0.0), "B1": (-10.0, 3.0, -1.0), "B2": (-10.0, -3.0, -3.0)}
    cog = (0.0, 0.3, 0.0)
    text = sequence_text(
        [(k, v, "") for k, v in lugs.items()],
        [f'lug = "{k}"' for k in lugs],
        'kind = "turnover"\nfrom = 0.0\nto = 85.0\nstep = 5.0',
        cog=cog,
    )
    model = model_of(text)
    for angle in (0.0, 20.0, 45.0, 70.0, 78.0):
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        xs = [p[0] * c - p[2] * s for p in lugs.values()]
        matrix = np.array([[1.0, 1.0, 1.0], xs, [p[1] for p in lugs.values()]])
        expected = np.linalg.solve(matrix, W * np.array([1.0, cog[0] * c - cog[2] * s, cog[1]]))
        state = model(angle)[0]
        assert state.tilt == 0.0 and state.held
        assert [state.hook_loads[k] for k in lugs] == pytest.approx(list(expected), abs=1e-9 * W)
    state = model(82.0)[0]
    assert state.held and state.slack == ("A",) and state.tilt != 0.0
    assert state.hook_loads["A"] == 0.0
    assert state.hook_loads["B1"] + state.hook_loads["B2"] == pytest.approx(W, abs=1e-9 * W)


# -- slack ropes and angles not held --------------------------------------------------------------


def test_a_slack_rope_is_reported_with_its_angle_range_and_the_angle_not_held():
    """The prism of the lever-rule test turned past tan(theta) = L / (2 h): the West rope
    would have to push, so it is slack from atan(10) = 84.29 deg on, and East alone cannot
    hold the angle."""
    text = sequence_text(
        [("A", (10.0, 0.0, 1.0), ""), ("B", (-10.0, 0.0, 1.0), "")],
        ['name = "East"\nlug = "A"', 'name = "West"\nlug = "B"'],
        'kind = "turnover"\nfrom = 0.0\nto = 88.0\nstep = 5.0',
    )
    result = run_sequence(loads_sequence(text))
    (stage,) = result.stages
    (slack,) = [r for r in stage.slack if r.what == "West"]
    edge = math.degrees(math.atan(10.0))
    assert slack.start == pytest.approx(edge, abs=1e-6) and slack.stop == 88.0
    (unheld,) = stage.not_held
    assert unheld.start == pytest.approx(edge, abs=1e-6)
    check = next(c for c in result.checks if c.name == "angle_held")
    assert not check.ok and check.value == pytest.approx(88.0 - edge, abs=1e-6)


def test_a_slack_sling_leg_leaves_the_equilibrium_of_the_other_leg():
    """Upend on a pivot with the head crane on a 2-leg sling along the body (lugs at x = 24
    and 40 m, legs 10 m: the apex 6 m off the axis above x = 32 m). Past tan(theta) = 4/3 the
    apex passes over the lower lug and the upper leg is slack: the hook hangs over the lower
    lug, and the head crane's share is that of a single rope there, W 18 / 24."""
    text = sequence_text(
        [("S1", (24.0, 0.0, 0.0), ""), ("S2", (40.0, 0.0, 0.0), "")],
        [
            'name = "Head"\nsling = { legs = [{ lug = "S1", length = 10.0, EA = 1e4 }, '
            '{ lug = "S2", length = 10.0, EA = 1e4 }] }'
        ],
        'kind = "upend"\nfrom = 0.0\nto = 80.0\nstep = 5.0\npivot = [0.0, 0.0, 0.0]',
        cog=(18.0, 0.0, 0.0),
    )
    result = run_sequence(loads_sequence(text))
    (stage,) = result.stages
    (slack,) = stage.slack
    assert slack.what == "Head/S2"
    assert slack.start == pytest.approx(math.degrees(math.atan(4.0 / 3.0)), abs=1e-6)
    model = StageModel(loads_sequence(text), loads_sequence(text).stages[0])
    for angle in (10.0, 40.0, 53.0):
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        state = model(angle)[0]
        assert state.hook_loads["Head"] == pytest.approx(W * 18 * c / (32 * c - 6 * s), abs=1e-9 * W)
    for angle in (54.0, 70.0, 80.0):
        state = model(angle)[0]
        assert state.held and "Head/S2" in state.slack
        assert state.hook_loads["Head"] == pytest.approx(W * 18 / 24, abs=1e-9 * W)
        assert state.sling_tensions["Head/S2"] == 0.0
        assert state.sling_tensions["Head/S1"] == pytest.approx(W * 18 / 24, abs=1e-9 * W)


# -- the worst between the steps ------------------------------------------------------------------


def fine_grid_max(model, start, stop, step, key):
    return max(model(a)[1][key] for a in np.linspace(start, stop, int(round((stop - start) / step)) + 1))


@pytest.mark.parametrize("example", ["block_turnover", "mast_upend"])
def test_continuous_maxima_never_below_a_ten_times_finer_grid(example):
    from helpers import EXAMPLES

    from liftplan.model.sequence import load_sequence

    seq = load_sequence(EXAMPLES / f"{example}.toml")
    result = run_sequence(seq)
    for stage in result.stages:
        st = stage.stage
        model = StageModel(seq, st)
        lo, hi = sorted((st.start, st.stop))
        for key, peak in stage.maxima.items():
            finer = fine_grid_max(model, lo, hi, st.step / 10, key)
            assert peak.value >= finer - 1e-12 * W, (key, peak, finer)
            assert lo <= peak.angle <= hi
            assert model(peak.angle)[1][key] == pytest.approx(peak.value, abs=1e-12 * W)


def test_a_peak_between_two_user_steps_is_found():
    """The block's top-edge lugs: their out-of-plane load peaks at 67.6 deg, between the 60 and
    70 deg grid points; the continuous maximum is the peak of a 1e-4 deg grid around it."""
    from helpers import EXAMPLES

    from liftplan.model.sequence import load_sequence

    seq = load_sequence(EXAMPLES / "block_turnover.toml")
    stage = run_sequence(seq).stages[0]
    peak = stage.maxima["lug_out:B1"]
    model = StageModel(seq, seq.stages[0])
    on_grid = max(s.lug_loads["B1"].out_of_plane for s in stage.states)
    dense = np.linspace(peak.angle - 0.2, peak.angle + 0.2, 2001)
    best = max(model(a)[1]["lug_out:B1"] for a in dense)
    assert 60.0 < peak.angle < 70.0
    assert peak.value > on_grid + 0.05  # t: the grid alone misses it by 0.1 t
    assert peak.value >= best - 1e-9 * W


def test_a_sharp_peak_narrower_than_the_step_is_bracketed_and_refined():
    """A load built with a peak 0.2 deg wide at 12.34 deg on a 5 deg grid: its height and angle
    are found to the search's tolerance, though neither neighbouring grid point sees it."""
    centre, width = 12.34, 0.2

    def evaluate(angle):
        bump = 50.0 / (1.0 + ((angle - centre) / width) ** 2)
        return None, {"load": 20.0 + 0.1 * angle + bump}

    sampler = Sampler(evaluate)
    grid = np.arange(0.0, 30.001, 5.0)
    angles = adaptive_samples(sampler, grid, 1e-5 * W, 1e-4)
    peak = continuous_maxima(sampler, angles, ["load"], 1e-9, 1e-10)["load"]
    # the exact maximum of the built load: d/da [0.1 a + 50 / (1 + u^2)] = 0, u = (a - c) / w
    u = 0.1 * width / 100.0  # 0.1 = 100 u / (w (1 + u^2)^2), to first order
    for _ in range(50):
        u = 0.1 * width * (1 + u * u) ** 2 / 100.0
    exact_angle = centre + u * width
    exact = 20.0 + 0.1 * exact_angle + 50.0 / (1.0 + u * u)
    assert max(evaluate(a)[1]["load"] for a in grid) < 30.0
    assert peak.angle == pytest.approx(exact_angle, abs=1e-6)
    assert peak.value == pytest.approx(exact, abs=1e-9)
    assert exact <= peak.bound < exact + 1e-3  # the curvature bound holds, and is tight


def test_the_bound_of_a_maximum_is_above_the_prisms_closed_form_and_close_to_it():
    """The prism of the lever-rule test with its -x lug's plate across the prism (normal x): the
    rope's load W (1/2 - h/L tan theta), vertical, is sin theta out of the plate, an interior
    maximum of W (1/2 - h/L tan theta) sin theta. The refined maximum is the closed form's
    (1e-9 W), and its bound is above it by less than 1e-4 W; every bound is at least its
    maximum."""
    length, h = 20.0, 1.0
    text = sequence_text(
        [("A", (10.0, 0.0, h), ""), ("B", (-10.0, 0.0, h), "normal = [1.0, 0.0, 0.0]")],
        ['name = "East"\nlug = "A"', 'name = "West"\nlug = "B"'],
        'kind = "turnover"\naxis = "y"\nfrom = 0.0\nto = 80.0\nstep = 10.0',
    )
    stage = run_sequence(loads_sequence(text)).stages[0]

    def across(theta):
        t = math.radians(theta)
        return W * (0.5 - h / length * math.tan(t)) * math.sin(t)

    best = minimize_scalar(
        lambda a: -across(a), bounds=(20.0, 70.0), method="bounded", options={"xatol": 1e-10}
    )
    peak = stage.maxima["lug_out:B"]
    assert peak.value == pytest.approx(across(best.x), abs=1e-9 * W)
    assert across(best.x) <= peak.bound < across(best.x) + 1e-4 * W
    for found in stage.maxima.values():
        assert found.bound >= found.value


# -- refusals -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("operation", "message"),
    [
        ('kind = "turnover"\nfrom = 0.0\nto = 90.0\nplumb = false', "only plumb hooks"),
        ('kind = "turnover"\nfrom = 0.0\nto = 90.0\naxis = "z"', "axis"),
        ('kind = "turnover"\nfrom = 0.0\nto = 90.0\nstep = 0.0', "step > 0"),
        ('kind = "turnover"\nfrom = 0.0\nto = 90.0\npivot = [0.0, 0.0, 0.0]', "hangs in the air"),
        ('kind = "upend"\nfrom = 0.0\nto = 90.0\ncranes = ["A"]', "two or more supports"),
        ('kind = "upend"\nfrom = 0.0\nto = 90.0\ncranes = ["Q", "A"]', "no such crane"),
    ],
)
def test_bad_sequences_are_refused_in_one_line(operation, message):
    text = sequence_text(
        [("A", (10.0, 0.0, 0.0), ""), ("B", (-10.0, 0.0, 0.0), "")], ['lug = "A"', 'lug = "B"'], operation
    )
    with pytest.raises(InvalidScene, match=message):
        loads_sequence(text)


def test_head_tail_and_pivot_in_one_vertical_plane_are_refused_as_indeterminate():
    text = sequence_text(
        [("H", (40.0, 0.0, 0.0), ""), ("T", (1.0, 0.0, 0.5), "")],
        ['name = "Head"\nlug = "H"', 'name = "Tail"\nlug = "T"'],
        'kind = "upend"\nfrom = 0.0\nto = 90.0\npivot = [0.0, 0.0, 0.0]',
        cog=(20.0, 0.0, 0.0),
    )
    with pytest.raises(InvalidScene, match="statically indeterminate"):
        loads_sequence(text)


def test_crane_keys_a_sequence_does_not_use_are_named_in_a_warning():
    from liftplan.model.sequence.objects import sequence_warnings

    text = sequence_text(
        [("H", (40.0, 0.0, 0.0), "")],
        ['name = "Head"\nlug = "H"\nboom_height = 60.0\nrope_length = 20.0\nswl = 200.0'],
        'kind = "upend"\nfrom = 0.0\nto = 90.0\npivot = [0.0, 0.0, 0.0]',
        cog=(20.0, 0.0, 0.0),
    )
    (line,) = sequence_warnings(loads_sequence(text))
    assert "boom_height, rope_length not used" in line


def test_a_stage_of_one_angle_holds_the_body_there():
    """from = to: a lift (or set-down) at one angle, one state, its loads the maxima."""
    text = sequence_text(
        [("A", (10.0, 0.0, 1.0), ""), ("B", (-10.0, 0.0, 1.0), "")],
        ['name = "East"\nlug = "A"', 'name = "West"\nlug = "B"'],
        'kind = "turnover"\nfrom = 30.0\nto = 30.0',
    )
    (stage,) = run_sequence(loads_sequence(text)).stages
    (state,) = stage.states
    share = W * (0.5 + 0.05 * math.tan(math.radians(30.0)))
    assert state.angle == 30.0 and state.hook_loads["East"] == pytest.approx(share, abs=1e-9 * W)
    assert stage.maxima["hook:East"].value == pytest.approx(share, abs=1e-9 * W)


def test_a_three_leg_sling_is_refused_with_its_reason():
    text = sequence_text(
        [("A", (10.0, 0.0, 0.0), ""), ("B", (-10.0, 1.0, 0.0), ""), ("C", (-10.0, -1.0, 0.0), "")],
        [
            'name = "K"\nsling = { legs = [{ lug = "A", length = 20.0, EA = 1e4 }, '
            '{ lug = "B", length = 20.0, EA = 1e4 }, { lug = "C", length = 20.0, EA = 1e4 }] }'
        ],
        'kind = "upend"\nfrom = 0.0\nto = 45.0\npivot = [0.0, 0.0, 0.0]',
    )
    with pytest.raises(InvalidScene, match="2-leg slings"):
        loads_sequence(text)


# -- planning the lugs ----------------------------------------------------------------------------

PLANNED = """
[body]
weight = 100.0
cog = [0.0, 0.0, 0.0]
[[lugs]]
name = "A"
at = [10.0, 0.0, 0.0]
capacity = 200.0
[[lugs]]
name = "B"
on = ["K1", "K2", "K3", "K4"]
[[candidates]]
name = "K1"
at = [-10.0, 0.0, 1.5]
[[candidates]]
name = "K2"
at = [-8.0, 0.0, 1.0]
capacity_out_of_plane = 1.0
normal = [1.0, 0.0, 0.0]
[[candidates]]
name = "K3"
at = [-10.0, 0.0, -1.0]
[[candidates]]
name = "K4"
at = [-6.0, 0.0, 0.0]
[[cranes]]
name = "East"
lug = "A"
[[cranes]]
name = "West"
lug = "B"
[sequence]
kind = "turnover"
from = 0.0
to = 60.0
step = 15.0
"""


def test_the_planned_lug_is_the_best_of_every_candidate_swept():
    """Every assignment swept in full, ranked as the planner ranks them (every check met, then
    the worst design lug load): the planner's choice is that one, and the bound it prunes by is
    never above an assignment's swept value."""
    from liftplan.model.sequence.file import loads_lug_choice
    from liftplan.model.sequence.lugplan import plan_lugs, worst_design_load

    choice = loads_lug_choice(PLANNED)
    plan = plan_lugs(choice)
    full = {}
    for cand in ("K1", "K2", "K3", "K4"):
        result = run_sequence(choice.sequence({"B": cand}))
        worst, _, mine = worst_design_load({s.stage.where: s.design for s in result.stages}, {"B"})
        full[cand] = (not all(c.ok for c in result.checks), round(worst, 6), round(mine[0], 6))
    assert plan.best.lugs == {"B": min(full, key=full.get)}
    assert plan.best.ok
    for option in plan.ranking:
        assert option.bound <= option.worst + 1e-9
    assert plan.options == 4


def test_a_file_that_plans_its_lugs_is_refused_by_the_plain_reader():
    with pytest.raises(InvalidScene, match="plans its lugs"):
        loads_sequence(PLANNED)

"""The last session's "seen, not fixed" list (task H14): each item's behaviour, held.

1. The design-load chain's tilt note says what its input is (the crane's worst tension over
   the heel/trim tolerance box and the CG envelope), not "the worst searched"; the planner's
   chain names its own input through the public :meth:`DesignLoadChain.factor_notes`.
2. Hinge rows of a ``PlanProblem`` built from Python are held to the planning file's guard: a
   lug pair that comes within 10 deg of plumb in the heel/trim box is refused in one line.
3. The flexible hull in water's casadi model is built once per discretisation and reused.
4. The console's per-rope tables at 64 ropes stay within 100 columns and are grouped.

Tolerances: where a cached model is compared with a fresh build, both solve the same equations
from the same start to the same Newton tolerance (1e-13 on residuals of order 1), so the
answers agree to round-off: 1e-9 relative is a wide margin that still catches a wrong parameter.
"""

from __future__ import annotations

import json

import pytest
from helpers import EXAMPLES, ROOT

from liftplan.model.rules import CraneLoads, DesignLoadChain, Rules


# -- 1. the chain's words ------------------------------------------------------------------
def _two_cranes(cog_searched=True):
    cranes = (
        CraneLoads("A", nominal=600.0, worst=612.0, tilt=630.0, swl=900.0),
        CraneLoads("B", nominal=400.0, worst=420.0, tilt=410.0, swl=900.0),
    )
    return DesignLoadChain(
        cranes, 1000.0, Rules(location="inshore"), cog_searched=cog_searched, tilt_note="3 deg governs"
    )


def _note(result, name):
    return next(f.note for f in result.factors if f.name == name)


def test_tilt_note_names_the_worst_tension_over_the_box_and_the_cg_envelope():
    chain = _two_cranes()
    note = _note(chain.result("A"), "tilt")
    assert "searched" not in note
    assert note == (
        "share at the rules' tilt 630 t against 612 t, the crane's worst tension over "
        "the heel/trim tolerance box and the CG envelope; 3 deg governs"
    )
    assert "in the worst tension (worst / nominal = 1.0200)" in _note(chain.result("A"), "cog")


def test_tilt_note_without_a_cg_envelope_says_the_box_only():
    chain = DesignLoadChain(
        _two_cranes().cranes, 1000.0, Rules(location="inshore", cog_factor=1.03), cog_searched=False
    )
    note = _note(chain.result("B"), "tilt")
    assert note == (
        "share at the rules' tilt 410 t against 420 t, the crane's worst tension over "
        "the heel/trim tolerance box (no CG envelope)"
    )


def test_chain_docstrings_do_not_say_worst_searched():
    import liftplan.model.rules.chain as chain
    from liftplan.planner.plans.design_loads import PlanChain

    for text in (chain.__doc__, chain.CraneLoads.__doc__, PlanChain.__doc__):
        assert "worst searched" not in text and "searched share" not in text


def test_plan_chain_uses_the_public_notes_hook_not_the_private_crane():
    """PlanChain overrides the documented :meth:`DesignLoadChain.factor_notes` (its own notes
    where it has a planner's load) and leaves the chain's private per-crane sums alone."""
    from liftplan.planner.plans.design_loads import PlanChain

    assert "_crane" not in vars(PlanChain)
    assert "factor_notes" in vars(PlanChain)
    assert DesignLoadChain.factor_notes.__doc__
    # a crane without a planner's load keeps the chain's own notes, and the sums are the chain's
    base = _two_cranes()
    plain = PlanChain(base.cranes, base.weight, base.rules, tilt_note=base.tilt_note)
    for a, b in zip(plain.results, base.results):
        assert a == b


def test_sling_plan_json_tilt_note_names_the_worst_tension(capsys):
    """The two-crane sling plan feeds the chain directly: its JSON notes are the chain's."""
    from liftplan.planner.cli import main

    assert main(["plan", str(EXAMPLES / "block_sling_plan.toml"), "--json"]) in (0, 4)
    text = capsys.readouterr().out
    assert "worst searched" not in text
    cranes = json.loads(text)["design_loads"]["cranes"]
    notes = [f["note"] for c in cranes for f in c["factors"] if f["name"] == "tilt"]
    assert len(notes) == 2
    assert all("the crane's worst tension over the heel/trim tolerance box" in n for n in notes)


# -- 2. hinge rows from Python meet the planning file's plumb rule ---------------------------
STEEP = 85.0  # deg from the horizontal: 85 + 2.83 (the +-2/+-2 box's tilt) > 80


def _steep_file(tmp_path):
    """The three-crawler 2-leg sling example with one more candidate 3 m below X+7.0-PO, on the
    same frame, so that the pair is 85 deg steep (and 3 m apart: the 8 m legs reach it)."""
    import math

    text = (EXAMPLES / "block_three_slings_plan.toml").read_text()
    dx = 3.0 / math.tan(math.radians(STEEP))
    extra = (
        f'\n[[candidates]]\nname = "STEEP"\nat = [{7.0 + dx!r}, 5.5, 0.0]\nbulkhead = "frame x = +7.0 m"\n'
    )
    text = text.replace("\n[plan]", extra + "\n[plan]", 1)
    path = tmp_path / "steep.toml"
    path.write_text(text)
    return path


def test_file_path_rules_the_steep_pair_out_and_its_derived_problem_passes_the_guard(tmp_path):
    from liftplan.planner import load_problem
    from liftplan.planner.plans.slings.apex import apex_problem

    problem = load_problem(_steep_file(tmp_path))
    derived, rigs = apex_problem(problem)  # builds PlanProblem(..., hinges=...) itself
    steep = problem.names.index("STEEP")
    assert not any(steep in pair for pair in rigs.lugs.tolist())
    reason = [k for k in rigs.ruled_out if "plumb" in k]
    assert len(reason) == 1 and rigs.ruled_out[reason[0]] >= 1
    assert len(derived.hinges) == len(rigs.lugs) > 0


def test_python_hinges_with_a_pair_near_plumb_are_refused_in_one_line(tmp_path):
    """The same pair given as a hinge row from Python: refused where the problem is built (it
    was accepted, and the plan's tensions went NaN or the search crashed)."""
    import dataclasses

    import numpy as np

    from liftplan.model.errors import InvalidScene
    from liftplan.planner import load_problem
    from liftplan.planner.plans.slings.apex import apex_problem

    problem = load_problem(_steep_file(tmp_path))
    derived, _ = apex_problem(problem)
    rows = np.array(derived.hinges)
    pts = problem.points
    rows[2, 0:3] = pts[problem.names.index("X+7.0-PO")]
    rows[2, 3:6] = pts[problem.names.index("STEEP")]
    with pytest.raises(InvalidScene) as err:
        dataclasses.replace(derived, hinges=tuple(map(tuple, rows)))
    text = str(err.value)
    assert "\n" not in text
    name = derived.names[2]
    assert text.startswith(f"hinges[2] ({name}): the lug pair A (7, 5.5, 3) B (")
    assert f"is {STEEP:.2f} deg from the horizontal" in text
    assert "heel/trim box (+-2, +-2 deg) tilts it by up to 2.83 deg" in text
    assert "steepest 87.00 deg at heel 0.00, trim 2.00 deg" in text  # the pair leans forward
    assert "expected a pair less than 77.17 deg from the horizontal" in text
    # exactly plumb, and one point
    rows[2, 3:6] = rows[2, 0:3] + [0.0, 0.0, 2.0]
    with pytest.raises(InvalidScene, match=r"hinges\[2\] .* is 90.00 deg from the horizontal"):
        dataclasses.replace(derived, hinges=tuple(map(tuple, rows)))
    rows[2, 3:6] = rows[2, 0:3]
    with pytest.raises(InvalidScene, match=r"hinges\[2\] .* is one point: expected two lugs apart"):
        dataclasses.replace(derived, hinges=tuple(map(tuple, rows)))
    # 75 deg is off plumb in this box (75 + 2.83 < 80): accepted
    rows[2, 3:6] = rows[2, 0:3] + [2.0 / np.tan(np.radians(75.0)), 0.0, 2.0]
    dataclasses.replace(derived, hinges=tuple(map(tuple, rows)))


def test_python_guard_names_the_pair_in_the_files_frame():
    """A ``choi``-frame problem shows the pair as written (x, y up, z to starboard)."""
    import dataclasses

    from liftplan.model.errors import InvalidScene
    from liftplan.model.statics.model import fixed_hinges
    from liftplan.planner import load_problem

    problem = load_problem(EXAMPLES / "tanker_plan.toml")  # frame = "choi"
    rows = fixed_hinges(problem.points)
    rows[1, 3:6] = rows[1, 0:3] + [0.0, 0.0, 1.0]  # z-up: straight up
    with pytest.raises(InvalidScene) as err:
        dataclasses.replace(problem, hinges=tuple(map(tuple, rows)))
    # BH1-S is at (4.2, 6, 12) in the file; one metre up is +y in the papers' frame
    assert "hinges[1] (BH1-S): the lug pair A (4.2, 6, 12) B (4.2, 7, 12) m" in str(err.value)


@pytest.mark.parametrize("heel, trim", [(0.0, 0.0), (2.0, 1.0), (5.0, 5.0), (20.0, 3.0)])
def test_python_guard_is_the_sling_planners_rule(heel, trim):
    """The sling planner rules pairs out by the model's :func:`near_plumb` itself (one rule, so
    neither path accepts what the other refuses), and that rule is the inclination plus the
    box's tilt against 90 deg - the margin, checked on 20 000 random pairs (seeded)."""
    import numpy as np

    from liftplan.model.statics.model import PLUMB_MARGIN, near_plumb
    from liftplan.planner.plans.slings.rigs import plumb_in_box

    assert plumb_in_box is near_plumb
    rng = np.random.default_rng(14)
    a = rng.uniform(-10.0, 10.0, (20000, 3))
    b = a + rng.normal(size=(20000, 3)) * [1.0, 1.0, 4.0]
    d = b - a
    incline = np.degrees(np.arctan2(np.abs(d[:, 2]), np.hypot(d[:, 0], d[:, 1])))
    tilt = np.degrees(np.arccos(np.cos(np.radians(heel)) * np.cos(np.radians(trim))))
    expected = incline + tilt >= 90.0 - PLUMB_MARGIN
    mine = near_plumb(a, b, heel, trim)
    assert np.array_equal(mine, expected) and 0 < mine.sum() < len(a)


# -- 3. the flexible hull in water: public helpers, and its model built once -----------------
def test_flexible_water_imports_no_private_helpers():
    """flexible_water.py takes the water model's rotation and result assembly by their public,
    documented names (it imported ``_rotation`` and ``_result``)."""
    import ast

    import liftplan.model.water.equilibrium as equilibrium

    tree = ast.parse((ROOT / "model" / "strength" / "flexible_water.py").read_text())
    taken = [
        alias.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) for alias in node.names
    ]
    assert "tilted_rotation" in taken and "equilibrium_result" in taken
    assert not [name for name in taken if name.startswith("_") and name != "_GAUSS3"]
    for name in ("tilted_rotation", "equilibrium_result"):
        assert "Parameters" in getattr(equilibrium, name).__doc__
    assert equilibrium._rotation is equilibrium.tilted_rotation  # the package still exports it


def _bow_lift(ei, boom=40.0):
    """The stranded barge grounded at the stern, lifted at the bow by four cranes (the scene of
    studies/flexible_ground.py), hooks at ``boom``."""
    from liftplan.model.scene.file import loads_scene

    text = (EXAMPLES / "stranded_barge.toml").read_text()
    text = text.replace(
        "cog = [5.0, 0.0, 2.0]", "cog = [5.0, 0.0, 2.0]\nweight_curve = [[-50.0, 140.0], [50.0, 260.0]]"
    )
    text = text.replace("[ground]", f"EI = [[-50.0, {ei!r}]]\n\n[ground]")
    text = text.replace("contact = [30.0, -2.0, -5.0]", "contact = [-45.0, 0.0, -5.0]")
    text += '\n[analysis]\nhull = "flexible"\n'
    for k, (x, y) in enumerate(((40.0, 10.0), (48.0, 10.0), (48.0, -10.0), (40.0, -10.0))):
        text += (
            f'\n[[lugs]]\nname = "B{k + 1}"\nat = [{x}, {y}, 5.0]\n\n[[cranes]]\nlug = "B{k + 1}"\n'
            f"boom_height = {boom + 0.01 * k!r}\nrope_length = 35.0\nEA = 50000.0\nswl = 2000.0\n"
        )
    return loads_scene(text, base=EXAMPLES)


def _numbers(eq):
    return [
        *eq.tensions.values(),
        eq.afloat.ground_reaction,
        eq.afloat.buoyancy,
        eq.pose.heel,
        eq.pose.trim,
        eq.flexible_hull.max_deflection.signed,
    ]


@pytest.mark.slow  # 8-12 s: the default run keeps under 10 minutes
def test_flexible_hull_in_water_builds_its_model_once_per_discretisation():
    """A second scene of the same discretisation (another EI, other hook heights) solves on the
    model built for the first (no new build: ~1.8 s a scene before), and gives what a fresh
    build gives."""
    import liftplan.model.strength.flexible_water as fw
    from liftplan.model import solve

    fw.water_beam_model.cache_clear()
    first = solve(_bow_lift(7e8))
    built = fw.water_beam_model.cache_info()
    assert first.flexible_hull.used == "flexible" and built.misses >= 1
    other = _bow_lift(2.1e9, boom=40.2)
    again = solve(other)
    reused = fw.water_beam_model.cache_info()
    assert reused.misses == built.misses and reused.hits > built.hits
    fw.water_beam_model.cache_clear()
    fresh = solve(other)
    assert fw.water_beam_model.cache_info().misses >= 1
    assert _numbers(again) == pytest.approx(_numbers(fresh), rel=1e-9, abs=1e-9)
    assert _numbers(again) != pytest.approx(_numbers(first), rel=1e-6)  # other numbers went in


# -- 4. the console at many ropes: 100 columns, long tables in groups ------------------------
def test_fold_and_grouped():
    from liftplan.planner.output.console.text import fold, grouped

    rows = [f"row {k}" for k in range(20)]
    out = grouped(rows)
    assert out[8] == "" and out[17] == "" and [r for r in out if r] == rows
    assert grouped(rows[:16]) == rows[:16]  # two groups or fewer: as they are
    line = (
        "spread: nominal 44.73 t, worst 66.56 t at heel +1.00 deg, trim +0.50 deg, CG (-5.00, 0.60, 7.00) m"
    )
    folded = fold(line, width=80)
    assert folded == [
        "spread: nominal 44.73 t, worst 66.56 t at heel +1.00 deg, trim +0.50 deg,",
        "  CG (-5.00, 0.60, 7.00) m",
    ]  # the point stays on one line
    assert fold("short") == ["short"]


def _check_console(text, n):
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= 100
    head = next(k for k, line in enumerate(lines) if line.startswith("lug  candidate crane"))
    rows = lines[head + 2 : head + 2 + n + (n - 1) // 8]
    assert [line for line in rows if line][0].startswith("L1 ")
    assert [line.split()[0] for line in rows if line] == [f"L{k + 1}" for k in range(n)]
    assert all(rows[k] == "" for k in range(8, len(rows), 9))  # groups of eight
    for title in ("worst in the box (CG in the file's frame):", "at the rules' tilt"):
        at = next(k for k, line in enumerate(lines) if line.startswith(title))
        assert lines[at + 2].split()[0] == "L1" and lines[at + 10] == ""
    sensitivity = next(k for k, line in enumerate(lines) if line.startswith("tension change per cm"))
    cells = lines[sensitivity + 1].split()
    assert cells[0] == "L1" and cells[14] == "L8" and len(cells) == 16  # eight hooks a line
    rank = next(k for k, line in enumerate(lines) if line.startswith("rank "))
    assert lines[rank].endswith("lugs (crane)") and lines[rank + 1].startswith("1 ")


def test_plan_console_at_26_ropes_fits_100_columns_in_groups():
    from liftplan.planner import load_problem, plan
    from liftplan.planner.output.console.summary import summary as plan_table

    _check_console(plan_table(plan(load_problem(EXAMPLES / "hull154_26_given.toml"))), 26)


@pytest.mark.slow
def test_plan_and_solve_consoles_at_64_ropes(capsys):
    """``liftplan plan examples/hull154_64_given.toml`` (~15 s) and the 64-rope solve table."""
    from liftplan.planner.cli import main

    assert main(["plan", str(EXAMPLES / "hull154_64_given.toml")]) == 0
    _check_console(capsys.readouterr().out, 64)
    assert main(["solve", str(EXAMPLES / "hull154_64_points.toml")]) == 0
    lines = capsys.readouterr().out.splitlines()
    table = lines[lines.index("") + 4 :]
    assert max(len(line) for line in table) <= 100  # the rows (the summary lines are text)


def test_sling_console_fits_100_columns():
    from liftplan.planner import load_problem, plan
    from liftplan.planner.output.console.summary import summary as plan_table

    text = plan_table(plan(load_problem(EXAMPLES / "block_sling_plan.toml")))
    assert max(len(line) for line in text.splitlines()) <= 100
    assert "ruled out: 4 beyond the crane's reach" in text

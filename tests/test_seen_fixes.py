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
from pathlib import Path

from liftplan.model.rules import CraneLoads, DesignLoadChain, Rules

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


# -- 1. the chain's words ------------------------------------------------------------------
def _two_cranes(cog_searched=True):
    cranes = (CraneLoads("A", nominal=600.0, worst=612.0, tilt=630.0, swl=900.0),
              CraneLoads("B", nominal=400.0, worst=420.0, tilt=410.0, swl=900.0))
    return DesignLoadChain(cranes, 1000.0, Rules(location="inshore"), cog_searched=cog_searched,
                           tilt_note="3 deg governs")


def _note(result, name):
    return next(f.note for f in result.factors if f.name == name)


def test_tilt_note_names_the_worst_tension_over_the_box_and_the_cg_envelope():
    chain = _two_cranes()
    note = _note(chain.result("A"), "tilt")
    assert "searched" not in note
    assert note == ("share at the rules' tilt 630 t against 612 t, the crane's worst tension over "
                    "the heel/trim tolerance box and the CG envelope; 3 deg governs")
    assert "in the worst tension (worst / nominal = 1.0200)" in _note(chain.result("A"), "cog")


def test_tilt_note_without_a_cg_envelope_says_the_box_only():
    chain = DesignLoadChain(_two_cranes().cranes, 1000.0, Rules(location="inshore", cog_factor=1.03),
                            cog_searched=False)
    note = _note(chain.result("B"), "tilt")
    assert note == ("share at the rules' tilt 410 t against 420 t, the crane's worst tension over "
                    "the heel/trim tolerance box (no CG envelope)")


def test_chain_docstrings_do_not_say_worst_searched():
    import liftplan.model.rules.chain as chain
    from liftplan.planner.design_loads import PlanChain

    for text in (chain.__doc__, chain.CraneLoads.__doc__, PlanChain.__doc__):
        assert "worst searched" not in text and "searched share" not in text


def test_plan_chain_uses_the_public_notes_hook_not_the_private_crane():
    """PlanChain overrides the documented :meth:`DesignLoadChain.factor_notes` (its own notes
    where it has a planner's load) and leaves the chain's private per-crane sums alone."""
    from liftplan.planner.design_loads import PlanChain

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

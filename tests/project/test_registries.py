"""The tables where the code grows (issue 30 item 4, docs/architecture.md): each lists its
implementations once, and every list a user can name agrees with it."""

from __future__ import annotations

import typing

import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import Rules
from liftplan.model.rules.codes import CODES, INTERFACE
from liftplan.model.scene.objects import MODELS
from liftplan.model.solve import ROPE_MODELS
from liftplan.planner.output.console.summary import SUMMARIES
from liftplan.planner.output.report.write import PAGES
from liftplan.planner.plan import KINDS, plan_kind
from liftplan.planner.plans.held import Plan
from liftplan.planner.plans.protocol import LiftPlan
from liftplan.planner.plans.slings import ApexSlingPlan, SlingPlan
from liftplan.planner.plans.strength import StrengthPlan
from liftplan.planner.problem.definition import SEARCHES
from liftplan.planner.problem.file import _PlanFile, load_problem
from liftplan.planner.problem.objectives import OBJECTIVES, SHAPES
from liftplan.planner.search.methods import METHODS


def test_every_rope_model_a_file_may_name_has_a_solver():
    assert set(ROPE_MODELS) == set(MODELS)


def test_every_search_a_file_may_name_is_a_method_or_auto():
    assert set(METHODS) | {"auto"} == set(SEARCHES)


def test_the_objectives_table_is_the_files_choices():
    plan_table = typing.get_type_hints(_PlanFile)["plan"]
    plan_table = typing.get_args(plan_table)[0] if typing.get_args(plan_table) else plan_table
    choices = typing.get_args(typing.get_args(plan_table.model_fields["objective"].annotation)[0])
    assert set(choices) == set(OBJECTIVES)
    assert {o.shape for o in OBJECTIVES.values()} <= set(SHAPES)


def test_every_rules_code_implements_the_interface():
    for name, (title, module) in CODES.items():
        assert title
        missing = [attr for attr in INTERFACE if not hasattr(module, attr)]
        assert missing == [], name
        assert Rules(code=name).factors is module
    with pytest.raises(InvalidScene, match="rules.code = 'DNV': expected one of 0027/ND"):
        Rules(code="DNV")


def test_every_kind_of_plan_has_its_outputs_and_the_interface():
    names = [kind.name for kind in KINDS]
    assert len(set(names)) == len(names)
    assert set(SUMMARIES) == set(names) == set(PAGES)
    for result in (Plan, SlingPlan, ApexSlingPlan, StrengthPlan):
        for member in ("kind", "checks", "frame", "in_file_frame", "to_json"):
            assert hasattr(result, member), (result, member)


def test_a_plan_is_a_lift_plan_of_the_kind_chosen_in_one_place():
    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    assert plan_kind(problem).name == "held"
    from liftplan.planner.plan import plan

    result = plan(problem)
    assert isinstance(result, LiftPlan)
    assert result.kind == "held"
    assert SUMMARIES[result.kind](result).startswith("1500 GT tanker, lug planning")

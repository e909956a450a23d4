"""The public API as a user's script calls it: type-checked by mypy (``.ci/typecheck``),
never run (pytest collects only ``test_*.py``). A signature or result attribute whose type
changes so that this script would break fails the type check."""

from pathlib import Path

from liftplan.model import Equilibrium, Scene, __version__, load_scene, loads_scene, solve
from liftplan.planner import Plan, PlanProblem, ReportFiles, load_problem, loads_problem, plan, write_report

version: str = __version__

scene: Scene = load_scene("examples/tanker_upright.toml")
scene = load_scene(Path("examples") / "tanker_upright.toml")
scene = loads_scene(Path("examples/tanker_upright.toml").read_text(), base=Path("examples"))
eq: Equilibrium = solve(scene)
eq = solve(scene, model="rigid")
tension: float = eq.tensions["T1"]
heel: float = eq.pose.heel
weight: float = eq.weight

problem: PlanProblem = load_problem("examples/tanker_plan.toml")
problem = loads_problem(Path("examples/tanker_plan.toml").read_text(), base="examples")
result = plan(problem, top=3)
if isinstance(result, Plan):
    lugs: dict[str, str] = result.lugs
    heights: dict[str, float] = result.boom_heights
    tensions: dict[str, float] = result.tensions
    spread: float = result.spread + result.worst_spread
files: ReportFiles = write_report(result, "out")
html: Path = files.html
pdf: Path | None = files.pdf

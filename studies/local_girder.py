"""What the hull girder inside the local search's moves costs, and what it finds.

Each case is planned by the local search (``search_local``, the method ``[plan] search =
"local"`` runs: its swaps, the exact evaluation of its set, its lower bound) twice in one run,
alternately, REPEAT times each, the least time kept:

* ``without``: today's method before the change: the search on the objective alone (the
  problem without ``[strength]``, so the search does not see the girder), then the plan's girder
  check of the set it ends on (:func:`~liftplan.planner.search.girder.set_girder` on the dense
  grid, what the plan adds after any search);
* ``with``: the search with the girder in its moves (planner/search/local_girder.py), whose
  set's girder is then checked the same way.

Cases: the 1500 GT tanker (examples/tanker_plan.toml, 16 candidates, four equal cranes) with
the weight curve and allowables of examples/tanker_strength.toml, (a) as
studies/combinations.py plans the ``girder`` x ``search_local`` cell (no CG box, no hook
tolerance, a CoG factor of 1.03), (b) the example as it is (CG box, hook tolerance 0.02 m),
(c) case (a) on the ten candidates of stations BH1, BH2, BH3, BH7 and BH8 (the test's case,
tests/planner/test_local_girder.py), (d) case (a) with five and (e) six cranes.

Run:  python studies/local_girder.py        (writes studies/out/local_girder.md and .json)
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).parent
ROOT = HERE.parent
OUT = HERE / "out"
REPEAT = 3
#: The test's ten candidates: stations BH1, BH2, BH3, BH7, BH8 (port and starboard each).
TEN = ("BH1", "BH2", "BH3", "BH7", "BH8")


def _document(plain):
    """The tanker planning file with the girder (``plain``: the combinations study's base)."""
    doc = tomllib.loads((ROOT / "examples" / "tanker_plan.toml").read_text(encoding="utf-8"))
    strength = tomllib.loads((ROOT / "examples" / "tanker_strength.toml").read_text(encoding="utf-8"))
    doc.pop("report", None)
    doc["body"]["weight_curve"] = strength["body"]["weight_curve"]
    doc["strength"] = strength["strength"]
    doc["plan"]["search"] = "local"
    if plain:
        for key in ("hook_tolerance", "cog_tolerance", "cog_envelope"):
            doc["plan"].pop(key, None)
        doc.setdefault("rules", {})["cog_factor"] = 1.03
    return doc


def cases():
    from liftplan.planner.problem.file import loads_problem

    def problem(doc):
        import tomli_w

        return loads_problem(tomli_w.dumps(doc))

    plain = problem(_document(True))
    ten = dataclasses.replace(
        plain, candidates=tuple(c for c in plain.candidates if c.name.split("-")[0] in TEN)
    )
    yield "tanker 4 of 16, no CG box (combinations' cell)", plain
    yield "tanker 4 of 16, CG box, hook 0.02 m (the example)", problem(_document(False))
    yield "tanker 4 of 10 (the test's case)", ten
    yield "tanker 5 of 16, no CG box", dataclasses.replace(plain, cranes=5)
    yield "tanker 6 of 16, no CG box", dataclasses.replace(plain, cranes=6)


def run(problem, aware):
    """(seconds, result, girder ratio) of one local search and its set's girder check."""
    from liftplan.planner.search.evaluator import SetEvaluator
    from liftplan.planner.search.girder import set_girder
    from liftplan.planner.search.local import search_local

    searched = problem if aware else dataclasses.replace(problem, strength=None)
    started = time.perf_counter()
    ranking, _ = search_local(searched, started)
    worst = set_girder(problem, ranking[0], SetEvaluator(problem).dense)
    seconds = time.perf_counter() - started
    return seconds, ranking[0], max(w.ratio for w in worst)


def main():
    rows = []
    for name, problem in cases():
        times = {False: [], True: []}
        out = {}
        for _ in range(REPEAT):
            for aware in (False, True):
                seconds, result, ratio = run(problem, aware)
                times[aware].append(seconds)
                out[aware] = {
                    "lugs": list(result.lugs),
                    "worst": result.worst_value,
                    "girder_ratio": ratio,
                }
        row = {
            "case": name,
            "without_s": min(times[False]),
            "with_s": min(times[True]),
            "ratio": min(times[True]) / min(times[False]),
            "without": out[False],
            "with": out[True],
        }
        rows.append(row)
        print(json.dumps(row), flush=True)
    OUT.mkdir(exist_ok=True)
    stamp = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    data = json.dumps({"run": stamp, "rows": rows}, indent=1)
    (OUT / "local_girder.json").write_text(data, encoding="utf-8")
    lines = [
        f"Run {stamp}, least of {REPEAT} each, alternately, one process.",
        "",
        "| case | without [s] | with [s] | ratio | without: worst, girder | with: worst, girder |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        a, b = r["without"], r["with"]
        lines.append(
            f"| {r['case']} | {r['without_s']:.2f} | {r['with_s']:.2f} | {r['ratio']:.2f}x | "
            f"{a['worst']:.2f} t, {a['girder_ratio']:.0%} | {b['worst']:.2f} t, {b['girder_ratio']:.0%} |"
        )
    (OUT / "local_girder.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())

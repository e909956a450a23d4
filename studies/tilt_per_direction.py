"""The rules' multi-hook tilt taken per direction against over the least hook spacing (issue 11).

0027/ND Rev 11 5.4 / Appendix B.1.2 turn a +-1.0 m hook elevation difference into a tilt
asin(1.0 / L) over the distance L between the hooks. With more than two hooks the design-load
chain used the least plan distance between any two hooks about every tilt axis; per direction,
L is the hooks' spacing along the direction the body tilts (``TiltGeometry.tilt_along``). On the
tanker fleet's plan (examples/tanker_fleet.toml) this prints, per crane, the worst load at the
rules' tilt both ways, for the fleet's separate vessels (5 deg) and for one vessel (3 deg).

Run: python studies/tilt_per_direction.py  -> studies/out/tilt_per_direction.md
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from liftplan.model.rules import TiltGeometry, governing_tilt
from liftplan.planner import load_problem, plan

OUT = Path(__file__).resolve().parent / "out"


def compare(result, separate_vessels):
    """Rows (crane, nominal, least-spacing tilt and load, per-direction tilt and load)."""
    problem = result.problem
    rules = dataclasses.replace(problem.rules, separate_vessels=separate_vessels)
    lugset = result.lugset
    names = lugset.crane_names
    preload = np.asarray(result.chosen.preload, dtype=float)
    geometry = TiltGeometry(
        {n: tuple(p) for n, p in zip(names, lugset.points)},
        problem.body.cog,
        problem.body.weight,
        preload=dict(zip(names, preload.tolist())),
        stiffness=dict(zip(names, lugset.stiffness.tolist())),
    )
    tilt, elevation = rules.design_tilt()
    offsets = [tuple(map(float, o)) for o in problem.cog_envelope.offsets()]
    vertices = offsets[1:] if len(offsets) > 1 else offsets
    least = governing_tilt(tilt, elevation, geometry.least_spacing())
    old = geometry.worst(least, vertices)
    new = geometry.worst_per_direction(tilt, elevation, vertices)
    header = (
        f"rules' tilt {tilt:g} deg, hook elevation {elevation:g} m; least hook spacing "
        f"{geometry.least_spacing():.2f} m -> {least:.2f} deg about every axis; spacing along "
        f"the heel tilt {geometry.spacing_along(0.0):.2f} m, along the trim tilt "
        f"{geometry.spacing_along(90.0):.2f} m"
    )
    rows = [
        (n, p, old[n].tilt, old[n].load, new[n].tilt, new[n].direction, new[n].load)
        for n, p in zip(names, preload)
    ]
    return header, rows


def main():
    result = plan(load_problem(Path(__file__).resolve().parents[1] / "examples" / "tanker_fleet.toml"))
    lines = [
        "# The rules' tilt per direction on the tanker fleet's plan",
        "",
        "Plan: " + ", ".join(f"{lab} {lug}" for lab, lug in result.lugs.items()),
        "",
    ]
    for separate in (True, False):
        header, rows = compare(result, separate)
        lines += [
            f"## {'separate vessels' if separate else 'one vessel'}",
            "",
            header,
            "",
            "| crane | level [t] | least-spacing tilt [deg] | load [t] | per-direction tilt [deg] "
            "| axis [deg from +x] | load [t] | change [t] |",
            "|---|---|---|---|---|---|---|---|",
        ]
        lines += [
            f"| {n} | {p:.2f} | {t0:.2f} | {l0:.2f} | {t1:.2f} | {d1:.1f} | {l1:.2f} | {l1 - l0:+.2f} |"
            for n, p, t0, l0, t1, d1, l1 in rows
        ]
        lines.append("")
    OUT.mkdir(exist_ok=True)
    (OUT / "tilt_per_direction.md").write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main()

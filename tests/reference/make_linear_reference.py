"""High-precision reference for the linear models (rigid, paper-elastic), 50 digits.

An independent implementation in mpmath, from the equations as written in the papers and
CONTRACT.md: the paper-elastic case solves the full (n + 3) x (n + 3) system in T and the
plane coefficients (the library solves a reduced 3 x 3 system instead).

Run:  python tests/reference/make_linear_reference.py   (rewrites linear_reference.json)
"""

import json
from pathlib import Path

import mpmath as mp

mp.mp.dps = 50

CASES = [
    {
        "name": "tanker upright level",
        "heel": 0,
        "trim": 0,
        "yaw": 0,
        "lift": 1,
        "weight": 904,
        "cog": [35.86, -6, 2.5],
        "lugs": [[16.2, -12, 6], [65.6, -12, 6], [65.6, 0, 6], [16.2, 0, 6]],
        "EA": [50000] * 4,
        "H": [40] * 4,
        "held": {"3": 272.0},
    },
    {
        "name": "tanker upright heel 3 trim -2",
        "heel": 3,
        "trim": -2,
        "yaw": 0,
        "lift": 1,
        "weight": 904,
        "cog": [35.86, -6, 2.5],
        "lugs": [[16.2, -12, 6], [65.6, -12, 6], [65.6, 0, 6], [16.2, 0, 6]],
        "EA": [50000] * 4,
        "H": [40] * 4,
        "held": {"3": 260.0},
    },
    {
        "name": "tanker upright heel -10 trim 10",
        "heel": -10,
        "trim": 10,
        "yaw": 0,
        "lift": 2,
        "weight": 904,
        "cog": [35.86, -6, 2.5],
        "lugs": [[16.2, -12, 6], [65.6, -12, 6], [65.6, 0, 6], [16.2, 0, 6]],
        "EA": [50000, 40000, 60000, 50000],
        "H": [40, 41, 39, 40.5],
        "held": {"3": 300.0},
    },
    {
        "name": "tanker capsized heel -2 trim 1",
        "heel": -2,
        "trim": 1,
        "yaw": 0,
        "lift": 1,
        "weight": 904,
        "cog": [35.86, -2.5, 6],
        "lugs": [[16.2, -4.78, 12], [65.6, -4.78, 12], [65.6, -1.22, 12], [16.2, -1.22, 12]],
        "EA": [50000] * 4,
        "H": [46] * 4,
        "held": {"3": 335.0},
    },
    {
        "name": "five lugs, yaw 10",
        "heel": 4,
        "trim": -3,
        "yaw": 10,
        "lift": 0.5,
        "weight": 500,
        "cog": [1, 0.5, 1.5],
        "lugs": [[10, 6, 4], [12, -5, 3], [-8, -6, 5], [-11, 4, 4], [0, 8, 2]],
        "EA": [30000, 35000, 30000, 25000, 40000],
        "H": [30, 31, 29, 30, 32],
        "held": {"2": 100.0, "4": 90.0},
    },
    {
        "name": "six lugs, uneven",
        "heel": -7,
        "trim": 6,
        "yaw": -15,
        "lift": 3,
        "weight": 1200,
        "cog": [2, -1, 2],
        "lugs": [[20, 8, 6], [20, -8, 6], [0, -9, 7], [-20, -8, 6], [-20, 8, 6], [0, 9, 5]],
        "EA": [60000] * 6,
        "H": [45, 45.5, 44, 46, 45, 44.5],
        "held": {"1": 200.0, "2": 210.0, "5": 190.0},
    },
]


def rotation(heel, trim, yaw):
    h, t, y = (mp.radians(mp.mpf(a)) for a in (heel, trim, yaw))
    rx = mp.matrix([[1, 0, 0], [0, mp.cos(h), -mp.sin(h)], [0, mp.sin(h), mp.cos(h)]])
    rz = mp.matrix([[mp.cos(y), -mp.sin(y), 0], [mp.sin(y), mp.cos(y), 0], [0, 0, 1]])
    ry = mp.matrix([[mp.cos(t), 0, mp.sin(t)], [0, 1, 0], [-mp.sin(t), 0, mp.cos(t)]])
    return rx * rz * ry


def world(case):
    rot = rotation(case["heel"], case["trim"], case["yaw"])
    lift = mp.mpf(case["lift"])
    lugs = [rot * mp.matrix([mp.mpf(str(v)) for v in p]) for p in case["lugs"]]
    cog = rot * mp.matrix([mp.mpf(str(v)) for v in case["cog"]])
    return lugs, cog, lift


def statics_rows(case, lugs, cog):
    weight = mp.mpf(str(case["weight"]))
    rows = [[mp.mpf(1)] * len(lugs), [p[0] for p in lugs], [p[1] for p in lugs]]
    rhs = [weight, weight * cog[0], weight * cog[1]]
    return rows, rhs


def rigid(case):
    lugs, cog, _ = world(case)
    n = len(lugs)
    rows, rhs = statics_rows(case, lugs, cog)
    for index, tension in case["held"].items():
        rows.append([mp.mpf(1) if j == int(index) else mp.mpf(0) for j in range(n)])
        rhs.append(mp.mpf(str(tension)))
    return mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))


def paper_elastic(case):
    """Unknowns (T_1..T_n, c0, c1, c2): statics, and T_i l_i / EA_i = c0 + c1 x_i + c2 y_i."""
    lugs, cog, lift = world(case)
    n = len(lugs)
    rows, rhs = statics_rows(case, lugs, cog)
    rows = [r + [0, 0, 0] for r in rows]
    for i, p in enumerate(lugs):
        length = mp.mpf(str(case["H"][i])) - lift - p[2]
        row = [mp.mpf(0)] * (n + 3)
        row[i] = length / mp.mpf(str(case["EA"][i]))
        row[n:] = [-1, -p[0], -p[1]]
        rows.append(row)
        rhs.append(mp.mpf(0))
    return mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))[:n]


def main():
    out = []
    for case in CASES:
        n = len(case["lugs"])
        out.append(
            {
                **case,
                "rigid": [mp.nstr(v, 30) for v in rigid(case)],
                "paper_elastic": [mp.nstr(paper_elastic(case)[i], 30) for i in range(n)],
            }
        )
    path = Path(__file__).with_name("linear_reference.json")
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {len(out)} cases to {path}")


if __name__ == "__main__":
    main()

"""Shared helpers of the tests."""

from pathlib import Path

import numpy as np

from liftplan.model import load_scene

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def example(name):
    """A scene from examples/ by file stem."""
    return load_scene(EXAMPLES / f"{name}.toml")


def three_supports(x1, springs, ei, q, x0, x2):
    """Reactions of a uniform beam on three spring supports at its ends and at x1 (closed form).

    Three-moment equation (Clapeyron) with support settlements: for spans l1 = x1 - x0,
    l2 = x2 - x1 of constant EI under a uniform load q (down), M sagging-positive, ends free
    (M0 = M2 = 0), the slopes of the two spans agree at the middle support when

        2 M1 (l1 + l2) = -q (l1^3 + l2^3) / 4 + 6 EI [(d1 - d0) / l1 + (d1 - d2) / l2]

    (d_i the supports' downward settlements): the rotation of a simply supported span's end
    is q l^3 / (24 EI) from the load and M l / (3 EI) from an end moment, and a settlement
    difference turns the chord by (d_i - d_j) / l; adding both spans' rotations at support 1
    and setting them equal gives the line above. Each span's free body gives the reactions
    R0 = q l1 / 2 + M1 / l1, R2 = q l2 / 2 + M1 / l2, R1 = q (l1 + l2) - R0 - R2, and the
    springs close it: d_i = R_i / K_i. The equation is linear in M1; solved exactly.
    With rigid supports (d = 0) and equal spans it gives M1 = -q l^2 / 8 and the textbook
    reactions 3 q l / 8, 10 q l / 8, 3 q l / 8.
    """
    l1, l2 = x1 - x0, x2 - x1

    def reactions(m1):
        r0, r2 = q * l1 / 2 + m1 / l1, q * l2 / 2 + m1 / l2
        return np.array([r0, q * (l1 + l2) - r0 - r2, r2])

    def mismatch(m1):
        d = reactions(m1) / np.asarray(springs, dtype=float)
        return (
            2 * m1 * (l1 + l2) + q * (l1**3 + l2**3) / 4 - 6 * ei * ((d[1] - d[0]) / l1 + (d[1] - d[2]) / l2)
        )

    f0 = mismatch(0.0)
    m1 = -f0 / (mismatch(1.0) - f0)
    return reactions(m1), m1

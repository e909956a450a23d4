"""The rules' design-load chain (liftplan.model.rules) against 0027/ND Rev 11's printed numbers,
an independent statics check, and the hand calculations of docs/design-loads.md.

Printed numbers are compared to the digits the document prints; computed quantities to the
closed forms written out here (independently of the library) to float64 rounding.
"""

import json
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.rules import (
    CraneLoads,
    DesignLoadChain,
    LugLoads,
    Rules,
    TiltGeometry,
    code_margin,
    cog_factor,
    dynamic_amplification,
    governing_tilt,
    read_rules,
    rules_tilt,
    skew_factor,
    sling_stiffness,
    yaw_factor,
)
from liftplan.model.rules.tilt import rotation_about
from liftplan.model.statics.model import Layout, rope_model

# Closed forms and lever-rule sums below are a handful of float64 operations: they agree with
# the library to a few ulp of the loads (~1e-13 t), so 1e-9 leaves ample margin and still
# catches any real difference.
EXACT = dict(rtol=1e-12, atol=1e-9)


def printed(value, digits):
    """``value`` rounded as a document prints it (``digits`` after the point)."""
    return round(value, digits)


# ---- 0027/ND Rev 11 Appendix B.1 worked example ------------------------------------------
# B.1.2: cranes on one vessel (5.4.2), L = 25.0 m, c = 12.0, d = 13.0, a = 10.0, b = 14.0,
# x = 0.9, z = 0.8 (m). B.1.5 (p. 83 of 84): B = 20.0, e = 11.0, f = 9.0, y = 0.6 (m).
ND = dict(L=25.0, c=12.0, d=13.0, a=10.0, b=14.0, x=0.9, z=0.8, B=20.0, e=11.0, f=9.0, y=0.6)


def nd_crane_loads(alpha_deg, p=ND):
    """0027/ND Rev 11 B.1.2 formulae, per unit weight: (crane #1, crane #2)."""
    al = math.radians(alpha_deg)
    s, c = math.sin(al), math.cos(al)
    one = ((p["b"] + p["z"]) * s + (p["d"] + p["x"]) * c) / (p["L"] * c + (p["b"] - p["a"]) * s)
    two = ((p["a"] + p["z"]) * s + (p["c"] + p["x"]) * c) / (p["L"] * c - (p["b"] - p["a"]) * s)
    return one, two


def nd_geometry(weight=1.0, p=ND):
    """Figure 19B-1 in the z-up frame: crane #1's lift points at x = 0, crane #2's at x = L and
    b - a higher, the CoG c from crane #1 and a below its lift points."""
    return TiltGeometry(
        {"crane1": (0.0, 0.0, 0.0), "crane2": (p["L"], 0.0, p["b"] - p["a"])}, (p["c"], 0.0, -p["a"]), weight
    )


def nd_envelope(p=ND):
    return [(sx * p["x"], 0.0, sz * p["z"]) for sx in (-1, 1) for sz in (-1, 1)]


def test_nd_b12_printed_tilt_numbers():
    # B.1.2 prints: "Tilt due to hook elevation difference of 1.0m = sin-1(1.0/25) = 2.29° < 3.0°
    # Hence 3° tilt requirement governs" and "for a hook spacing, L, of less than 19.1m, the tilt
    # angle from a 1m hook elevation difference will be more than 3°".
    assert printed(math.degrees(math.asin(1.0 / ND["L"])), 2) == 2.29
    tilt, elevation = rules_tilt()  # 5.4.2: hooks on one vessel
    assert (tilt, elevation) == (3.0, 1.0)
    assert governing_tilt(tilt, elevation, ND["L"]) == 3.0
    threshold = 1.0 / math.sin(math.radians(3.0))
    assert printed(threshold, 1) == 19.1
    assert governing_tilt(tilt, elevation, 19.0) > 3.0
    assert_allclose(governing_tilt(tilt, elevation, 12.0), math.degrees(math.asin(1 / 12)), **EXACT)


def test_nd_b12_crane_loads_equal_the_formulae():
    # The stored copy of B.1.2 is cut off after "[(14+0.8)*sin3] + [(13+0.9": the example's
    # results are not printed there, so the formulae themselves are the reference. The
    # library's lever rule in the tilted plane, searched over both tilt senses and the four
    # envelope corners, must find exactly the formula's governing cases.
    worst = nd_geometry().worst(3.0, nd_envelope())
    one, two = nd_crane_loads(3.0)
    assert_allclose(worst["crane1"].load, one, **EXACT)
    assert_allclose(worst["crane2"].load, two, **EXACT)
    # the formula's case: envelope towards the crane, low, and that crane's side raised
    assert worst["crane1"].cog_offset == (-0.9, 0.0, -0.8) and worst["crane1"].direction == 0.0
    assert worst["crane2"].cog_offset == (0.9, 0.0, -0.8) and worst["crane2"].direction == 180.0
    # hand-checked values of the formulae (4 decimals)
    assert (printed(one, 4), printed(two, 4)) == (0.5821, 0.5432)


def test_nd_b15_lift_point_loads():
    # B.1.5: lift point 1 = crane #1 x (f + y) / B, lift point 4 = crane #1 x (e + y) / B, etc.
    one, two = nd_crane_loads(3.0)
    p = ND
    expected = {
        "LP1": one * (p["f"] + p["y"]) / p["B"],
        "LP4": one * (p["e"] + p["y"]) / p["B"],
        "LP2": two * (p["f"] + p["y"]) / p["B"],
        "LP3": two * (p["e"] + p["y"]) / p["B"],
    }
    # the same through the library: crane #1's share split by the lever rule across the pair
    # (lift point 1 e from the CoG, lift point 4 f from it), the envelope moved y towards each
    pair = TiltGeometry({"LP1": (0.0, p["e"], 0.0), "LP4": (0.0, -p["f"], 0.0)}, (0.0, 0.0, -1.0), one)
    assert_allclose(pair.loads(0.0, cog_offset=(0.0, p["y"], 0.0))["LP1"], expected["LP1"], **EXACT)
    assert_allclose(pair.loads(0.0, cog_offset=(0.0, -p["y"], 0.0))["LP4"], expected["LP4"], **EXACT)
    assert [printed(expected[k], 4) for k in ("LP1", "LP4", "LP2", "LP3")] == [0.2794, 0.3376, 0.2607, 0.3151]


# ---- factors, each against its clause -----------------------------------------------------
@pytest.mark.parametrize(
    "weight, onshore, inshore, offshore",
    [
        (100.0001, 1.05, 1.12, 1.25),
        (300.0, 1.05, 1.12, 1.25),
        (300.0001, 1.05, 1.10, 1.20),
        (1000.0, 1.05, 1.10, 1.20),
        (1000.5, 1.03, 1.08, 1.15),
        (2500.0, 1.03, 1.08, 1.15),
        (2500.5, 1.03, 1.05, 1.10),
        (50_000.0, 1.03, 1.05, 1.10),
    ],
)
def test_daf_table_5_1_rows(weight, onshore, inshore, offshore):
    # 0027/ND Rev 11 Table 5-1, printed to two decimals; row upper bounds are inclusive.
    got = [dynamic_amplification(weight, where) for where in ("onshore", "inshore", "offshore")]
    assert got == [onshore, inshore, offshore]


def test_daf_table_5_1_light_lifts():
    # 3 < W <= 100 t: onshore 1.10, inshore 1.07 + 0.05 sqrt(100/SHL), offshore 1 + 0.25 sqrt(100/SHL)
    assert dynamic_amplification(100.0, "onshore") == 1.10
    assert_allclose(dynamic_amplification(100.0, "inshore", 25.0), 1.07 + 0.05 * 2.0, **EXACT)
    assert_allclose(dynamic_amplification(100.0, "offshore", 25.0), 1.0 + 0.25 * 2.0, **EXACT)
    # note 1: under 3 t the item is taken as 3 t (still the first row)
    assert dynamic_amplification(0.5, "onshore") == 1.10
    with pytest.raises(InvalidScene, match="static hook load"):
        dynamic_amplification(50.0, "inshore")
    with pytest.raises(InvalidScene, match=r"rules.location = 'nearshore'"):
        dynamic_amplification(500.0, "nearshore")


def test_tilt_rules_5_4():
    assert rules_tilt(separate_vessels=True) == (5.0, 1.0)  # 5.4.4 / 5.4.5
    assert rules_tilt(synchronised_sheerleg=True) == (1.5, 0.5)  # 5.4.6: 5.4.2 halved
    with pytest.raises(InvalidScene, match="synchronised_sheerleg"):
        rules_tilt(separate_vessels=True, synchronised_sheerleg=True)
    with pytest.raises(InvalidScene, match="hook_elevation"):
        governing_tilt(3.0, 2.0, 1.5)


def test_skew_yaw_cog_and_code_margin():
    assert skew_factor(True) == (1.25, "default")  # 5.6.12
    assert skew_factor(True, computed=1.08) == (1.08, "computed")
    assert skew_factor(False, computed=1.3) == (1.0, "determinate")
    assert skew_factor(False, override=1.1) == (1.1, "rules")
    assert yaw_factor(slings_on_hook=2, hooks=2) == 1.05  # 5.4.7
    assert yaw_factor(slings_on_hook=1, hooks=4) == 1.0
    assert cog_factor(searched=True, factor=1.03) == 1.0  # no double count
    assert cog_factor(searched=False, factor=1.03) == 1.03
    with pytest.raises(InvalidScene, match="rules.cog_factor: missing"):
        cog_factor(searched=False)
    assert [code_margin(n) for n in (1, 2, 3, 4, 6)] == [0.0, 0.20, 0.33, 0.50, 0.50]
    assert code_margin(4, override=0.25) == 0.25


def test_sling_stiffness_5_6_13():
    # E = 80 000 N/mm2 on A = 0.785 d2: a 100 mm sling has EA = 80 000 x 7 850 N = 628 MN.
    assert_allclose(sling_stiffness(0.1), 628.0e6 / 9806.65, **EXACT)


# ---- tilt statics ------------------------------------------------------------------------
def held_by_casadi(points, cog, weight, preload, ea, length, heel, trim, lift=1.0):
    """The model's own ``held`` function (planner/README), set to hold ``preload`` at level."""
    n = len(points)
    body = np.array(points, float)
    boom = lift + body[:, 2] + length + np.asarray(preload) * length / ea
    p = np.concatenate(
        [[0.0], body.reshape(-1), cog, [weight], boom, np.full(n, length), np.full(n, ea), [50.0]]
    )
    assert p.size == Layout(n).size
    tensions, _, _ = rope_model(n).held([lift, math.radians(heel), math.radians(trim)], p)
    return np.array(tensions).ravel()


@pytest.mark.parametrize("heel, trim", [(3.0, 0.0), (0.0, -4.0)])
def test_held_tilt_equals_the_casadi_held_model(heel, trim):
    # Lugs not at one height, so the stiffness enters; the library's numpy statics and the
    # casadi model are written independently. Both are a 3x3 solve on ~1e3 t numbers: 1e-9 t.
    points = [(16.2, 6.0, 6.0), (65.6, 6.0, 5.0), (65.6, -6.0, 7.0), (16.2, -6.0, 6.5)]
    cog, weight, ea, length = (35.86, 0.4, 2.5), 904.0, 50_000.0, 30.0
    preload = [280.0, 170.0, 185.0, 269.0]
    geometry = TiltGeometry(
        {f"T{i + 1}": pt for i, pt in enumerate(points)},
        cog,
        weight,
        preload={f"T{i + 1}": t for i, t in enumerate(preload)},
        stiffness={f"T{i + 1}": ea / length for i in range(4)},
    )
    level = held_by_casadi(points, cog, weight, preload, ea, length, 0.0, 0.0)
    tilt, direction = (heel, 0.0) if heel else (trim, 90.0)  # heel about +x, trim about +y
    got = geometry.loads(tilt, direction)
    want = held_by_casadi(points, cog, weight, preload, ea, length, heel, trim)
    assert_allclose([got[f"T{i + 1}"] for i in range(4)], want, rtol=0, atol=1e-9)
    assert_allclose(list(geometry.loads(0.0).values()), level, rtol=0, atol=1e-9)


def test_three_hooks_are_statics_alone():
    geometry = TiltGeometry(
        {"A": (0.0, 0.0, 0.0), "B": (20.0, -5.0, 1.0), "C": (8.0, 9.0, -0.5)}, (9.0, 1.0, -3.0), 300.0
    )
    loads = geometry.loads(4.0, 33.0)
    rot = rotation_about(33.0, 4.0)
    world = {k: rot @ np.array(v) for k, v in geometry.points.items()}
    g = rot @ np.array(geometry.cog)
    # equilibrium at the tilted pose: forces and both moments (300 t x ~20 m: 1e-9 relative)
    assert_allclose(sum(loads.values()), 300.0, rtol=1e-12)
    for axis in (0, 1):
        assert_allclose(sum(t * world[k][axis] for k, t in loads.items()), 300.0 * g[axis], rtol=1e-12)


def test_tilt_refusals():
    four = {"A": (0, 0, 0), "B": (10, 0, 0), "C": (10, 8, 0), "D": (0, 8, 0)}
    with pytest.raises(InvalidScene, match="tilt preload: missing"):
        TiltGeometry(four, (5, 4, -2), 100.0)
    with pytest.raises(InvalidScene, match="tilt stiffness: missing"):
        TiltGeometry({**four, "D": (0, 8, 1.0)}, (5, 4, -2), 100.0, preload=dict.fromkeys(four, 25.0))
    with pytest.raises(InvalidScene, match="collinear"):
        TiltGeometry({"A": (0, 0, 0), "B": (5, 0, 0), "C": (10, 0, 0)}, (5, 0, -1), 10.0).loads(1.0)
    # a CG far below two close lift points: at 20 deg one line goes slack, and says so
    slack = TiltGeometry({"A": (0, 0, 0), "B": (2, 0, 0)}, (0.2, 0, -20.0), 10.0)
    with pytest.raises(EquilibriumNotFound, match="goes slack"):
        slack.loads(20.0)


# ---- hand calculation 1: two cranes, 1 200 t hull block (docs/design-loads.md) -----------
def two_crane_chain(lug_capacity=700.0):
    w, p = 1200.0, ND
    geometry = nd_geometry(w)
    alpha = governing_tilt(*rules_tilt(), p["L"])
    tilt = geometry.worst(alpha, nd_envelope())
    nominal = {"C1": w * p["d"] / p["L"], "C2": w * p["c"] / p["L"]}
    worst = {"C1": w * (p["d"] + p["x"]) / p["L"], "C2": w * (p["c"] + p["x"]) / p["L"]}
    pairs = {"C1": (("LP1", p["f"]), ("LP4", p["e"])), "C2": (("LP2", p["f"]), ("LP3", p["e"]))}
    cranes = []
    for name, hook in (("C1", "crane1"), ("C2", "crane2")):
        lugs = tuple(
            LugLoads(
                lug,
                share=worst[name] * (far + p["y"]) / p["B"],
                tilt_share=tilt[hook].load * (far + p["y"]) / p["B"],
                sling_angle=60.0,
                capacity=lug_capacity,
            )
            for lug, far in pairs[name]
        )
        cranes.append(
            CraneLoads(name, nominal[name], worst[name], tilt[hook].load, swl=900.0, radius=24.0, lugs=lugs)
        )
    return DesignLoadChain(tuple(cranes), w, Rules(location="inshore", rigging_weight=30.0))


def test_hand_calculation_two_crane_1200t():
    chain = two_crane_chain()
    one, two = nd_crane_loads(3.0)
    c1, c2 = chain.result("C1"), chain.result("C2")
    assert_allclose([c1.tilt_share, c2.tilt_share], [1200 * one, 1200 * two], **EXACT)
    # doc, step by step (t, 1 decimal as printed in docs/design-loads.md)
    assert printed(c1.tilt_share, 1) == 698.6 and printed(c2.tilt_share, 1) == 651.8
    factor = {f.name: f for f in c1.factors}
    assert factor["daf"].value == 1.08  # Table 5-1 inshore, 1000 < 1 260 t <= 2500
    assert factor["cog"].value == 1.0 and "searched" in factor["cog"].note
    assert factor["skew"].value == 1.0 and factor["skew"].applies_to == "none"  # determinate
    assert factor["yaw"].value == 1.05 and factor["yaw"].applies_to == "lug"  # two slings on the hook
    assert_allclose(c1.static_hook_load, 1200 * one * 1.05 + 30.0, **EXACT)
    assert_allclose(c1.dynamic_hook_load, (1200 * one * 1.05 + 30.0) * 1.08, **EXACT)
    assert [printed(r.static_hook_load, 1) for r in (c1, c2)] == [763.5, 714.4]
    assert [printed(r.design_hook_load, 1) for r in (c1, c2)] == [824.6, 771.6]
    assert [printed(r.utilisation, 3) for r in (c1, c2)] == [0.916, 0.857]
    assert c1.check == Check.upper(
        "design_hook_load",
        "C1",
        c1.design_hook_load,
        900.0,
        "t",
        note="dynamic hook load / chart SWL at 24 m",
    )
    assert_allclose(c1.code_margin.value, (624.0 * 1.05 + 30.0) * 1.20, **EXACT)
    lugs = {lug.lug: lug for r in chain.results for lug in r.lugs}
    lp4 = 1200 * one * (ND["e"] + ND["y"]) / ND["B"]
    assert_allclose(lugs["LP4"].vertical, lp4 * 1.05 * 1.08 * 1.05, **EXACT)
    assert_allclose(lugs["LP4"].leg_load, lugs["LP4"].vertical / math.sin(math.radians(60.0)), **EXACT)
    assert_allclose(lugs["LP4"].design_load, lugs["LP4"].leg_load * 1.30, **EXACT)
    assert_allclose(lugs["LP4"].out_of_plane, 0.05 * lugs["LP4"].design_load, **EXACT)
    assert {k: printed(v.design_load, 1) for k, v in lugs.items()} == {
        "LP1": 599.3,
        "LP4": 724.2,
        "LP2": 559.2,
        "LP3": 675.7,
    }
    assert [lug.check.ok for lug in lugs.values()] == [True, False, True, True]
    assert [c.name for c in chain.checks if not c.ok] == ["lug_design_load"]


# ---- hand calculation 2: the 1500 GT tanker on four floating cranes ----------------------
TANKER = {
    "Big-P": (16.2, 6.0, 6.0),
    "Big-S": (16.2, -6.0, 6.0),
    "Mid-P": (65.6, 6.0, 6.0),
    "Mid-S": (65.6, -6.0, 6.0),
}
TANKER_COG, TANKER_W = (35.86, 0.0, 2.5), 904.0
TANKER_ENVELOPE = [(sx * 0.5, sy * 0.3, sz * 0.2) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def rectangle_share(name, dx=0.0, dy=0.0):
    """Held (no-twist) share on the 49.4 x 12 m lug rectangle with the CG moved by (dx, dy):
    W/4 + W (x_G - x_m)(x_i - x_m) / (4 * 24.7^2) + W y_G y_i / (4 * 6^2)."""
    x, y, _ = TANKER[name]
    xm = 40.9
    return (
        TANKER_W / 4
        + TANKER_W * (TANKER_COG[0] + dx - xm) * (x - xm) / (4 * 24.7**2)
        + TANKER_W * dy * y / (4 * 6.0**2)
    )


def tanker_chain():
    nominal = {k: rectangle_share(k) for k in TANKER}
    worst = {k: max(rectangle_share(k, v[0], v[1]) for v in TANKER_ENVELOPE) for k in TANKER}
    geometry = TiltGeometry(TANKER, TANKER_COG, TANKER_W, preload=nominal)
    alpha = governing_tilt(*rules_tilt(separate_vessels=True), geometry.least_spacing())
    tilt = geometry.worst(alpha, TANKER_ENVELOPE)
    k, delta = 50_000.0 / 30.0, 0.02  # EA / l0 [t/m], hook tolerance [m]
    swl = {"Big-P": 1000.0, "Big-S": 1000.0, "Mid-P": 450.0, "Mid-S": 450.0}
    cranes = tuple(
        CraneLoads(
            name,
            nominal[name],
            worst[name],
            tilt[name].load,
            swl=swl[name],
            skew=1.0 + k * delta / nominal[name],
        )
        for name in TANKER
    )
    rules = Rules(
        location="inshore",
        separate_vessels=True,
        rigging_weight={"Big-P": 60.0, "Big-S": 60.0, "Mid-P": 25.0, "Mid-S": 25.0},
    )
    return DesignLoadChain(cranes, TANKER_W, rules), alpha


def test_hand_calculation_tanker_four_cranes():
    chain, alpha = tanker_chain()
    assert alpha == 5.0  # 5.4.5: 5 deg against asin(1/12) = 4.78 deg
    big, mid = chain.result("Big-P"), chain.result("Mid-P")
    assert [printed(big.nominal, 2), printed(mid.nominal, 2)] == [272.11, 179.89]  # PHYSICS.md
    assert [printed(big.worst, 2), printed(mid.worst, 2)] == [287.99, 195.76]
    # tilt: the held shares equal the level ones with the CG moved 3.7 tan 5 deg towards the
    # lug, along the worst plan direction (lugs coplanar, CG 3.5 + 0.2 m below them)
    a, b = 24.7 / (4 * 24.7**2), 6.0 / (4 * 6.0**2)
    rise = TANKER_W * (0.5 * a + 0.3 * b + 3.7 * math.tan(math.radians(5.0)) * math.hypot(a, b))
    assert_allclose([big.tilt_share, mid.tilt_share], [big.nominal + rise, mid.nominal + rise], **EXACT)
    assert [printed(big.tilt_share, 2), printed(mid.tilt_share, 2)] == [300.54, 208.31]
    factor = {f.name: f for f in big.factors}
    assert factor["daf"].value == 1.10  # Table 5-1 inshore, 300 < 949.2 t <= 1000 (5.5.2)
    assert factor["skew"].applies_to == "hook and lug" and printed(factor["skew"].value, 4) == 1.1225
    assert {f.name: f.value for f in mid.factors}["skew"] == pytest.approx(1 + 1000 / 30 / 179.885, rel=1e-5)
    assert_allclose(big.static_hook_load, big.tilt_share * 1.05 * (1 + 100 / 3 / big.nominal) + 60.0, **EXACT)
    assert [printed(r.design_hook_load, 1) for r in (big, mid)] == [455.6, 312.7]
    assert [printed(r.utilisation, 3) for r in (big, mid)] == [0.456, 0.695]
    assert [printed(r.code_margin.value, 1) for r in (big, mid)] == [518.6, 320.8]  # 50 %, 4 cranes
    assert all(c.ok for c in chain.checks)
    out = json.loads(json.dumps(chain.to_json()))
    assert out["cranes"][0]["check"]["name"] == "design_hook_load"
    assert [f["name"] for f in out["cranes"][0]["factors"]] == [
        "weight_contingency",
        "cog",
        "tilt",
        "skew",
        "yaw",
        "daf",
    ]
    assert all(f["source"] for f in out["cranes"][0]["factors"])


# ---- chain logic --------------------------------------------------------------------------
def test_tilt_is_the_larger_share_never_a_product():
    # the planner's box already holds a larger share than the rules' tilt: tilt factor 1
    crane = CraneLoads("A", nominal=500.0, worst=560.0, tilt=540.0, swl=1000.0)
    other = CraneLoads("B", nominal=500.0, worst=560.0, tilt=540.0, swl=1000.0)
    chain = DesignLoadChain((crane, other), 1000.0, Rules(location="onshore", weight_contingency=1.0))
    result = chain.result("A")
    assert {f.name: f.value for f in result.factors}["tilt"] == 1.0
    assert_allclose(result.static_hook_load, 560.0, **EXACT)
    assert_allclose(result.dynamic_hook_load, 560.0 * 1.05, **EXACT)  # onshore, 300 < 1000 t


def test_no_envelope_takes_the_cog_factor_and_chart_with_dynamics():
    crane = CraneLoads("A", nominal=100.0, worst=100.0, tilt=None, swl=120.0)
    rules = Rules(location="onshore", cog_factor=1.03, weight_contingency=1.0, chart_includes_dynamics=True)
    chain = DesignLoadChain((crane,), 100.0, rules, cog_searched=False)
    result = chain.result("A")
    assert_allclose(result.static_hook_load, 103.0, **EXACT)
    assert result.design_hook_load == result.static_hook_load  # 10.3.2
    assert result.code_margin is None  # one crane
    with pytest.raises(InvalidScene, match="rules.cog_factor: missing"):
        DesignLoadChain((crane,), 100.0, Rules(), cog_searched=False)


def test_over_the_chart_fails_the_check():
    cranes = tuple(
        CraneLoads(n, nominal=250.0, worst=260.0, tilt=270.0, swl=300.0, skew=1.1)
        for n in ("A", "B", "C", "D")
    )
    chain = DesignLoadChain(cranes, 1000.0, Rules(location="offshore"))
    result = chain.result("A")
    # offshore, 1000 < 1 050 t <= 2500: DAF 1.15; four hooks: the computed skew on the hook
    assert_allclose(result.design_hook_load, 270.0 * 1.05 * 1.1 * 1.15, **EXACT)
    assert not result.check.ok and result.check.value > result.check.limit
    assert "FAIL design_hook_load A" in result.check.line()


# ---- [rules] table and bad input ----------------------------------------------------------
def test_rules_table_defaults_and_overrides():
    assert read_rules(None) == Rules()
    rules = read_rules(
        {
            "location": "inshore",
            "weight_contingency": 1.1,
            "daf": 1.2,
            "skew_factor": 1.3,
            "tilt": 2.0,
            "hook_elevation": 0.5,
            "yaw_factor": 1.1,
            "separate_vessels": True,
            "rigging_weight": {"Big-P": 25},
            "consequence_factor": 1.5,
            "lateral_fraction": 0.1,
            "chart_includes_dynamics": True,
            "code_margin": 0.25,
            "cog_factor": 1.05,
        }
    )
    assert rules.design_tilt() == (2.0, 0.5)
    assert rules.rigging_for("Big-P") == 25.0 and rules.rigging_for("other") == 0.0
    assert Rules(separate_vessels=True, daf=1.1).design_tilt() == (5.0, 1.0)


@pytest.mark.parametrize(
    "table, message",
    [
        ({"locaton": "inshore"}, "rules.locaton = 'inshore': unknown key, expected one of location"),
        ({"location": "nearshore"}, "rules.location = 'nearshore'"),
        ({"daf": "1.1"}, "rules.daf = '1.1'"),
        ({"daf": 0.9}, "rules.daf = 0.9: expected a finite factor >= 1"),
        ({"weight_contingency": float("nan")}, "rules.weight_contingency = nan"),
        ({"tilt": 45.0}, "rules.tilt = 45.0: expected a design tilt in [0, 30) deg"),
        ({"hook_elevation": -1.0}, "rules.hook_elevation = -1.0: expected a finite number >= 0"),
        ({"separate_vessels": "yes"}, "rules.separate_vessels = 'yes'"),
        ({"separate_vessels": True, "synchronised_sheerleg": True}, "rules.synchronised_sheerleg = true"),
        ({"separate_vessels": True}, "rules.daf: missing"),
        ({"rigging_weight": -5.0}, "rules.rigging_weight = -5.0: expected a finite number >= 0"),
        ({"lateral_fraction": 1.5}, "rules.lateral_fraction = 1.5"),
        ({"code_margin": -0.1}, "rules.code_margin = -0.1"),
    ],
    ids=lambda v: str(v)[:30],
)
def test_rules_table_bad_input(table, message):
    with pytest.raises(InvalidScene) as err:
        read_rules(table)
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_chain_bad_input():
    good = CraneLoads("A", nominal=100.0, worst=110.0, tilt=115.0, swl=300.0)
    with pytest.raises(InvalidScene, match=r"cranes\[B\].worst = 90.0: expected >= nominal"):
        CraneLoads("B", nominal=100.0, worst=90.0, tilt=None, swl=300.0)
    with pytest.raises(InvalidScene, match=r"cranes\[B\].swl = 0.0: expected a number > 0"):
        CraneLoads("B", nominal=100.0, worst=100.0, tilt=None, swl=0.0)
    with pytest.raises(InvalidScene, match=r"lugs\[L1\].sling_angle = 95.0"):
        LugLoads("L1", share=50.0, sling_angle=95.0)
    with pytest.raises(InvalidScene, match=r"cranes\[B\].tilt: missing"):
        DesignLoadChain((good, CraneLoads("B", 100.0, 110.0, None, 300.0)), 200.0, Rules())
    with pytest.raises(InvalidScene, match="expected unique crane names"):
        DesignLoadChain((good, good), 200.0, Rules())
    with pytest.raises(InvalidScene, match="rules.rigging_weight.Z: no such crane"):
        DesignLoadChain((good,), 200.0, Rules(rigging_weight={"Z": 3.0}))
    with pytest.raises(InvalidScene, match="no such crane"):
        DesignLoadChain((good,), 200.0, Rules()).result("Q")


# -- the rules' tilt per direction -----------------------------------------------------------------


def test_tilt_per_direction_closed_forms():
    """Four hooks on a 40 m x 12 m rectangle: a 1.0 m elevation difference tilts the body by
    asin(1/12) about the long axis (heel) and asin(1/40) < 3 deg about the short one, so 3 deg
    governs there; the least-spacing rule takes asin(1/12) about every axis."""
    import math

    from liftplan.model.rules import TiltGeometry

    points = {"A": (0.0, 0.0, 0.0), "B": (40.0, 0.0, 0.0), "C": (40.0, 12.0, 0.0), "D": (0.0, 12.0, 0.0)}
    geometry = TiltGeometry(points, (20.0, 6.0, -2.0), 400.0, preload=dict.fromkeys(points, 100.0))
    assert geometry.spacing_along(0.0) == pytest.approx(12.0, abs=1e-12)
    assert geometry.spacing_along(90.0) == pytest.approx(40.0, abs=1e-12)
    # a diagonal tilt: the rectangle's extent along (-sin, cos) of 45 deg
    assert geometry.spacing_along(45.0) == pytest.approx((40.0 + 12.0) / math.sqrt(2.0), abs=1e-12)
    assert geometry.tilt_along(0.0, 3.0, 1.0) == pytest.approx(math.degrees(math.asin(1 / 12)), abs=1e-12)
    assert geometry.tilt_along(90.0, 3.0, 1.0) == 3.0
    per = geometry.worst_per_direction(3.0, 1.0)
    least = geometry.worst(math.degrees(math.asin(1 / 12)))
    for name in points:
        assert per[name].load <= least[name].load + 1e-9
        assert per[name].tilt == pytest.approx(geometry.tilt_along(per[name].direction, 3.0, 1.0))
    # every direction's load at its own tilt is at most the reported worst (the sweep's samples)
    for d in np.linspace(0.0, 360.0, 73):
        loads = geometry.loads(geometry.tilt_along(d, 3.0, 1.0), d)
        assert all(loads[n] <= per[n].load + 1e-9 for n in points)


def test_tilt_per_direction_two_hooks_is_the_two_crane_rule():
    import math

    from liftplan.model.rules import TiltGeometry

    geometry = TiltGeometry({"P": (0.0, 0.0, 5.0), "Q": (10.0, 0.0, 5.0)}, (4.0, 0.0, 1.0), 100.0)
    per = geometry.worst_per_direction(3.0, 1.0)
    old = geometry.worst(math.degrees(math.asin(0.1)))
    for name in ("P", "Q"):
        assert per[name].load == pytest.approx(old[name].load, abs=1e-12)


def test_tilt_per_direction_refuses_an_elevation_beyond_the_spacing():
    from liftplan.model.rules import TiltGeometry

    geometry = TiltGeometry(
        {"A": (0.0, 0.0, 0.0), "B": (20.0, 0.0, 0.0), "C": (40.0, 0.5, 0.0)}, (20.0, 0.2, -1.0), 100.0
    )
    with pytest.raises(InvalidScene, match="hook_elevation = 1.0: expected less than the hook spacing"):
        geometry.tilt_along(0.0, 3.0, 1.0)

"""The ``[rules]`` table of a planning file, read into :class:`~liftplan.model.rules.settings.Rules`.

```toml
[rules]
location = "inshore"            # "onshore" | "inshore" | "offshore" (DAF column, Table 5-1)
weight_contingency = 1.05       # Design Weight = weight x this
# cog_factor = 1.03             # only when no CoG envelope is searched ([plan] cog_tolerance = 0)
# daf = 1.10                    # replaces Table 5-1
# skew_factor = 1.25            # replaces the computed skew factor
# tilt = 3.0                    # deg, replaces the rules' tilt
# hook_elevation = 1.0          # m, replaces the rules' hook elevation difference
yaw_factor = 1.05
separate_vessels = true         # cranes on separate vessels: 5 deg
synchronised_sheerleg = false   # one sheerleg vessel, synchronised hooks: 1.5 deg / 0.5 m
rigging_weight = 12.0           # t per hook, or { Big-P = 25.0, Small-S = 8.0 }
consequence_factor = 1.30       # lift points (Table 11-1)
lateral_fraction = 0.05         # lateral lift point load / factored load
chart_includes_dynamics = false # compare the static hook load with the chart (10.3.2)
# code_margin = 0.5             # replaces 20 / 33 / 50 %; 0 switches the check off
code = "0027/ND"                # the rules code the factors come from (the only one implemented)
```

The shape is checked by pydantic (unknown keys, wrong types), the values by :class:`Rules`;
either way one :class:`~liftplan.model.errors.InvalidScene` line naming ``rules.KEY``, the
value and what is expected.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Strict, ValidationError

from liftplan.model.errors import InvalidScene
from liftplan.model.rules.codes import CODES, DEFAULT_CODE
from liftplan.model.rules.settings import Rules
from liftplan.model.scene.file import Key, Num, Table, Text, one_line

Flag = Annotated[bool, Strict()]


class RulesTable(Table):
    """Schema of ``[rules]`` (defaults as in :class:`Rules`), each key with its documentation
    (``Key``: the convention is in :mod:`liftplan.model.scene.file`)."""

    location: Literal["onshore", "inshore", "offshore"] = Key(
        "offshore",
        doc=(
            "the DAF column of Table 5-1 (offshore is the most onerous); when not given, offshore is "
            "assumed and the console and report say so"
        ),
        example='location = "inshore"',
    )
    weight_contingency: Num = Key(
        1.05,
        doc="design weight = weight x this (6.2.1; 1.05 is this project's assumption)",
        unit="-",
        values="number >= 1",
        example="weight_contingency = 1.05",
    )
    cog_factor: Num | None = Key(
        None,
        doc="factor on the shares when `plan.cog_tolerance` is zero (6.2.3)",
        unit="-",
        values="number >= 1",
        absent="none; required when no CoG envelope is searched",
        example="cog_factor = 1.03",
    )
    daf: Num | None = Key(
        None,
        doc="replaces the DAF of Table 5-1; required offshore with `separate_vessels`",
        unit="-",
        values="number >= 1",
        absent="Table 5-1",
        example="daf = 1.10",
    )
    skew_factor: Num | None = Key(
        None,
        doc="replaces the computed skew factor (the rules' default is 1.25, 5.6.12)",
        unit="-",
        values="number >= 1",
        absent="computed from `plan.hook_tolerance`",
        example="skew_factor = 1.25",
    )
    tilt: Num | None = Key(
        None,
        doc="replaces the rules' multi-hook tilt (5.4)",
        unit="deg",
        values="number, 0 <= tilt < 30",
        absent="3, or 5 with `separate_vessels`",
        example="tilt = 3.0",
    )
    hook_elevation: Num | None = Key(
        None,
        doc=(
            "replaces the rules' hook elevation difference; its tilt is taken per direction, over the "
            "hooks' spacing along the tilt (two hooks: their spacing)"
        ),
        unit="m",
        values="number >= 0",
        absent="1.0",
        example="hook_elevation = 1.0",
    )
    yaw_factor: Num = Key(
        1.05,
        doc="on lug loads of a hook with more than one sling (5.4.7)",
        unit="-",
        values="number >= 1",
        example="yaw_factor = 1.05",
    )
    separate_vessels: Flag = Key(
        False, doc="cranes on separate vessels: 5 deg tilt (5.4.4, 5.4.5)", example="separate_vessels = true"
    )
    synchronised_sheerleg: Flag = Key(
        False,
        doc="hooks of one sheerleg vessel, closely synchronised: the one-vessel tilt halved (5.4.6)",
        example="synchronised_sheerleg = false",
    )
    rigging_weight: Num | dict[Text, Num] = Key(
        0.0,
        doc=(
            "hook block, slings, shackles on each hook, added to its static hook load (6.2.2); per "
            "crane by `cranes[].name`"
        ),
        unit="t",
        values="number >= 0, or a table crane name = number",
        example='rigging_weight = { "Sheerleg A" = 12.0 }',
    )
    consequence_factor: Num = Key(
        1.30,
        doc="lug design load = leg load x this (Table 11-1)",
        unit="-",
        values="number >= 1",
        example="consequence_factor = 1.30",
    )
    lateral_fraction: Num = Key(
        0.05,
        doc="lateral lug load as a fraction of its design load",
        unit="-",
        values="number, 0 <= f < 1",
        example="lateral_fraction = 0.05",
    )
    chart_includes_dynamics: Flag = Key(
        False,
        doc="the chart already includes dynamics: compare the static hook load with it (10.3.2)",
        example="chart_includes_dynamics = true",
    )
    code_margin: Num | None = Key(
        None,
        doc="the crane-code margin over the calculated share; 0 switches the check off",
        unit="-",
        values="number >= 0",
        absent="0.20 / 0.33 / 0.50 for 2 / 3 / 4+ cranes",
        example="code_margin = 0.5",
    )
    code: Literal[tuple(CODES)] = Key(
        DEFAULT_CODE,
        doc=(
            "the rules code every factor comes from (GL Noble Denton 0027/ND Rev 11, now "
            "DNVGL-ST-N001); the only one implemented"
        ),
        example='code = "0027/ND"',
    )


class _RulesFile(Table):
    # wraps the table so that pydantic's locations read "rules.KEY"
    model_config = Table.model_config | {"extra": "ignore"}
    rules: RulesTable = RulesTable()


def rules_from_table(table):
    """A validated ``[rules]`` table to :class:`Rules`.

    Parameters
    ----------
    table : RulesTable or None
        None (no ``[rules]`` table): the defaults.

    Returns
    -------
    Rules
    """
    if table is None:
        return Rules()
    values = table.model_dump()
    if "location" not in table.model_fields_set:  # not given: Rules assumes (and says so)
        values["location"] = None
    return Rules(**values)


def read_rules(raw):
    """``[rules]`` as parsed TOML (a dict, or None when absent) to :class:`Rules`.

    Raises
    ------
    InvalidScene
        One line, e.g. ``rules.daf = 0.9: expected a finite factor >= 1 (1 = no increase)``.
    """
    if raw is not None and not isinstance(raw, dict):
        raise InvalidScene(f"rules = {raw!r}: expected a table [rules]")
    try:
        data = _RulesFile.model_validate({"rules": raw if raw is not None else {}})
    except ValidationError as err:
        raise InvalidScene(one_line(err, _RulesFile)) from None
    return rules_from_table(data.rules)

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
from liftplan.model.scene.file import Num, Table, Text, one_line

Flag = Annotated[bool, Strict()]


class RulesTable(Table):
    """Schema of ``[rules]`` (defaults as in :class:`Rules`)."""

    location: Literal["onshore", "inshore", "offshore"] = "offshore"
    weight_contingency: Num = 1.05
    cog_factor: Num | None = None
    daf: Num | None = None
    skew_factor: Num | None = None
    tilt: Num | None = None
    hook_elevation: Num | None = None
    yaw_factor: Num = 1.05
    separate_vessels: Flag = False
    synchronised_sheerleg: Flag = False
    rigging_weight: Num | dict[Text, Num] = 0.0
    consequence_factor: Num = 1.30
    lateral_fraction: Num = 0.05
    chart_includes_dynamics: Flag = False
    code_margin: Num | None = None
    code: Literal[tuple(CODES)] = DEFAULT_CODE


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

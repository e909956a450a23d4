"""The lifting rules' design-load chain: static shares in, design hook and lug loads out.

Read this first. The planner finds each crane's static share of the weight (nominal, and the
worst over the heel/trim box and the CoG envelope it searched). The rules (GL Noble Denton
0027/ND Rev 11, now DNVGL-ST-N001) turn those into the loads a crane chart and a lug are
checked against, one named factor at a time: weight contingency, CoG (a factor only when no
envelope was searched), the multi-hook tilt (:mod:`.tilt` computes each hook's share at the
rules' tilt with rigid-body vertical-line statics), skew, yaw, the dynamic amplification factor
by weight and location, plus the rigging weight on each hook; the dynamic hook load is checked
against the chart SWL at the crane's radius, the lug's leg load (sling angle, consequence
factor, lateral allowance) against the lug's capacity, and the crane-code margin 20 / 33 / 50 %
beside them. :mod:`.factors` holds each factor as a small function citing its clause (and says
where a value could not be found in the stored rules text), :mod:`.settings` the overridable
:class:`Rules`, :mod:`.table` the ``[rules]`` file table, :mod:`.chain` the
:class:`DesignLoadChain`. ``docs/design-loads.md`` walks through it with two hand calculations.

Example::

    from liftplan.model.rules import CraneLoads, DesignLoadChain, Rules
    chain = DesignLoadChain(cranes=(CraneLoads("A", nominal=600, worst=612, tilt=630, swl=900),
                                    CraneLoads("B", nominal=600, worst=612, tilt=630, swl=900)),
                            weight=1200, rules=Rules(location="inshore"))
    chain.result("A").design_hook_load, chain.result("A").check.ok
"""

from liftplan.model.rules.chain import (
    CraneDesignLoad,
    CraneLoads,
    DesignLoadChain,
    Factor,
    LugDesignLoad,
    LugLoads,
)
from liftplan.model.rules.factors import (
    CODE_MARGIN,
    CODE_MARGIN_MANY,
    DEFAULT_SKEW_FACTOR,
    code_margin,
    cog_factor,
    dynamic_amplification,
    governing_tilt,
    rules_tilt,
    skew_factor,
    sling_stiffness,
    weight_contingency,
    yaw_factor,
)
from liftplan.model.rules.settings import Rules
from liftplan.model.rules.table import RulesTable, read_rules, rules_from_table
from liftplan.model.rules.tilt import TiltGeometry, TiltLoad, rotation_about

__all__ = [
    "CODE_MARGIN",
    "CODE_MARGIN_MANY",
    "DEFAULT_SKEW_FACTOR",
    "CraneDesignLoad",
    "CraneLoads",
    "DesignLoadChain",
    "Factor",
    "LugDesignLoad",
    "LugLoads",
    "Rules",
    "RulesTable",
    "TiltGeometry",
    "TiltLoad",
    "code_margin",
    "cog_factor",
    "dynamic_amplification",
    "governing_tilt",
    "read_rules",
    "rotation_about",
    "rules_from_table",
    "rules_tilt",
    "skew_factor",
    "sling_stiffness",
    "weight_contingency",
    "yaw_factor",
]

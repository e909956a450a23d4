"""Sling lifts: cranes whose hooks carry sling sets (2-4 legs) or spreader bars.

* :mod:`.geometry` - where a hook sits over its lugs (pair apex, tripod apex, spreader rig) and
  how the legs share its load;
* :mod:`.rigs` - every rig one crane's sling can take on the candidates (the candidate rule);
* :mod:`.two_crane` - two cranes: exhaustive over rigs x rigs x both assignments, lever rule
  along the hook line (:class:`SlingPlan`);
* :mod:`.apex` - three or more cranes on 3/4-leg slings: the apexes are body-fixed lift points
  planned by the held-preload search (:class:`ApexSlingPlan`);
* :mod:`.lift` - what both plans share: labels, the rules' chain, checks, the rigging scene.

``plan()`` (:mod:`liftplan.planner.plan`) dispatches through :func:`uses_slings` and
:func:`plan_slings`.
"""

from __future__ import annotations

from liftplan.planner.plans.slings.apex import ApexSlingPlan, plan_apex_slings
from liftplan.planner.plans.slings.two_crane import SlingOption, SlingPlan, plan_two_slings, uses_slings
from liftplan.planner.search.progress import phase

__all__ = ["ApexSlingPlan", "SlingOption", "SlingPlan", "plan_slings", "plan_two_slings", "uses_slings"]


def plan_slings(problem, top=None):
    """Plan a lift whose cranes carry sling sets: two cranes by :func:`plan_two_slings`, three
    or more (3/4-leg slings) by :func:`~.apex.plan_apex_slings`."""
    if problem.cranes == 2:  # one vectorised pass: no plan before it ends (Ctrl-C: none)
        with phase("sling plan: every pair of rigs", None):
            return plan_two_slings(problem, top)
    return plan_apex_slings(problem, top)

"""The kinds of plan: each a planner and a result that is a
:class:`~liftplan.planner.plans.protocol.LiftPlan`. The kind is chosen in one place,
:data:`liftplan.planner.plan.KINDS`.

* :mod:`.held` - single ropes with a held level preload (:class:`~.held.Plan`), by the search
  of :mod:`liftplan.planner.search`;
* :mod:`.lengths` - the same with each crane's rope length chosen within its range;
* :mod:`.slings` - cranes on sling sets or spreader bars (two cranes, or 3/4-leg slings);
* :mod:`.strength` - lift forces chosen for the hull girder (bending, shear);
* shared by them: :mod:`.protocol` (what a plan is), :mod:`.common` (the JSON's fixed keys,
  the objectives in words, the file frame), :mod:`.design_loads` (the rules' chain fed by a
  plan), :mod:`.breakout` (the breakout case of a bedded hull).
"""

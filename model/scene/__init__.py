"""The scene: what hangs from what, read from a scene file and checked where it is made.

Modules:

* :mod:`.objects` - the frozen scene (:class:`~.objects.Scene`: body, lugs, cranes, ground,
  water, analysis) and its checks.
* :mod:`.file` - scene files (TOML, every key in ``docs/scene-files.md``) read by pydantic
  into a :class:`~.objects.Scene` (:func:`~.file.load_scene`, :func:`~.file.loads_scene`).
* :mod:`.writer` - the one scene writer: a :class:`~.objects.Scene` of a body in air as the
  text of a scene file that reads back to it (:func:`~.writer.scene_toml`).
* :mod:`.hull` - a hull as a closed triangle mesh, with its compartments; :mod:`.hullfit` a
  parametric hull fitted to published particulars.
* :mod:`.rigging_gear` - sling sets and spreader bars between a hook and its lugs.
* :mod:`.plausibility` - implausible magnitudes (unit slips): warnings, not errors.

The scene imports nothing of the models that solve it (:mod:`liftplan.model.statics`,
:mod:`liftplan.model.water`); they import it.
"""

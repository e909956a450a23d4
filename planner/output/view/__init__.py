"""The 3D view of a rigged lift: the scene's geometry at each state (:mod:`.geometry`, built by
:mod:`.states` from a solved scene, a plan or a load curve), drawn by one writer each: plotly
for the stand-alone or embedded HTML page (:mod:`.page`, the figure in :mod:`.figure`),
trimesh for glTF (:mod:`.gltf`) and matplotlib for the report's printed stills
(:mod:`.stills`). The ``liftplan view`` command and ``--view FILE`` are in :mod:`.command`.

plotly and trimesh are imported only here and only when a view is drawn: ``liftplan solve``
without ``--view`` never loads them.
"""

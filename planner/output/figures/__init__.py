"""Figures (matplotlib, object API, no pyplot state): each function returns a Figure.

* :mod:`.plan` - a plan in plan view and its ranking, the load curve, the spread map.
* :mod:`.strength` - the hull girder of a solved state (loads, shear force, bending moment).
* :mod:`.lift` - the load curve with the breakout, the soil's pull and the water draining.
"""

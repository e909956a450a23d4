"""Plain-text output for the terminal: no colour, fixed columns, units in every header.

* :mod:`.tables` - the ``solve``, ``lift`` and ``batch`` tables; :mod:`.rope_table` many ropes
  grouped by station; :mod:`.lift` the load curve's extra lines; :mod:`.text` the layout rules
  (a width every table fits, long tables in groups).
* :mod:`.summary` - a plan's summary by its kind: :mod:`.held` (single ropes, also with rope
  lengths), :mod:`.slings`, :mod:`.strength`.
"""

"""The recommendation report: one self-contained A4 HTML file (and a PDF with the ``[pdf]``
extra), the chosen plan as a scene file ``liftplan solve`` reads back, and plan.json.

* :mod:`.write` - the one writer (:func:`~.write.write_report`), for every kind of plan;
* :mod:`.page` - the page every kind shares: A4 print layout, title block, tables, figures;
* :mod:`.held`, :mod:`.slings`, :mod:`.strength` - each kind's page and scene file.
"""

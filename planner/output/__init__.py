"""What a person reads: console tables, figures, the A4 report, and the rule for output paths.

Nothing here is imported until a command needs it (matplotlib and WeasyPrint are heavy):

* :mod:`.console` - text tables for the terminal, a plan's summary by its kind;
* :mod:`.figures` - matplotlib figures (object API);
* :mod:`.report` - the recommendation report (HTML, PDF, the plan's scene file, plan.json),
  written by one writer (:func:`liftplan.planner.output.report.write.write_report`) from the
  page of the plan's kind;
* :mod:`.paths` - one rule for every path the command line writes to.
"""

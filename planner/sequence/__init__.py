"""``liftplan sequence``: the command, its console table, figure and report (issue 26).

The physics is :mod:`liftplan.model.sequence`; this package only shows it.
"""

"""liftplan's optimisation, reports and command line, around :mod:`liftplan.model`."""

"""Many solves: batch studies on Dask and the Monte-Carlo hook check.

:mod:`.study` reads study files (which cases), :mod:`.run` runs them on a local or remote Dask
cluster with a resumable journal, :mod:`.check` checks one plan against many cases in one
batched casadi call, :mod:`.montecarlo` draws hook-height errors on the forward elastic model.
"""

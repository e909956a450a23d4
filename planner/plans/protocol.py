"""What every kind of plan is: the :class:`LiftPlan` protocol the outputs rely on."""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable


@runtime_checkable
class LiftPlan(Protocol):
    """A finished plan, whatever its kind.

    Attributes
    ----------
    kind : str
        The name of its row in :data:`liftplan.planner.plan.KINDS`; the console, the report
        and the scene writer choose their sections by it.
    problem : PlanProblem
        What was planned.
    frame : str
        The planning file's frame; every coordinate a person reads is in it
        (:meth:`in_file_frame`).
    checks : tuple of Check
        Every check that can fail (SWL, design loads, strength, ...), each flagged.
    """

    problem: Any

    @property
    def kind(self) -> str: ...

    @property
    def frame(self) -> str: ...

    @property
    def checks(self) -> tuple: ...

    def in_file_frame(self, vector: Any) -> Any:
        """A body-frame vector in the planning file's frame."""
        ...

    def to_json(self) -> dict:
        """The plan as JSON (the fixed keys of ``docs/scene-files.md`` and the kind's own)."""
        ...

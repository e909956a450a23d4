"""What a search may spend: time (a deadline) and work (a count), and which ran out.

Time depends on the machine and its load; work does not: a search stopped by its work limit
gives the same plan on any machine (``[plan] work_limit``), one stopped by its time limit may
not. Each search spends one unit per step it counts (rows evaluated, swaps taken, cells
searched, cutting-plane rounds) and asks :meth:`Budget.out` before the next.
"""

from __future__ import annotations

import time
from dataclasses import dataclass


@dataclass
class Budget:
    """A deadline and a work count, either or both unlimited.

    Parameters
    ----------
    deadline : float or None
        ``time.perf_counter()`` value after which the search stops.
    work : int or None
        Units the search may spend.
    spent : int
        Units spent so far.
    """

    deadline: float | None = None
    work: int | None = None
    spent: int = 0

    @classmethod
    def of(cls, seconds=None, work=None, started=None):
        """A budget of ``seconds`` from ``started`` (default now) and ``work`` units."""
        started = time.perf_counter() if started is None else started
        return cls(None if seconds is None else started + seconds, work)

    def spend(self, units=1):
        """Count ``units`` of work done."""
        self.spent += units

    def out(self):
        """``"work_limit"`` or ``"time_limit"`` when that has run out, else None."""
        if self.work is not None and self.spent >= self.work:
            return "work_limit"
        if self.deadline is not None and time.perf_counter() > self.deadline:
            return "time_limit"
        return None

"""Progress lines on stderr for the long phases of ``liftplan plan`` (tqdm).

Shown only when asked (``progress=True``) or, by default (``progress=None``), when stderr is a
terminal; never on stdout, so ``--json`` is untouched. Each line names its phase and, where
known, the best value so far and the bound; it appears after :data:`DELAY` seconds (a short
phase shows nothing) and is removed when the phase ends.

The bar has a fixed width and comes before the numbers, so a narrow terminal cuts the numbers'
tail, never the bar. A terminal whose size is unknown (a pty with no size set: 0 columns and
0 lines) is drawn :data:`FALLBACK_WIDTH` wide and taken as :data:`FALLBACK_HEIGHT` lines high:
tqdm alone draws no bar at 0 columns and no line at all at 0 lines. A phase without natural
steps (one long MIP solve, the design loads) is redrawn every :data:`TICK` seconds by a
background thread, so its elapsed time moves.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time

#: Seconds before a line is shown: a phase shorter than this shows nothing.
DELAY = 1.0
#: Seconds between redraws of a line by its ticker thread.
TICK = 0.5
#: Least time between two redraws of a line  [s] (tqdm's default).
MININTERVAL = 0.1
#: Columns assumed where the terminal's width is unknown.
FALLBACK_WIDTH = 100
#: Lines assumed where the terminal's height is unknown.
FALLBACK_HEIGHT = 24
#: The line: phase, share done with a fixed-width bar, count, elapsed time, best / bound, then
#: the time left (tqdm's estimate from the rate so far; last, so a narrow terminal cuts it first).
BAR_FORMAT = (
    "{desc}: {percentage:3.0f}% |{bar:20}| {n_fmt}/{total_fmt} {unit} [{elapsed}]{postfix}, {remaining} left"
)
#: The line of a phase whose steps are counted but not known in advance (no bar to fill).
OPEN_FORMAT = "{desc}: {n_fmt} {unit} [{elapsed}]{postfix}"
#: The line of a phase without steps.
PHASE_FORMAT = "{desc}: {elapsed}{postfix}"


def shown(progress, file=None):
    """Whether progress is shown: ``progress`` itself, or when None, whether ``file`` (stderr)
    is a terminal."""
    if progress is not None:
        return bool(progress)
    stream = sys.stderr if file is None else file
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # closed or not a real stream
        return False


def width(file):
    """Columns of the terminal ``file`` writes to; :data:`FALLBACK_WIDTH` where unknown."""
    return _size(file, "columns", "COLUMNS", FALLBACK_WIDTH)


def height(file):
    """Lines of the terminal ``file`` writes to; :data:`FALLBACK_HEIGHT` where unknown (tqdm
    takes a terminal of 0 lines for one with no room and draws nothing)."""
    return _size(file, "lines", "LINES", FALLBACK_HEIGHT)


def _size(file, what, variable, fallback):
    try:
        value = getattr(os.get_terminal_size(file.fileno()), what)
    except (AttributeError, OSError, ValueError):
        value = 0
    if value <= 0:
        try:
            value = int(os.environ.get(variable, "0"))
        except ValueError:
            value = 0
    return value if value > 0 else fallback


class _Ticker(threading.Thread):
    """Redraws a bar every :data:`TICK` s until stopped (a phase without steps)."""

    def __init__(self, bar):
        super().__init__(daemon=True, name="liftplan-progress")
        self.bar, self.stop = bar, threading.Event()

    def run(self):
        while not self.stop.wait(TICK):
            if time.time() - self.bar.start_t >= DELAY:
                with contextlib.suppress(Exception):  # a bar closed meanwhile
                    self.bar.refresh()


def progress_bar(total, progress, desc="plan", unit="set", ticker=False):
    """A progress line on stderr, or None when not shown (:func:`shown`).

    Parameters
    ----------
    total : int or None
        Steps of the phase (None: unknown, no bar drawn).
    progress : bool or None
    desc : str
        The phase's name.
    unit : str
    ticker : bool
        Redraw it every :data:`TICK` s (a phase whose steps are long or few).

    Returns
    -------
    tqdm.tqdm or None
        Close it when the phase ends (its ticker stops with it).
    """
    if not shown(progress):
        return None
    from tqdm import tqdm

    bar = tqdm(
        total=total,
        desc=desc,
        unit=unit,
        file=sys.stderr,
        delay=DELAY,
        mininterval=MININTERVAL,
        leave=False,
        ncols=width(sys.stderr),
        nrows=height(sys.stderr),
        bar_format=BAR_FORMAT if total else (OPEN_FORMAT if unit else PHASE_FORMAT),
    )
    if ticker:
        thread = _Ticker(bar)
        original = bar.close

        def close():
            thread.stop.set()
            original()

        bar.close = close
        thread.start()
    return bar


def best_bound(best, bound=None, extra=""):
    """The postfix of a line: best value so far, bound and gap where known."""
    parts = []
    if best is not None and best == best and abs(best) != float("inf"):
        parts.append(f"best {best:.4g}")
        if bound is not None and bound == bound and abs(bound) != float("inf"):
            low = min(bound, best)
            parts.append(f"bound {low:.4g}")
            if best > 0:
                parts.append(f"gap {100 * (best - low) / best:.2g} %")
    if extra:
        parts.append(extra)
    return ", ".join(parts)


@contextlib.contextmanager
def phase(desc, progress=None, postfix=""):
    """A line for a phase without steps (``with phase("design loads"): ...``): its name, the
    time it has run and ``postfix``, redrawn every :data:`TICK` s after :data:`DELAY` s."""
    bar = progress_bar(None, progress, desc=desc, unit="", ticker=True)
    if bar is not None and postfix:
        bar.set_postfix_str(postfix, refresh=False)
    try:
        yield bar
    finally:
        if bar is not None:
            bar.close()

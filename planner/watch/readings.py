"""Read a lift's recorded readings: a CSV or a JSON file, one reading per line.

CSV: a header ``time,<crane or lug name>,...[,heel,trim]`` then one row per time. Each rope's
column may name its planned label (``L1``), its crane or its candidate lug; every rope of the
plan needs one. ``heel`` and ``trim`` (deg, the liftplan convention: heel > 0 starboard down,
trim > 0 bow down) come together or not at all. ``hook:<name>`` columns (optional, any of the
ropes) are measured boom-tip heights above the datum [m]. JSON: one object per line (JSON
Lines) or one array of objects, each with the same keys as the CSV's columns.

What is wrong with the file as a whole (a missing rope, a name not in the plan, a column
twice, heel without trim) raises :class:`InvalidScene` (one line). What is wrong with one row
(a negative tension, a NaN or empty cell, a number that is not one, a time not after the
previous one, a wrong number of cells) makes that :class:`Reading` flagged: its ``flag`` says
why, and nothing is estimated from it.
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene

HOOK_PREFIX = "hook:"


@dataclass(frozen=True)
class Reading:
    """One time's readings, in the plan's label order.

    Parameters
    ----------
    line : int
        Line of the file it came from (1-based).
    time : float  [s]  (NaN when it could not be read)
    tensions : numpy.ndarray (n,)  [t]
    heel, trim : float or None  [deg]
        None without an inclinometer.
    hooks : numpy.ndarray (n,)  [m]
        Measured boom-tip heights; NaN where not read.
    flag : str or None
        Why the row cannot be used (one line), else None.
    """

    line: int
    time: float
    tensions: np.ndarray
    heel: float | None = None
    trim: float | None = None
    hooks: np.ndarray | None = None
    flag: str | None = None

    @property
    def has_angles(self):
        return self.heel is not None

    @property
    def hook_mask(self):
        """Which hooks have a measured height."""
        if self.hooks is None:
            return np.zeros(len(self.tensions), dtype=bool)
        return np.isfinite(self.hooks)


class Columns:
    """A readings file's columns matched to the plan's ropes (from its header)."""

    def __init__(self, basis, names, where):
        self.basis, self.where = basis, where
        names = [str(name).strip() for name in names]
        known = basis.names()
        self.names = names
        self.tension = {}  # column index -> rope index
        self.hook = {}
        self.time = self.heel = self.trim = None
        labels = list(basis.labels)
        seen = {}
        for k, name in enumerate(names):
            if name in seen:
                raise InvalidScene(f"{where}: column {name!r} appears twice; expected each column once")
            seen[name] = k
            if name == "time":
                self.time = k
            elif name in ("heel", "trim"):
                setattr(self, name, k)
            else:
                target = self.hook if name.startswith(HOOK_PREFIX) else self.tension
                rope = name[len(HOOK_PREFIX) :].strip() if name.startswith(HOOK_PREFIX) else name
                matches = known.get(rope)
                if not matches:
                    raise InvalidScene(
                        f"{where}: column {name!r}: no crane or lug {rope!r} in the plan; expected one "
                        f"of {', '.join(labels)} (or their crane or lug names), time, heel, trim, "
                        f"{HOOK_PREFIX}NAME"
                    )
                if len(matches) > 1:
                    raise InvalidScene(
                        f"{where}: column {name!r} names more than one rope ({', '.join(sorted(matches))}); "
                        "expected the planned labels L1.. instead"
                    )
                rope_index = labels.index(next(iter(matches)))
                if rope_index in target.values():
                    raise InvalidScene(
                        f"{where}: two columns for rope {labels[rope_index]} ({name!r} and another); "
                        "expected one per rope"
                    )
                target[k] = rope_index
        if self.time is None:
            raise InvalidScene(f"{where}: no time column; expected a header time,<crane or lug name>,...")
        missing = [i for i in range(basis.n) if i not in self.tension.values()]
        if missing:
            i = missing[0]
            raise InvalidScene(
                f"{where}: no load-cell column for rope {labels[i]} (crane {basis.cranes[i]!r}, lug "
                f"{basis.candidates[i]!r}); expected one tension column per crane of the plan"
            )
        if (self.heel is None) != (self.trim is None):
            raise InvalidScene(f"{where}: heel without trim or trim without heel; expected both or neither")

    def reading(self, cells, line, previous_time):
        """A :class:`Reading` from one row's cells (strings or numbers), flagged when bad."""
        n = self.basis.n
        tensions = np.full(n, np.nan)
        hooks = np.full(n, np.nan) if self.hook else None
        time = math.nan
        if len(cells) != len(self.names):
            return Reading(
                line,
                time,
                tensions,
                hooks=hooks,
                flag=f"line {line}: {len(cells)} values, the header has {len(self.names)}",
            )

        def number(k):
            value = cells[k]
            if isinstance(value, bool):
                raise ValueError
            value = float(value)  # a string, an int or a float; None raises TypeError
            if not math.isfinite(value):
                raise ValueError
            return value

        values = {}
        for k, name in enumerate(self.names):
            try:
                values[k] = number(k)
            except (TypeError, ValueError):
                return Reading(
                    line,
                    time,
                    tensions,
                    hooks=hooks,
                    flag=f"line {line}: {name} = {cells[k]!r} is not a finite number",
                )
        time = values[self.time]
        for k, i in self.tension.items():
            tensions[i] = values[k]
        for k, i in self.hook.items():
            hooks[i] = values[k]
        heel = values[self.heel] if self.heel is not None else None
        trim = values[self.trim] if self.trim is not None else None
        flag = None
        negative = [self.names[k] for k, i in self.tension.items() if values[k] < 0.0]
        if negative:
            flag = f"line {line}: negative tension in {', '.join(negative)}; expected a load >= 0 t"
        elif previous_time is not None and not time > previous_time:
            flag = f"line {line}: time {time:g} s is not after the previous reading's {previous_time:g} s"
        return Reading(line, time, tensions, heel, trim, hooks, flag)


class ReadingParser:
    """Turns a readings file's lines into :class:`Reading` objects, one line at a time (so a
    growing file can be followed): the first non-blank line sets the columns."""

    def __init__(self, basis, where="readings"):
        self.basis, self.where = basis, where
        self.columns = None
        self.kind = None  # "csv" or "json"
        self.previous_time = None

    def feed(self, text, line):
        """The reading of one line of the file, or None (a blank line or the CSV header)."""
        text = text.strip()
        if not text or (self.kind == "json" and text in ("[", "]")):
            return None
        if self.kind is None:
            self.kind = "json" if text[0] in "[{" else "csv"
            if self.kind == "csv":
                self.columns = Columns(self.basis, next(csv.reader([text])), self.where)
                return None
        if self.kind == "csv":
            cells = next(csv.reader([text]))
        else:
            try:
                row = json.loads(text.lstrip("[").rstrip(",").rstrip("]"))
            except json.JSONDecodeError as err:
                return self._flagged(line, f"line {line}: not a JSON object ({err.msg})")
            if not isinstance(row, dict):
                return self._flagged(line, f"line {line}: not a JSON object")
            if self.columns is None:
                self.columns = Columns(self.basis, list(row), self.where)
            names = self.columns.names
            extra = sorted(set(row) - set(names))
            if extra or len(row) != len(names):
                missing = sorted(set(names) - set(row))
                what = f"key {extra[0]!r} not in the first object" if extra else f"no {missing[0]!r}"
                return self._flagged(line, f"line {line}: {what}; expected the first object's keys")
            cells = [row[name] for name in names]
        reading = self.columns.reading(cells, line, self.previous_time)
        if reading.flag is None:
            self.previous_time = reading.time
        return reading

    def _flagged(self, line, reason):
        return Reading(line, math.nan, np.full(self.basis.n, np.nan), flag=reason)


def read_readings(basis, path):
    """Every reading of a file (CSV or JSON), flagged rows included.

    Raises
    ------
    InvalidScene
        The file cannot be read, has no header or readings, or its columns do not match the plan.
    """
    where = f"--readings {path}"
    try:
        with open(path, encoding="utf-8") as handle:
            lines = handle.read().splitlines()
    except OSError as err:
        raise InvalidScene(f"{where}: cannot read ({err.strerror or err})") from None
    except UnicodeDecodeError:
        raise InvalidScene(f"{where}: not a text file; expected a CSV or JSON of readings") from None
    parser = ReadingParser(basis, where)
    text = "\n".join(lines).strip()
    if text.startswith("[") and "\n" not in text:  # a JSON array on one line
        try:
            rows = json.loads(text)
        except json.JSONDecodeError as err:
            raise InvalidScene(f"{where}: not valid JSON ({err.msg})") from None
        lines = [json.dumps(row) for row in rows] if isinstance(rows, list) else lines
    out = [r for k, line in enumerate(lines) if (r := parser.feed(line, k + 1)) is not None]
    if parser.columns is None:
        raise InvalidScene(f"{where}: empty; expected a header time,<crane or lug name>,... and readings")
    return out

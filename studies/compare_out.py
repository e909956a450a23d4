"""Compare the study outputs in studies/out/ with their committed version.

After ``python studies/run_all.py`` this says, file by file, whether the outputs reproduce:
the physics and plan results (tensions, spreads, chosen lugs, errors against published
numbers) must match; timings (seconds, rates, speed-ups, load averages, the machine) are
expected to differ from run to run and machine to machine and are reported apart.

Run:  python studies/compare_out.py                  (every file, against HEAD)
      python studies/compare_out.py --rev 4b07c8a    (against another commit)
      python studies/compare_out.py table3.csv planner_scale.json   (some files)
      python studies/compare_out.py -v               (also list every differing value)
      python studies/compare_out.py --tol 1e-6       (a looser relative tolerance)

The committed file is read with ``git show REV:studies/out/<file>``; the working file is the
one in studies/out/. Files are compared by kind:

* ``.json``: both trees are flattened to paths (``fleet.plan_best``, ``rows[3].seconds``)
  and compared value by value; numbers with the relative tolerance ``--tol`` (default
  1e-9; differences of at most ``--atol`` = 1e-12 in absolute value are rounding noise
  and pass), everything else exactly. A number in a list of numbers (a curve) is compared
  on the list's scale: its difference over the list's largest magnitude, so that a
  bending-moment curve's zero at the hull's end is not held to 1e-9 of itself.
* ``.csv``: cell by cell, row by row, each cell classified by its column's name.
* ``.md``: line by line; the numbers must be the same as printed (their strings equal), the
  rest of the line too. A number is a timing if its table column's header is, if a time or
  rate unit follows it (s, ms, us, µs, /s, M/s, x), or if it follows "load average".
* ``.png``: decoded to pixels (Pillow) and compared; a figure that differs is listed with
  the share of pixels that changed, to be looked at: a figure can show timings too.

Each differing value falls into one class:

* timing: a name in its path says it is a measured time or the machine's state
  (:func:`is_timing`): "time", "seconds", "speedup", "wall", the unit suffixes ``_s``,
  ``_ms``, ``_us``, rates ``per_s``, ``load_average`` / ``load_1min``, ``waited``,
  ``machine``, ``run`` (a date). ``NOT_TIMING`` lists names that look like timings but are
  results (draining's ``peak_time_s`` is simulated time);
* time-limited: a result of a search stopped by its time limit, which depends on the
  machine's speed: every value in a JSON object whose ``stopped`` is ``time_limit`` (in
  either version), and the paths in ``TIME_LIMITED``;
* (none): a value named in ``ZERO`` for its file, at most that small in both versions: a
  difference of two results that should be equal (planner_scale's ``excess`` of a plan
  over the proved optimum) is zero there, whatever its last digits;
* roundoff: a value whose name says it is a solver's leftover (``residual``, ``closure``)
  and is at most ``--noise`` (1e-6) in both versions: ideally zero, its last digits vary;
* physics: everything else; these must match.

Per file the verdict is ``same`` (byte for byte, or within the tolerances), ``timing-only``,
``roundoff`` (roundoff and timing differences only), ``time-limited`` (time-limited, roundoff
and timing differences only), ``PHYSICS`` (a physics value differs, with the largest
relative difference and where), ``STRUCTURE`` (keys, rows or lines added or removed),
``image differs``, ``new`` (not in REV) or ``missing`` (in REV, not on disk).
The exit status is 1 if any file is PHYSICS, STRUCTURE, new or missing, else 0.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import math
import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
OUT = HERE / "out"

#: Names that match the timing rules but are results, per file (or "*" for every file).
NOT_TIMING: dict[str, set[str]] = {
    "draining.csv": {"peak_time_s"},  # simulated time at the peak crane load
}
#: Paths (prefixes of the flattened JSON path) holding the result of a time-limited search
#: that records no ``stopped`` of its own, per file.
TIME_LIMITED: dict[str, tuple[str, ...]] = {
    # the spread-optimal plan: search_strength(..., time_limit=30.0), see spread_search.stopped
    "ferry_strength.json": ("spread.", "spread_search."),
}
#: Names whose values are zero when at most this small in both versions, per file: a
#: difference of two results that should be equal, which keeps their rounding.
ZERO: dict[str, dict[str, float]] = {
    # the plan's worst over the proved optimum - 1 [%]: below 1e-6 % the optimum itself
    "planner_scale.json": {"excess": 1e-6},
}
#: ``stopped`` values that mean a search ran out of time.
TIME_LIMIT_STOPS = {"time_limit", "time limit", "time"}

_WORDS_TIMING = {"time", "times", "timing", "seconds", "speedup", "wall", "waited", "machine", "run"}
_SUFFIX_TIMING = re.compile(r"_(s|ms|us)$")
_RATE = re.compile(r"(^|_)per_s(_|$)")
_LOAD = re.compile(r"^load_(average|1min)")
#: A number as a summary prints it (1,386 / -0.412 / 5.5e-14), then the unit after it, if any.
_MD_NUMBER = re.compile(
    r"""(?<![\w.])
        ([-+]?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:[eE][-+]?\d+)?)
        (\s*(?:µs|us|ms|s|M/s|/s|x)\b)?""",
    re.VERBOSE,
)
_MD_TIMING_UNITS = {"µs", "us", "ms", "s", "M/s", "/s", "x"}

_WORDS_RESIDUAL = {"residual", "residuals", "closure"}

TIMING, TIME_LIMITED_CLASS, ROUNDOFF, PHYSICS = "timing", "time-limited", "roundoff", "physics"


def is_timing(name: str, file: str = "") -> bool:
    """Whether one key or column name says its value is a measured time or the machine's state."""
    if name in NOT_TIMING.get(file, set()) | NOT_TIMING.get("*", set()):
        return False
    low = name.lower()
    words = set(re.split(r"[^a-z0-9]+", low))
    return bool(
        words & _WORDS_TIMING or _SUFFIX_TIMING.search(name) or _RATE.search(low) or _LOAD.search(low)
    )


@dataclass
class Difference:
    where: str
    old: object
    new: object
    kind: str  # TIMING, TIME_LIMITED_CLASS, ROUNDOFF or PHYSICS
    relative: float | None = None  # for numbers


@dataclass
class Result:
    file: str
    verdict: str = "same"
    differences: list[Difference] = field(default_factory=list)
    structure: list[str] = field(default_factory=list)
    note: str = ""

    def worst(self, kind: str) -> Difference | None:
        numeric = [d for d in self.differences if d.kind == kind and d.relative is not None]
        if numeric:
            return max(numeric, key=lambda d: d.relative)
        others = [d for d in self.differences if d.kind == kind]
        return others[0] if others else None

    def count(self, kind: str) -> int:
        return sum(d.kind == kind for d in self.differences)


def relative_difference(a: float, b: float, scale: float = 0.0) -> float:
    """|a - b| over the larger magnitude of the two (or ``scale`` if that is larger)."""
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    if math.isinf(a) or math.isinf(b) or math.isnan(a) or math.isnan(b):
        return math.inf
    return abs(a - b) / max(abs(a), abs(b), scale)


def _number(value) -> float | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return None
    return None


def is_residual(name: str) -> bool:
    """Whether a name says its value is a solver's leftover (ideally zero): residual, closure."""
    return bool(set(re.split(r"[^a-z0-9]+", name.lower())) & _WORDS_RESIDUAL)


class Comparer:
    def __init__(self, tol: float, atol: float, noise: float):
        self.tol, self.atol, self.noise = tol, atol, noise

    def value(self, result: Result, where: str, old, new, kind: str, name: str = "", scale: float = 0.0):
        """Record one differing value (numbers within the tolerances pass).

        ``name``: the key or column, for the residual rule; ``scale``: the largest magnitude in
        the list the value belongs to (0 for a single value), the relative difference's floor.
        """
        a, b = _number(old), _number(new)
        if a is not None and b is not None:
            zero = ZERO.get(result.file, {}).get(name)
            if a == b or abs(a - b) <= self.atol or (zero and max(abs(a), abs(b)) <= zero):
                return
            rel = relative_difference(a, b, scale)
            if rel <= self.tol:
                return
            if kind == PHYSICS and is_residual(name) and max(abs(a), abs(b)) <= self.noise:
                kind = ROUNDOFF
            result.differences.append(Difference(where, old, new, kind, rel))
        elif old != new:
            result.differences.append(Difference(where, old, new, kind))

    # JSON -----------------------------------------------------------------------------------------

    def json(self, result: Result, old_text: str, new_text: str) -> None:
        old, new = json.loads(old_text), json.loads(new_text)
        prefixes = TIME_LIMITED.get(result.file, ())
        self._walk(result, "", old, new, False, False, prefixes)

    def _walk(self, result, path, old, new, timing, limited, prefixes, name="", scale=0.0):
        if isinstance(old, dict) and isinstance(new, dict):
            stops = {str(old.get("stopped", "")), str(new.get("stopped", ""))}
            limited = limited or bool(stops & TIME_LIMIT_STOPS)
            for key in old.keys() | new.keys():
                sub = f"{path}.{key}" if path else str(key)
                if key not in old or key not in new:
                    result.structure.append(f"{sub}: {'added' if key not in old else 'removed'}")
                    continue
                timing_here = timing or is_timing(str(key), result.file)
                self._walk(result, sub, old[key], new[key], timing_here, limited, prefixes, str(key))
        elif isinstance(old, list) and isinstance(new, list) and _records(old) and _records(new):
            self._records(result, path, old, new, timing, limited, prefixes)
        elif isinstance(old, list) and isinstance(new, list):
            if len(old) != len(new):
                result.structure.append(f"{path}: {len(old)} items -> {len(new)}")
            numbers = [abs(x) for x in (*old, *new) if _number(x) is not None and not isinstance(x, str)]
            scale = max(numbers) if numbers and len(numbers) == len(old) + len(new) else 0.0  # a curve
            for i, (a, b) in enumerate(zip(old, new)):
                self._walk(result, f"{path}[{i}]", a, b, timing, limited, prefixes, name, scale)
        else:
            limited_here = limited or any((path + ".").startswith(p) for p in prefixes)
            kind = TIMING if timing else TIME_LIMITED_CLASS if limited_here else PHYSICS
            self.value(result, path, old, new, kind, name, scale)

    def _records(self, result, path, old, new, timing, limited, prefixes):
        """A list of records (rows of a table): paired by their labels, else by position."""
        fields = _label_fields(old, new, result.file)
        if not fields:
            if len(old) != len(new):
                result.structure.append(f"{path}: {len(old)} items -> {len(new)}")
            pairs = [(f"{path}[{i}]", a, b) for i, (a, b) in enumerate(zip(old, new))]
        else:
            by_label = {_label(b, fields): b for b in new}
            pairs = []
            for a in old:
                label = _label(a, fields)
                where = f"{path}[{', '.join(map(str, label))}]"
                if label in by_label:
                    pairs.append((where, a, by_label.pop(label)))
                else:
                    result.structure.append(f"{where}: removed")
            result.structure += [f"{path}[{', '.join(map(str, k))}]: added" for k in by_label]
        for where, a, b in pairs:
            self._walk(result, where, a, b, timing, limited, prefixes)

    # CSV ------------------------------------------------------------------------------------------

    def csv(self, result: Result, old_text: str, new_text: str) -> None:
        old = list(csv.DictReader(io.StringIO(old_text)))
        new = list(csv.DictReader(io.StringIO(new_text)))
        if len(old) != len(new):
            result.structure.append(f"{len(old)} rows -> {len(new)}")
        for i, (a, b) in enumerate(zip(old, new)):
            if a.keys() != b.keys():
                result.structure.append(f"row {i}: columns {sorted(a.keys() ^ b.keys())}")
            for column in a.keys() & b.keys():
                kind = TIMING if is_timing(column, result.file) else PHYSICS
                self.value(result, f"row {i + 2} {column}", a[column], b[column], kind, column)

    # Markdown -------------------------------------------------------------------------------------

    def markdown(self, result: Result, old_text: str, new_text: str) -> None:
        old, new = old_text.splitlines(), new_text.splitlines()
        if len(old) != len(new):
            result.structure.append(f"{len(old)} lines -> {len(new)}")
        header: list[str] = []
        for number, (a, b) in enumerate(zip(old, new), start=1):
            cells = _cells(a)
            if cells is None:
                header = []  # out of a table
            elif not header:
                header = cells  # a table's first row names its columns
            if a != b:
                self._markdown_line(result, number, a, b, header)

    def _markdown_line(self, result, number, a, b, header):
        cells_a, cells_b = _cells(a), _cells(b)
        if cells_a is not None and cells_b is not None and len(cells_a) == len(cells_b):
            pieces = [
                (cells_a[i], cells_b[i], header[i] if i < len(header) else "") for i in range(len(cells_a))
            ]
        else:
            pieces = [(a, b, "")]
        for text_a, text_b, column in pieces:
            if text_a == text_b:
                continue
            where = f"line {number}" + (f" [{column}]" if column else "")
            numbers_a, numbers_b = _md_numbers(text_a), _md_numbers(text_b)
            rest_a, rest_b = _MD_NUMBER.sub("#", text_a), _MD_NUMBER.sub("#", text_b)
            if rest_a != rest_b or len(numbers_a) != len(numbers_b):
                result.differences.append(Difference(where, text_a, text_b, PHYSICS))
                continue
            column_timing = bool(column) and is_timing(column, result.file)
            for (value_a, unit, after_load), (value_b, _, _) in zip(numbers_a, numbers_b):
                if value_a == value_b:
                    continue
                timing = column_timing or unit in _MD_TIMING_UNITS or after_load
                x, y = float(value_a.replace(",", "")), float(value_b.replace(",", ""))
                kind = TIMING if timing else PHYSICS
                result.differences.append(
                    Difference(where, value_a, value_b, kind, relative_difference(x, y))
                )

    # PNG ------------------------------------------------------------------------------------------

    def image(self, result: Result, old_bytes: bytes, new_bytes: bytes) -> None:
        try:
            import numpy as np
            from PIL import Image
        except ImportError:
            result.verdict, result.note = "image differs", "bytes differ (no Pillow to compare pixels)"
            return
        a = np.asarray(Image.open(io.BytesIO(old_bytes)).convert("RGBA"))
        b = np.asarray(Image.open(io.BytesIO(new_bytes)).convert("RGBA"))
        result.verdict = "image differs"
        if a.shape != b.shape:
            result.note = f"size {a.shape[1]}x{a.shape[0]} -> {b.shape[1]}x{b.shape[0]}"
            return
        changed = np.any(a != b, axis=-1)
        if not changed.any():
            result.verdict, result.note = "same", "pixels identical (bytes differ)"
            return
        rows, cols = np.nonzero(changed)
        result.note = (
            f"{changed.mean():.2%} of pixels changed, within x {cols.min()}-{cols.max()}, "
            f"y {rows.min()}-{rows.max()} of {a.shape[1]}x{a.shape[0]}: look at it"
        )


def _records(items: list) -> bool:
    return bool(items) and all(isinstance(item, dict) for item in items)


def _label(record: dict, fields: list[str]) -> tuple:
    return tuple(tuple(v) if isinstance(v := record.get(f), list) else v for f in fields)


def _label_fields(old: list[dict], new: list[dict], file: str) -> list[str]:
    """The fields that name a record rather than give its result: strings (or short lists of
    scalars) in every record, not timings, taking the same values in both versions, and
    together different in each record (planner_scale's problem and method). [] if none do."""

    def labels(items, key):
        values = [item.get(key) for item in items]
        ok = all(isinstance(v, str) or (isinstance(v, list) and _short_scalars(v)) for v in values)
        return sorted(map(str, values)) if ok else None

    keys = set.intersection(*(set(item) for item in old + new))
    fields = sorted(
        k
        for k in keys
        if not is_timing(k, file) and labels(old, k) is not None and labels(old, k) == labels(new, k)
    )
    for items in (old, new):
        if not fields or len({_label(item, fields) for item in items}) != len(items):
            return []
    return fields


def _short_scalars(values: list) -> bool:
    """A short list of scalars, as a start attitude (20.0, 5.0); not a histogram."""
    return len(values) <= 4 and all(isinstance(v, str | int | float | bool) or v is None for v in values)


def _cells(line: str) -> list[str] | None:
    line = line.strip()
    if not (line.startswith("|") and line.endswith("|")):
        return None
    return [cell.strip() for cell in line[1:-1].split("|")]


def _md_numbers(text: str) -> list[tuple[str, str, bool]]:
    """The numbers in a piece of text: (as printed, the unit after it, after 'load average')."""
    load_at = text.lower().find("load average")
    return [
        (m.group(1), (m.group(2) or "").strip(), 0 <= load_at < m.start()) for m in _MD_NUMBER.finditer(text)
    ]


# git and the driver ------------------------------------------------------------------------------


def git(*args: str) -> bytes:
    """A git command's output, run at the repository's top (where REV:path names are rooted)."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], cwd=HERE, check=True, capture_output=True)
    top = root.stdout.decode().strip()
    return subprocess.run(["git", *args], cwd=top, check=True, capture_output=True).stdout


def committed_files(rev: str, relative: str) -> set[str]:
    """The files (not folders) directly in the folder at REV."""
    listing = git("ls-tree", rev, "--", f"{relative}/").decode().splitlines()
    return {line.split("\t", 1)[1].rsplit("/", 1)[-1] for line in listing if " blob " in line}


def compare_file(comparer: Comparer, name: str, rev: str, relative: str, names_at_rev: set[str]) -> Result:
    result = Result(name)
    path = OUT / name
    if name not in names_at_rev:
        result.verdict = "new"
        return result
    if not path.exists():
        result.verdict = "missing"
        return result
    old_bytes, new_bytes = git("show", f"{rev}:{relative}/{name}"), path.read_bytes()
    if old_bytes == new_bytes:
        return result
    suffix = path.suffix.lower()
    if suffix == ".png":
        comparer.image(result, old_bytes, new_bytes)
        return result
    old_text, new_text = old_bytes.decode(), new_bytes.decode()
    if suffix == ".json":
        comparer.json(result, old_text, new_text)
    elif suffix == ".csv":
        comparer.csv(result, old_text, new_text)
    elif suffix == ".md":
        comparer.markdown(result, old_text, new_text)
    else:
        result.differences.append(Difference("(whole file)", "...", "...", PHYSICS))
    if result.structure:
        result.verdict = "STRUCTURE"
    elif result.count(PHYSICS):
        result.verdict = "PHYSICS"
    elif result.count(TIME_LIMITED_CLASS):
        result.verdict = "time-limited"
    elif result.count(ROUNDOFF):
        result.verdict = "roundoff"
    elif result.count(TIMING):
        result.verdict = "timing-only"
    else:
        result.verdict, result.note = "same", "differs only within the tolerances"
    return result


def _show(value, width: int = 40) -> str:
    text = repr(value) if not isinstance(value, str) else value
    return text if len(text) <= width else text[: width - 3] + "..."


def describe(result: Result) -> str:
    parts = []
    for kind in (PHYSICS, TIME_LIMITED_CLASS, ROUNDOFF, TIMING):
        worst = result.worst(kind)
        if worst is None:
            continue
        size = f"max rel {worst.relative:.2g}" if worst.relative is not None else "text"
        parts.append(
            f"{kind}: {result.count(kind)} values, {size} at {worst.where} "
            f"({_show(worst.old, 24)} -> {_show(worst.new, 24)})"
        )
    if result.structure:
        more = " ..." if len(result.structure) > 3 else ""
        parts.insert(0, f"structure: {'; '.join(result.structure[:3])}{more}")
    if result.note:
        parts.append(result.note)
    return "; ".join(parts)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", help="file names in studies/out/ (default: all)")
    parser.add_argument("--rev", default="HEAD", help="the commit to compare with (default HEAD)")
    parser.add_argument("--tol", type=float, default=1e-9, help="relative tolerance for numbers")
    parser.add_argument("--atol", type=float, default=1e-12, help="absolute difference taken as rounding")
    parser.add_argument(
        "--noise", type=float, default=1e-6, help="largest residual / closure taken as a solver's leftover"
    )
    parser.add_argument("-v", "--verbose", action="store_true", help="list every differing value")
    args = parser.parse_args(argv)

    root = Path(git("rev-parse", "--show-toplevel").decode().strip())
    relative = OUT.relative_to(root).as_posix()
    names_at_rev = committed_files(args.rev, relative)
    on_disk = {p.name for p in OUT.iterdir() if p.is_file()}
    names = sorted(args.files or (names_at_rev | on_disk))
    comparer = Comparer(args.tol, args.atol, args.noise)

    bad = 0
    width = max(map(len, names), default=0)
    for name in names:
        result = compare_file(comparer, name, args.rev, relative, names_at_rev)
        bad += result.verdict in {"PHYSICS", "STRUCTURE", "new", "missing"}
        print(f"{name:<{width}}  {result.verdict:<13}  {describe(result)}".rstrip())
        if args.verbose:
            for line in result.structure:
                print(f"    structure  {line}")
            for d in result.differences:
                size = f"  rel {d.relative:.3g}" if d.relative is not None else ""
                print(f"    {d.kind:<12} {d.where}: {_show(d.old, 60)} -> {_show(d.new, 60)}{size}")
    print(f"\n{len(names)} files against {args.rev}; {bad} with physics, structure, new or missing")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

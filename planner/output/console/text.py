"""Text layout of the console summaries: a width every table fits, long tables in groups,
long lines of text folded (``liftplan plan``; :mod:`.plan_console`, :mod:`.sling_console`)."""

from __future__ import annotations

#: Columns of the console: every table fits, a longer line of text is folded (:func:`fold`).
WIDTH = 100
#: Rows of a long table come in groups of this many, a blank line between (from 2 groups on).
GROUP = 8


def grouped(rows, size=GROUP):
    """Table rows with a blank line after every ``size`` of them, when there are more than
    2 ``size`` (a long column is read by its groups)."""
    if len(rows) <= 2 * size:
        return list(rows)
    out = []
    for start in range(0, len(rows), size):
        out += ([""] if start else []) + list(rows[start : start + size])
    return out


def fold(line, width=WIDTH, indent="  "):
    """A line of text folded to ``width`` columns: at the last "; " that fits, else the last
    ", ", else the last space, never inside parentheses (a point's coordinates stay on one
    line); continuation lines indented. Lines that fit are kept."""
    out = []
    while len(line) > width:
        depth, level = 0, []
        for char in line[: width + 1]:
            depth += (char == "(") - (char == ")")
            level.append(depth)
        cut = None
        for outside in (True, False):  # a parenthesis stays whole where it can
            for mark in ("; ", ", ", " "):
                spots = [
                    k
                    for k in range(len(indent) + 1, width)
                    if line.startswith(mark, k) and (level[k] == 0 or not outside)
                ]
                if spots:
                    cut = spots[-1] + len(mark.rstrip())
                    break
            if cut is not None:
                break
        if cut is None:
            break  # no place to fold: kept whole
        out.append(line[:cut].rstrip())
        line = indent + line[cut:].lstrip()
    return out + [line]

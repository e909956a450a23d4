"""The report's title block: who the plan is for and who signs it (``[report]`` in a
planning file).

Every field is a plain string shown on page 1 of the report; an empty field prints as a blank
line to be filled in by hand. ``date`` empty means the day the report is written.
"""

from __future__ import annotations

import datetime
from dataclasses import dataclass, fields

from liftplan.model.errors import InvalidScene

#: Longest field accepted [characters]: a title block line, not a paragraph.
MAX_LENGTH = 200

#: Field -> label in the title block, in the order printed.
LABELS = {
    "project": "Project",
    "client": "Client",
    "document": "Document no.",
    "revision": "Revision",
    "date": "Date",
    "prepared_by": "Prepared by",
    "checked_by": "Checked by",
    "approved_by": "Approved by",
}


@dataclass(frozen=True)
class ReportInfo:
    """The title block of a report; every field may be empty.

    Parameters
    ----------
    project : str
        Project name (also in the running header of every page).
    client : str
    document : str
        Document number.
    revision : str
        Revision (e.g. ``"A"``, ``"0"``, ``"P1"``).
    prepared_by, checked_by, approved_by : str
        Names (or initials) of who prepared, checked and approved the plan.
    date : str
        The issue date as it should be printed; empty: the day the report is written.
    """

    project: str = ""
    client: str = ""
    document: str = ""
    revision: str = ""
    prepared_by: str = ""
    checked_by: str = ""
    approved_by: str = ""
    date: str = ""

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            if not isinstance(value, str):
                raise InvalidScene(f"report.{f.name} = {value!r}: expected a string")
            if len(value) > MAX_LENGTH:
                raise InvalidScene(
                    f"report.{f.name} = {value[:20]!r}... ({len(value)} characters): "
                    f"expected at most {MAX_LENGTH} characters"
                )
            if any(ord(c) < 32 for c in value):
                raise InvalidScene(
                    f"report.{f.name} = {value!r}: expected one line (no control characters or line breaks)"
                )
            object.__setattr__(self, f.name, value.strip())

    def rows(self, today=None):
        """(label, value) per field in print order; ``date`` defaults to ``today``.

        Parameters
        ----------
        today : datetime.date, optional
            Default: the current date.
        """
        day = (today or datetime.date.today()).isoformat()
        return [
            (label, (getattr(self, name) or day) if name == "date" else getattr(self, name))
            for name, label in LABELS.items()
        ]

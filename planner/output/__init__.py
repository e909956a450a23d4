"""What a person reads: console tables, figures, the A4 report, and the rule for output paths.

Nothing here is imported until a command needs it (matplotlib and WeasyPrint are heavy):
:mod:`.console` (solve, lift, batch tables; the plan summaries in :mod:`.plan_console` and
:mod:`.sling_console`; many ropes grouped by :mod:`.rope_table`), :mod:`.figures` and
:mod:`.strength_figure` (matplotlib, object API), :mod:`.report` / :mod:`.sling_report` with
:mod:`.report_page` (HTML and PDF), :mod:`.paths` (one rule for every output path).
"""

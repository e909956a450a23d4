"""The handlers of ``liftplan watch`` and ``liftplan simulate`` (loaded when they run; their
options are in :mod:`.command`)."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from liftplan.model.errors import InvalidScene
from liftplan.planner.output.paths import make_parent, output_file, replaced
from liftplan.planner.plan import plan
from liftplan.planner.plans.watch_basis import WatchBasis, watch_basis
from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.progress import progress_bar
from liftplan.planner.watch.readings import ReadingParser, read_readings
from liftplan.planner.watch.simulate import Errors, Noise, simulate, truth_json, write_csv
from liftplan.planner.watch.update import Watcher, file_frame

CHECK_FAILED = 4
#: Seconds between looks at a followed file.
POLL = 0.1


def load_basis(path):
    """The :class:`WatchBasis` of a planning file (planned now) or of a plan JSON."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise InvalidScene(f"{path}: cannot read ({err.strerror or err})") from None
    except UnicodeDecodeError:
        raise InvalidScene(f"{path}: not a text file; expected a planning file or a plan JSON") from None
    if text.lstrip().startswith("{"):
        try:
            data = json.loads(text)
        except json.JSONDecodeError as err:
            raise InvalidScene(f"{path}: not valid JSON ({err.msg}); expected a plan JSON") from None
        return WatchBasis.from_json(data.get("watch") if isinstance(data, dict) else None, where=str(path))
    result = plan(load_problem(path))
    failed = [c for c in result.checks if not c.ok]
    if failed:  # the lift is watched against this plan all the same: say that it fails a check
        names = ", ".join(f"{c.name} {c.subject}" for c in failed[:3])
        print(
            f"liftplan: warning: {path}: the plan fails {len(failed)} check(s) ({names}); watched as planned",
            file=sys.stderr,
        )
    return watch_basis(result)


def watch(args):
    """``liftplan watch``: the exit code."""
    if args.idle is not None and not args.idle > 0:
        raise InvalidScene(f"--idle {args.idle:g}: expected a number of seconds > 0")
    if args.idle is not None and not args.follow:
        raise InvalidScene("--idle: only with --follow; expected --follow --idle S")
    readings_path = Path(args.readings)
    if not args.follow and not readings_path.is_file():
        raise InvalidScene(f"--readings {readings_path}: no such file; expected a CSV or JSON of readings")
    watcher = Watcher(load_basis(args.plan))
    failed = 0
    if args.follow:
        updates = _followed(watcher, readings_path, args.idle)
    else:
        readings = read_readings(watcher.basis, readings_path)
        updates = _replayed(watcher, readings)
    for update in updates:
        print(json.dumps(update.to_json()) if args.json else line(update), flush=args.follow)
        failed += update.stop
    if failed:
        print(f"liftplan: {failed} reading(s) flagged or with the stop signal (exit 4)", file=sys.stderr)
        return CHECK_FAILED
    return 0


def _replayed(watcher, readings):
    bar = progress_bar(len(readings), None, desc="watch", unit="readings")
    try:
        for reading in readings:
            yield watcher.update(reading)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()


def _followed(watcher, path, idle):
    """Updates of a file as lines are added to it (a partial last line waits for its end)."""
    parser = ReadingParser(watcher.basis, f"--readings {path}")
    waited = 0.0
    while not path.exists():
        time.sleep(POLL)
        waited += POLL
        if idle is not None and waited >= idle:
            raise InvalidScene(f"--readings {path}: no such file after {idle:g} s")
    with open(path, encoding="utf-8") as handle:
        pending, count, last = "", 0, time.monotonic()
        while True:
            chunk = handle.readline()
            if chunk:
                pending += chunk
                if not pending.endswith("\n"):
                    continue
                count += 1
                text, pending = pending, ""
                reading = parser.feed(text, count)
                last = time.monotonic()
                if reading is not None:
                    yield watcher.update(reading)
                continue
            if idle is not None and time.monotonic() - last >= idle:
                return
            time.sleep(POLL)


def line(update):
    """One reading's update as a console line."""
    e, r = update.estimate, update.reading
    head = f"t {r.time:8.2f} s" if r.time == r.time else f"line {r.line}"
    if e is None:
        return f"{head}  STOP  {update.reason}"
    labels = update.basis.labels
    weight = "-" if e.reasons[0] else f"{e.weight:.1f}+-{e.sigma[0]:.1f} t"
    value, sigma, _ = file_frame(e, update.basis.frame)
    cog = ", ".join("-" if v is None else f"{v:.2f}+-{s:.2f}" for v, s in zip(value, sigma))
    hooks = " ".join(
        f"{label} {'-' if e.reasons[4 + k] else f'{e.state[4 + k] * 100:+.1f}'}"
        for k, label in enumerate(labels)
    )
    moves = " ".join(f"{label} {m * 100:+.1f}" for label, m in zip(labels, update.advice.moves))
    verdict = "STOP" if update.stop else "ok"
    return (
        f"{head}  W {weight}  CG ({cog}) m  hook errors [cm] {hooks}  move [cm] {moves}  {verdict}: "
        f"{update.reason}"
    )


def _pairs(text, option, keys):
    out = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, sep, value = part.partition("=")
        key = key.strip()
        if not sep or key not in keys:
            raise InvalidScene(
                f"{option} {text!r}: {part!r}; expected KEY=VALUE with KEY one of {', '.join(keys)}"
            )
        try:
            out[key] = float(value)
        except ValueError:
            raise InvalidScene(f"{option} {text!r}: {key} = {value!r} is not a number") from None
    return out


def simulate_lift(args):
    """``liftplan simulate``: the exit code."""
    output = output_file(args.output, "--output", (".csv",))
    truth = output_file(args.truth, "--truth", (".json",)) if args.truth else None
    errors = Errors(**_pairs(args.errors, "--errors", ("hook", "cog", "weight")))
    basis = load_basis(args.plan)
    accuracy = basis.accuracy
    noise = Noise(
        **{
            "load_cell": accuracy.load_cell,
            "inclinometer": accuracy.inclinometer,
            "hook": accuracy.hook,
            **_pairs(args.noise, "--noise", ("load_cell", "inclinometer", "hook")),
        }
    )
    lift = simulate(
        basis,
        errors,
        noise,
        seed=args.seed,
        steps=args.steps,
        rate=args.rate,
        drift=args.drift,
        inclinometer=not args.no_inclinometer,
        hooks=args.hook_heights,
    )
    make_parent(output)
    with replaced(output) as temporary, open(temporary, "w", encoding="utf-8") as handle:
        write_csv(basis, lift, handle)
    written = [str(output)]
    if truth is not None:
        make_parent(truth)
        with replaced(truth) as temporary, open(temporary, "w", encoding="utf-8") as handle:
            json.dump(truth_json(basis, lift), handle)
        written.append(str(truth))
    print(f"liftplan: wrote {', '.join(written)}", file=sys.stderr)
    return 0

"""Run a batch study (:mod:`~liftplan.planner.batch.study`) on Dask and write a tidy table.

One row per case, failed cases included with their reason; never an aborted sweep. Rows
are appended to a journal (``OUTPUT.partial``) as tasks finish, so an interrupted run
resumes where it stopped when the same command is run again; the table itself is written
whole, sorted by case, only when every case is done.

Dask's local cluster (one single-threaded worker process per core: the casadi calls hold
the GIL) is the default; ``scheduler`` connects to a running cluster instead, whose workers
must have liftplan installed.
"""

from __future__ import annotations

import csv
import logging
import os
import signal
import sys
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from liftplan.model.errors import InvalidScene, LiftPlanError, PlanInfeasible
from liftplan.model.extras import require
from liftplan.model.frames import choi_to_zup
from liftplan.model.statics.model import rope_model
from liftplan.planner.batch.check import CheckCases, check_plan
from liftplan.planner.batch.lock import output_lock
from liftplan.planner.batch.montecarlo import block_solver, draw_units, solve_draws
from liftplan.planner.plan import plan

#: Result columns of each kind of study (after ``case``, the parameters, status, reason).
RESULTS = {
    "plan": [
        "lugs",
        "boom_heights",
        "spread",
        "worst_spread",
        "worst_heel",
        "worst_trim",
        "min_tension",
        "max_tension",
        "utilisation",
        "bound",
        "evaluated",
        "seconds",
    ],
    "check": ["worst_spread", "worst_heel", "worst_trim", "min_tension", "max_tension", "utilisation"],
    # a Monte-Carlo draw: tension.L1..Ln first (see results_columns), then these
    # (above_design_tension last: added after the others, so scripts reading by position hold)
    "montecarlo": [
        "heel",
        "trim",
        "spread",
        "max_tension",
        "above_plan_worst",
        "above_design_load",
        "above_swl",
        "slack",
        "above_design_tension",
    ],
}
JOURNAL_MARK = "# liftplan batch"


@dataclass(frozen=True)
class BatchSummary:
    """What a batch run did.

    Parameters
    ----------
    output : pathlib.Path
        The table written.
    cases : int
        Cases in the study.
    ran : int
        Cases run by this call (the rest were done by an interrupted run).
    counts : dict of str to int
        Cases per status, over the whole table.
    seconds : float  [s]
        Wall time of this call's cases (cluster start excluded).
    cores : int
        Worker threads.
    """

    output: Path
    cases: int
    ran: int
    counts: dict
    seconds: float
    cores: int

    @property
    def rate_per_core(self):
        """Cases per second per core in this call  [1/s]."""
        return self.ran / self.seconds / self.cores if self.ran and self.seconds > 0 else 0.0


def results_columns(study):
    """The result columns of a study's table."""
    if study.kind == "montecarlo":
        return [f"tension.{label}" for label in study.labels] + RESULTS["montecarlo"]
    return RESULTS[study.kind]


def header(study):
    return ["case", *study.columns(), "status", "reason", *results_columns(study)]


def run_study(study, client=None, scheduler=None, workers=None, restart=False, progress=True, output=None):
    """Run every case of a study not yet done and write its table.

    Parameters
    ----------
    study : Study
    client : dask.distributed.Client, optional
        Use this client (the caller owns it).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``); default a local cluster.
    workers : int, optional
        Local cluster size (default: one per core).
    restart : bool
        Discard the journal of an interrupted run instead of resuming it.
    progress : bool
        Show a progress bar on stderr.
    output : path, optional
        Overrides the study's output table.

    Returns
    -------
    BatchSummary

    Raises
    ------
    PlanInfeasible
        A ``check`` study whose base scene has no feasible plan.
    LiftPlanError
        The scheduler cannot be reached, or the journal belongs to another study.
    OutputLocked
        Another run is writing the same output table (its pid, host and start time).
    """
    require("batch", "dask.distributed", "msgpack")  # before any work, in one line
    output = Path(output or study.output)
    with output_lock(output):  # one run per table: a second is refused, never interleaved
        return _run(study, client, scheduler, workers, restart, progress, output)


def _run(study, client, scheduler, workers, restart, progress, output):
    """:func:`run_study` holding the output's lock."""
    from tqdm import tqdm

    if client is None and scheduler:
        probe_scheduler(scheduler)  # before any work: a wrong address costs seconds, not a plan
    # the plan every case checks (or draws hook errors on)
    base = plan(study.problem({})) if study.kind in ("check", "montecarlo") else None
    journal = Journal(output.with_name(output.name + ".partial"), study, restart)
    pending = [(i, case) for i, case in study.cases() if i not in journal.done]
    runnable = pending
    if study.kind == "check":
        # a grid point that is no valid planning scene (each sweep value is; a combination
        # may not be): its cases are invalid rows with the reason, not numbers
        reasons, per = study.grid_reasons, max(study.sample_count, 1)
        journal.write(
            [
                _row(study, i, case, "invalid", _one_line_text(reasons[i // per]))
                for i, case in pending
                if reasons[i // per]
            ]
        )
        runnable = [(i, case) for i, case in pending if not reasons[i // per]]
    tasks = _tasks(study, runnable, base)
    seconds, cores = 0.0, 1
    if tasks:
        with _connect(client, scheduler, workers) as dask_client:
            from dask.distributed import as_completed

            cores = sum(dask_client.nthreads().values())
            # imports and casadi JIT compiles on every worker before the clock starts
            dask_client.run(
                warm_up, len(base.chosen.indices) if base is not None else None, study.kind == "montecarlo"
            )
            start = time.perf_counter()
            futures = {dask_client.submit(fn, *args, pure=False): chunk for fn, args, chunk in tasks}
            with tqdm(
                total=study.size,
                initial=study.size - len(runnable),
                unit="case",
                disable=not progress,
                file=sys.stderr,
                dynamic_ncols=True,
            ) as bar:
                for future in as_completed(futures):
                    try:
                        rows = _rows(study, futures[future], future.result(), base)
                    except Exception as err:  # noqa: BLE001 - a lost worker fails its cases only
                        rows = _failed_rows(study, futures[future], "error", _one_line(err))
                    journal.write(rows)
                    bar.update(len(rows))
            seconds = time.perf_counter() - start
    counts = journal.finish(output)
    return BatchSummary(
        output=output, cases=study.size, ran=len(pending), counts=counts, seconds=seconds, cores=cores
    )


@contextmanager
def _connect(client, scheduler, workers):
    if client is not None:
        yield client
        return
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout=f"{HANDSHAKE_SECONDS}s")
        except Exception as err:  # noqa: BLE001 - whatever answers there, one line naming it
            raise LiftPlanError(
                f"--scheduler {scheduler}: cannot connect ({_one_line(err)}); expected the address "
                "of a running Dask scheduler, e.g. tcp://10.0.0.5:8786"
            ) from None
        with client:
            yield client
        return
    count = workers or os.cpu_count() or 1
    # Ctrl-C is the command's to handle: workers started with SIGINT ignored keep it so (it
    # survives exec), and print no tracebacks or solver warnings of their own when it comes
    main = threading.current_thread() is threading.main_thread()  # only it may set handlers
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        cluster = LocalCluster(
            n_workers=count,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        )
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)
    with _quiet_close() as quiet, cluster, Client(cluster) as client:
        try:
            yield client
        finally:
            quiet(client)


#: Dask's loggers (and those of the event loops under it) that report a closing cluster.
DASK_LOGGERS = ("distributed", "tornado", "asyncio")


def _silence_dask():
    """Dask's loggers in this process to CRITICAL; their levels before (a Dask task too)."""
    previous = {name: logging.getLogger(name).level for name in DASK_LOGGERS}
    for name in DASK_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL)
    return previous


@contextmanager
def _quiet_close():
    """A local cluster closed without Dask's shutdown noise.

    Closing a cluster races its workers' last heartbeats and result messages: a worker
    whose connection closes under it logs a ``CommClosedError`` traceback at ERROR (seen
    around a successful study with one row per chunk). None of it concerns the study, whose
    rows are all in by then, so stderr is kept for liftplan's own lines: yields a function
    that, given the client, turns Dask's loggers to CRITICAL in every worker, every nanny
    and this process (the scheduler's) just before the close; this process's levels are put
    back after it. (A local cluster's nannies live in this process.)
    """
    previous = {}

    def quiet(client):
        previous.update(_silence_dask())
        try:
            client.run(_silence_dask)
        except Exception:  # noqa: BLE001, S110 - a worker already gone has nothing to say
            pass

    try:
        yield quiet
    finally:
        for name, level in previous.items():
            logging.getLogger(name).setLevel(level)


#: Seconds a scheduler has to answer the connection handshake.
HANDSHAKE_SECONDS = 10.0
#: A Dask handshake is ~100 bytes; a first frame larger than this is another protocol.
_HANDSHAKE_BYTES = 1 << 16


def probe_scheduler(address, timeout=HANDSHAKE_SECONDS):
    """Check that a Dask scheduler answers at ``address`` within ``timeout`` seconds.

    A Dask scheduler greets each connection with a small msgpack handshake frame. Anything
    else (an HTTP server waiting for a request, a service sending text) is refused here in
    one line, where Dask itself would wait for ever or read the text as a frame length of
    exabytes. ``tcp://`` addresses (and bare ``host:port``) are probed so; other protocols
    (``tls://``, ``inproc://``, ...) by connecting a Dask client with its own configuration
    and closing it: either way before the base plan is computed and any journal written.

    Raises
    ------
    LiftPlanError
        Naming the address and what answered.
    """

    def refuse(why):
        return LiftPlanError(
            f"--scheduler {address}: {why}; expected the address of a running Dask "
            "scheduler, e.g. tcp://10.0.0.5:8786"
        )

    if str(address).startswith("inproc://"):  # a scheduler inside this very process: a command has none
        raise refuse("an inproc:// scheduler lives inside one Python process, never another's")
    import socket
    import struct

    import msgpack
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address)
        if scheme != "tcp":
            _probe_client(address, timeout, refuse)
            return
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as err:
        raise refuse(f"not an address ({err})") from None
    deadline = time.monotonic() + timeout

    def read(sock, count):
        data = b""
        while len(data) < count:
            sock.settimeout(max(deadline - time.monotonic(), 1e-3))
            chunk = sock.recv(count - len(data))
            if not chunk:
                raise refuse("the connection was closed before a Dask handshake")
            data += chunk
        return data

    try:
        with socket.create_connection((host, port), timeout=timeout) as sock:
            (size,) = struct.unpack("<Q", read(sock, 8))
            if not 16 <= size <= _HANDSHAKE_BYTES:
                raise refuse("something answered, but not a Dask scheduler (not its handshake)")
            body = read(sock, size)
    except TimeoutError:
        raise refuse(f"no Dask handshake within {timeout:g} s") from None
    except OSError as err:
        raise refuse(f"cannot connect ({err.strerror or err})") from None
    try:
        (frames,) = struct.unpack_from("<Q", body)
        first = struct.unpack_from("<Q", body, 8)[0]
        greeting = msgpack.loads(body[8 + 8 * frames : 8 + 8 * frames + first])
        ok = isinstance(greeting, dict) and "python" in greeting
    except (struct.error, ValueError, msgpack.UnpackException):
        ok = False
    if not ok:
        raise refuse("something answered, but not a Dask scheduler (not its handshake)")


def _probe_client(address, timeout, refuse):
    """Connect a Dask client to ``address`` and close it; a :class:`LiftPlanError` (from
    ``refuse``) naming why it could not connect."""
    from dask.distributed import Client

    try:
        with Client(address, timeout=f"{timeout}s"):
            pass
    except Exception as err:  # noqa: BLE001 - whatever failed, one line naming it
        raise refuse(f"cannot connect ({_one_line(err)})") from None


def _tasks(study, pending, base):
    """(function, arguments, cases) per Dask task; ``base`` is the plan a check study checks."""
    chunks = [pending[k : k + study.chunk] for k in range(0, len(pending), study.chunk)]
    if study.kind == "plan":
        return [(plan_rows, (study, chunk), chunk) for chunk in chunks]
    if study.kind == "montecarlo":
        return montecarlo_tasks(study, base, pending)
    # numbers, not Python objects, cross to the workers and back: Dask moves arrays fast
    # and lists of dicts slowly (measured 2 s of 4 for 60 000 cases)
    return [
        (
            check_chunk,
            (
                CheckTask(
                    base.problem,
                    base.chosen.indices,
                    base.chosen.preload,
                    check_cases(study, base.problem, chunk),
                    study.grid,
                    base.chosen.cranes,
                ),
            ),
            chunk,
        )
        for chunk in chunks
    ]


@dataclass(frozen=True)
class CheckTask:
    """One Dask task of a ``check`` study: the plan and a chunk of cases as arrays."""

    problem: object
    indices: tuple
    preload: np.ndarray
    cases: CheckCases
    grid: int
    cranes: tuple = None


def montecarlo_tasks(study, base, pending):
    """(function, arguments, cases) per Dask task of a ``montecarlo`` study.

    Every draw is made here from the seed (the same numbers however the run is chunked or
    resumed); a task takes the plan's scene and its chunk of errors as one array.
    """
    spec = study.montecarlo
    scale = spec.scale(base)
    errors = draw_units(spec.draws, len(base.labels), spec.distribution, spec.seed) * scale
    chunks = [pending[k : k + study.chunk] for k in range(0, len(pending), study.chunk)]
    return [(montecarlo_chunk, (base.scene, errors[[i for i, _ in chunk]]), chunk) for chunk in chunks]


def montecarlo_chunk(scene, errors):
    """Solve one chunk of draws (runs on a worker): (errors, tensions, heel, trim) arrays."""
    tensions, heel, trim = solve_draws(scene, errors)
    return errors, tensions, heel, trim


def montecarlo_rows(study, base, cases, result):
    """Table rows of a chunk of Monte-Carlo draws, judged against the plan."""
    errors, tensions, heel, trim = result
    design = np.array([c.design_hook_load for c in base.capacity])
    covered = np.array([c.design_tension for c in base.capacity])  # the same, static
    swl = np.asarray(base.chosen.swl, dtype=float)
    limit = base.lugset.limit  # the plan's own limit (the rules' chain under the chart SWL)
    labels = base.labels
    rows = []
    for (index, _), e, t, h, r in zip(cases, errors, tensions, heel, trim):
        numbers = [float(v) for v in e]
        if not np.all(np.isfinite(t)):
            rows.append(
                [
                    index,
                    *numbers,
                    "failed",
                    "no stable upright elastic equilibrium for these hook errors",
                    *([""] * len(results_columns(study))),
                ]
            )
            continue
        spread = float(np.ptp(t))
        slack = int(np.sum(t <= 0.0))
        over = np.flatnonzero(t > limit)
        status, reason = "ok", ""
        if over.size:
            i = int(over[np.argmax(t[over] - limit[over])])
            status, reason = (
                "unsafe",
                f"rope {labels[i]} {t[i]:.1f} t over the plan's limit {limit[i]:.1f} t (chart SWL "
                f"{swl[i]:g} t by the rules' chain)",
            )
        elif slack:
            i = int(np.argmin(t))
            status, reason = "unsafe", f"rope {labels[i]} slack"
        rows.append(
            [
                index,
                *numbers,
                status,
                reason,
                *t.tolist(),
                float(h),
                float(r),
                spread,
                float(t.max()),
                int(spread > base.worst_spread + 1e-6),
                _above(t, design),
                int(np.any(t > swl)),
                slack,
                _above(t, covered),
            ]
        )
    return rows


def _above(tensions, limits):
    """1 if a rope is above its limit, 0 if none is; "" when a limit is unknown (a design
    load not computed is no pass)."""
    if not np.all(np.isfinite(limits)):
        return ""
    return int(np.any(tensions > limits))


def check_chunk(task):
    """Check one chunk of cases (runs on a worker); returns a :class:`CheckResult`."""
    return check_plan(
        task.problem, task.indices, task.preload, task.cases, grid=task.grid, cranes=task.cranes
    )


def check_cases(study, problem, cases):
    """The :class:`CheckCases` arrays of ``check`` cases (file frame to ``z-up``)."""
    to_zup = choi_to_zup if problem.frame == "choi" else tuple
    values = [case for _, case in cases]
    base_cog = tuple(study.base["body"]["cog"])

    def column(key, default):
        return np.array([float(v.get(key, default)) for v in values])

    return CheckCases(
        weight=column("body.weight", problem.body.weight),
        cog=np.array([to_zup(tuple(v.get("body.cog", base_cog))) for v in values], dtype=float),
        heel_tolerance=column("plan.tolerance.heel", problem.heel_tolerance),
        trim_tolerance=column("plan.tolerance.trim", problem.trim_tolerance),
        min_tension=column("plan.min_tension", problem.min_tension),
    )


def _rows(study, cases, result, base=None):
    """Table rows of a finished task (``plan``: rows already; ``check``, ``montecarlo``:
    from the arrays)."""
    if study.kind == "plan":
        return result
    if study.kind == "montecarlo":
        return montecarlo_rows(study, base, cases, result)
    numbers = np.column_stack(
        [
            result.worst_spread,
            result.worst_heel,
            result.worst_trim,
            result.min_tension,
            result.max_tension,
            result.utilisation,
        ]
    )
    return [
        _row(study, index, case, status, reason, row.tolist())
        for (index, case), status, reason, row in zip(cases, result.status, result.reason, numbers)
    ]


def warm_up(cranes=None, elastic=False):
    """Import the planner on a worker, and compile the batched model of ``cranes`` ropes
    (``elastic``: the mapped elastic solve of a Monte-Carlo study instead)."""
    # start-up of a worker: the planner is loaded before its first case, not during it
    import liftplan.planner.plans.held  # noqa: F401

    if cranes is not None and elastic:
        block_solver(cranes)
    elif cranes is not None:
        rope_model(cranes).held_columns  # noqa: B018 - compiled on first use


def plan_rows(study, cases):
    """Rows of ``plan`` cases: each planned on its own (runs on a worker)."""
    rows = []
    for index, case in cases:
        start = time.perf_counter()
        try:
            result = plan(study.problem(case))
        except InvalidScene as err:
            rows.append(_row(study, index, case, "invalid", _one_line(err)))
        except PlanInfeasible as err:
            rows.append(_row(study, index, case, "infeasible", _one_line(err)))
        except LiftPlanError as err:
            rows.append(_row(study, index, case, "failed", _one_line(err)))
        except Exception as err:  # noqa: BLE001 - one bad case never aborts the sweep
            rows.append(_row(study, index, case, "error", _one_line(err)))
        else:
            chosen = result.chosen
            low, high = chosen.tension_range
            rows.append(
                _row(
                    study,
                    index,
                    case,
                    "ok",
                    "",
                    [
                        " ".join(chosen.lugs),
                        " ".join(f"{h:.4f}" for h in chosen.boom_heights),
                        result.spread,
                        result.worst_spread,
                        chosen.worst.heel,
                        chosen.worst.trim,
                        low,
                        high,
                        chosen.max_utilisation,
                        chosen.bound,
                        result.stats.evaluated,
                        time.perf_counter() - start,
                    ],
                )
            )
    return rows


def _row(study, index, case, status, reason, results=None):
    results = results if results is not None else [""] * len(results_columns(study))
    results = ["" if isinstance(v, float) and np.isnan(v) else v for v in results]
    return [index, *study.row_values(case), status, reason, *results]


def _failed_rows(study, cases, status, reason):
    return [_row(study, index, case, status, reason) for index, case in cases]


def _one_line(err):
    text = _one_line_text(str(err)) or type(err).__name__
    return text if isinstance(err, LiftPlanError) else f"{type(err).__name__}: {text}"


def _one_line_text(text):
    return text.strip().replace("\n", " ")


class Journal:
    """The rows of a run so far, appended as they come (``OUTPUT.partial``).

    Its first line holds the study's fingerprint: a journal is resumed only by the study
    that wrote it.
    """

    def __init__(self, path, study, restart):
        self.path = path
        self.header = header(study)
        self.mark = f"{JOURNAL_MARK} {study.fingerprint}"
        self.done = set()
        if restart or not path.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
            with path.open("w", newline="", encoding="utf-8") as f:
                f.write(self.mark + "\n")
                csv.writer(f).writerow(self.header)
            return
        self._resume()

    def _resume(self):
        text = self.path.read_text(encoding="utf-8")
        first = text.split("\n", 1)[0]
        if first != self.mark:
            raise LiftPlanError(
                f"{self.path}: an interrupted run of a different study (or a changed study "
                "file); expected the same study, or rerun with --restart"
            )
        # a row cut off mid-write by the interruption has no newline: drop it
        complete = text[: text.rfind("\n") + 1]
        if len(complete) != len(text):
            self.path.write_text(complete, encoding="utf-8")
        rows = list(csv.reader(complete.splitlines()[1:]))
        if not rows or rows[0] != self.header:
            raise LiftPlanError(
                f"{self.path}: the journal's columns differ from the study's; "
                "expected the same study, or rerun with --restart"
            )
        self.done = {int(row[0]) for row in rows[1:] if len(row) == len(self.header)}

    def write(self, rows):
        with self.path.open("a", newline="", encoding="utf-8") as f:
            csv.writer(f).writerows(rows)
            f.flush()

    def finish(self, output):
        """Write the sorted table (atomically) and remove the journal; counts per status."""
        with self.path.open(newline="", encoding="utf-8") as f:
            f.readline()
            reader = csv.reader(f)
            next(reader)
            rows = {int(row[0]): row for row in reader if len(row) == len(self.header)}
        status = self.header.index("status")
        counts = {}
        for row in rows.values():
            counts[row[status]] = counts.get(row[status], 0) + 1
        temporary = output.with_name(output.name + ".tmp")
        with temporary.open("w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(self.header)
            writer.writerows(rows[k] for k in sorted(rows))
        os.replace(temporary, output)
        self.path.unlink()
        return counts

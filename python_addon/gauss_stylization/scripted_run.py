"""A Stylize run that goes through at once: scripts, background mode, the redo panel.

The solvers of all objects are set up first (on a worker thread, progress
shown meanwhile), then each object runs its steps. Steps go in chunks of about
CHUNK_SECONDS, and at most a tenth of the run, so progress can be shown between
them; chunking does not change the result (n steps are n steps). An object that
cannot be set up or fails while stepping is restored and skipped with a message
naming it; the others are kept. The operator's one undo step covers them all.
"""

import time

from .errors import SettingsError
from .progress import ProgressReport
from .session import Session
from .solver_setup import SolverSetup
from .targets import TITLE, report_skipped

CHUNK_SECONDS = 0.1


def _set_up(planned, report):
    """Sessions for the plans whose solvers could be built, and [(name, why)] of the others."""
    results = SolverSetup(planned.plans).wait(report)
    sessions, failed = [], []
    for plan, result in zip(planned.plans, results):
        try:
            if isinstance(result, Exception) or result is None:
                raise result or SettingsError("the set-up did not finish")
            sessions.append(Session(plan, result))
        except SettingsError as exc:
            failed.append((plan.name, str(exc)))
            planned.give_up(plan)
    return sessions, failed


def _advance(session, count, report, done, total):
    """Run ``count`` steps of ``session`` in chunks, reporting progress of ``total`` steps."""
    chunk, left = 1, count
    most = max(1, total // 10)  # a chunk never skips a tenth of the whole run
    while left > 0:
        steps = min(chunk, left)
        start = time.perf_counter()
        session.step(steps)
        left -= steps
        seconds = max((time.perf_counter() - start) / steps, 1e-6)
        chunk = max(1, min(most, int(CHUNK_SECONDS / seconds)))
        report.update((done + count - left) / total,
                      "Stylizing '%s': step %d of %d" % (session.name, count - left, count))


def run(operator, context, planned, steps):
    """Run every planned object ``steps`` steps (None: each object's Script Steps), keep what
    succeeded and report the rest. Returns the operator's result."""
    with ProgressReport(context, TITLE) as report:
        sessions, failed = _set_up(planned, report)
        counts = [steps if steps is not None else session.obj.gauss_stylization.iterations
                  for session in sessions]
        total, done, kept = max(sum(counts), 1), 0, []
        for session, count in zip(sessions, counts):
            try:
                _advance(session, count, report, done, total)
            except SettingsError as exc:
                session.cancel()
                failed.append((session.name, str(exc)))
                continue
            except (ValueError, RuntimeError) as exc:
                session.cancel()
                failed.append((session.name, "The solver failed: %s" % exc))
                continue
            done += count
            kept.append(session)
    for session in kept:
        session.keep()
    report_skipped(operator, failed, any_left=bool(kept))
    return {'FINISHED'} if kept else {'CANCELLED'}

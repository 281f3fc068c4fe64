"""Solver set-ups on a worker thread, watched from Blender's main thread.

A solver's set-up (ordering, factorization) takes seconds on a mesh of a few
hundred thousand vertices, and so does the re-factorization when the pins
change. gauss_core releases the GIL while it sets up, so a Python thread can
run it while the live run's timer keeps Blender responsive and polls the
progress; a scripted run waits for it the same way, reporting progress
meanwhile (wait()). The thread touches no Blender data.

    setup = SolverSetup(plans)   # starts at once; PinsSetup(session, pins) likewise
    setup.done, setup.fraction, setup.text()   # poll from the main thread
    setup.cancel()               # stops the set-up in progress, nothing is built further
    setup.results                # per task: its result, or the SettingsError that refused it
"""

import threading

from ..errors import SettingsError

POLL_SECONDS = 0.05  # how often wait() looks at the progress


class BackgroundSetup:
    def __init__(self, gauss_core, tasks):
        """tasks: [(weight, text, run)], run one after the other: run(progress) returns the task's
        result (progress: the gauss_core.Progress to report to); weight is
        the task's share of the whole (its vertex count), text what it does ("Preparing ...")."""
        self.tasks = list(tasks)
        self.results = [None] * len(self.tasks)
        self.current = 0  # index of the task running
        self._gauss_core = gauss_core
        self._progress = None  # gauss_core.Progress of the current task
        self._cancelled = False
        self._total = float(sum(weight for weight, _text, _run in self.tasks)) or 1.0
        self._thread = threading.Thread(target=self._work, name="Gauss Stylize set-up", daemon=True)
        self._thread.start()

    def _work(self):
        for index, (_weight, _text, run) in enumerate(self.tasks):
            # The new Progress is in place before the flag is read, so cancel() stops either this
            # task (through the Progress) or every later one (through the flag).
            self._progress = self._gauss_core.Progress()
            self.current = index
            if self._cancelled:
                return
            try:
                self.results[index] = run(self._progress)
            except self._gauss_core.Cancelled:
                return
            except SettingsError as exc:
                self.results[index] = exc
            except Exception as exc:  # anything else must reach the main thread too, never vanish
                self.results[index] = SettingsError("Setting up the solver failed: %s" % exc)
        self.current = len(self.tasks)

    @property
    def done(self):
        return not self._thread.is_alive()

    @property
    def cancelled(self):
        return self._cancelled

    @property
    def fraction(self):
        """0..1 of the whole, each task counted by its weight."""
        index = self.current
        if index >= len(self.tasks):
            return 1.0
        progress = self._progress
        within = progress.fraction if progress is not None else 0.0  # None: the thread has not begun
        finished = sum(weight for weight, _text, _run in self.tasks[:index])
        return (finished + within * self.tasks[index][0]) / self._total

    def text(self):
        """What runs now, e.g. "Preparing 501,128 vertices" (no fraction)."""
        return self.tasks[min(self.current, len(self.tasks) - 1)][1]

    def cancel(self):
        """Stop: the task in progress ends at its next check, later ones never start. Waits for the thread."""
        self._cancelled = True
        progress = self._progress
        if progress is not None:
            progress.cancel()
        self._thread.join()

    def wait(self, report=None):
        """Block until every task is done, updating ``report`` (a progress.ProgressReport)."""
        while not self.done:
            self._thread.join(POLL_SECONDS)
            if report is not None:
                report.update(self.fraction, self.text())
        if report is not None:  # the end of the stage, also when it ended before the first look
            report.update(self.fraction, self.text())
        return self.results


def _vertices(count):
    return "{:,} vertices".format(count)


class SolverSetup(BackgroundSetup):
    """The solvers of session.Plan objects (Plan.build_solver), one after the other."""

    def __init__(self, plans):
        plans = list(plans)
        texts = ["Preparing " + _vertices(plan.num_vertices) if len(plans) == 1 else
                 "Preparing '%s' (%d of %d): %s" % (plan.name, number, len(plans), _vertices(plan.num_vertices))
                 for number, plan in enumerate(plans, 1)]
        super().__init__(plans[0].gauss_core if plans else None,
                         [(plan.num_vertices, text, plan.build_solver) for plan, text in zip(plans, texts)])


class PinsSetup(BackgroundSetup):
    """A running session's solver re-factored for new pins (Solver.set_pins); the session must
    not step until it is done. A cancelled or refused re-factorization leaves the old pins."""

    def __init__(self, session, pins):
        solver = session.solver

        def refactor(progress):
            solver.set_pins(pins, progress=progress)

        super().__init__(session.gauss_core, [(session.arrays.num_vertices, "Preparing the new pins of %s"
                                               % _vertices(session.arrays.num_vertices), refactor)])

"""Setting up the solvers of a run on a worker thread, watched from Blender's main thread.

A solver's set-up (ordering, factorization) takes seconds on a mesh of a few
hundred thousand vertices. gauss_core releases the GIL while it sets up, so a
Python thread can run it while the live run's timer keeps Blender responsive
and polls the progress; a scripted run waits for it the same way, reporting
progress meanwhile (wait()). The thread only calls Plan.build_solver(), which
touches no Blender data.

    setup = SolverSetup(plans)   # starts at once
    setup.done, setup.fraction, setup.text()   # poll from the main thread
    setup.cancel()               # stops the set-up in progress, nothing is built further
    setup.results                # per plan: a solver, or the SettingsError that refused it
"""

import threading

from .errors import SettingsError

POLL_SECONDS = 0.05  # how often wait() looks at the progress


class SolverSetup:
    def __init__(self, plans):
        """plans: session.Plan objects, set up one after the other in this order."""
        self.plans = list(plans)
        self.results = [None] * len(self.plans)
        self.current = 0  # index of the plan being set up
        self._gauss_core = self.plans[0].gauss_core if self.plans else None
        self._progress = None  # gauss_core.Progress of the current set-up (when the module has one)
        self._cancelled = False
        self._total = float(sum(plan.num_vertices for plan in self.plans)) or 1.0
        self._thread = threading.Thread(target=self._work, name="Gauss Stylize set-up", daemon=True)
        self._thread.start()

    def _new_progress(self):
        progress_type = getattr(self._gauss_core, "Progress", None)
        return progress_type() if progress_type is not None else None

    def _work(self):
        cancelled = getattr(self._gauss_core, "Cancelled", ())
        for index, plan in enumerate(self.plans):
            self._progress = self._new_progress()
            self.current = index
            if self._cancelled:
                return
            try:
                self.results[index] = plan.build_solver(self._progress)
            except cancelled:
                return
            except SettingsError as exc:
                self.results[index] = exc
            except Exception as exc:  # anything else must reach the main thread too, never vanish
                self.results[index] = SettingsError("Setting up the solver failed: %s" % exc)
        self.current = len(self.plans)

    @property
    def done(self):
        return not self._thread.is_alive()

    @property
    def cancelled(self):
        return self._cancelled

    @property
    def fraction(self):
        """0..1 of the whole set-up, counting each mesh by its vertices; None if unknown."""
        index = self.current
        if index >= len(self.plans):
            return 1.0
        progress = self._progress
        if progress is None and len(self.plans) == 1:
            return None
        within = progress.fraction if progress is not None else 0.0
        finished = sum(plan.num_vertices for plan in self.plans[:index])
        return (finished + within * self.plans[index].num_vertices) / self._total

    def text(self):
        """What is being set up, e.g. "Preparing 501,128 vertices" (no fraction)."""
        index = min(self.current, len(self.plans) - 1)
        plan = self.plans[index]
        vertices = "{:,} vertices".format(plan.num_vertices)
        if len(self.plans) == 1:
            return "Preparing " + vertices
        return "Preparing '%s' (%d of %d): %s" % (plan.name, index + 1, len(self.plans), vertices)

    def cancel(self):
        """Stop: the set-up in progress ends at its next check, later ones never start. Waits for the thread."""
        self._cancelled = True
        progress = self._progress
        if progress is not None:
            progress.cancel()
        self._thread.join()

    def wait(self, report=None):
        """Block until every set-up is done, updating ``report`` (a progress.ProgressReport)."""
        while not self.done:
            self._thread.join(POLL_SECONDS)
            if report is not None:
                report.update(self.fraction, self.text())
        if report is not None:  # the end of the stage, also when it ended before the first look
            report.update(self.fraction, self.text())
        return self.results

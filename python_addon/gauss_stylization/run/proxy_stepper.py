"""A proxy run's solver steps on a worker thread, one step at a time, while Blender's main thread
writes the previous one into the mesh (issue 31: a live tick of a sculpt under 50 ms).

The main thread alone decides when a step starts (``start()``) and touches the solver only while the
worker is ``idle``: every change of settings, pins or weights then lands between two steps, in the
order the artist made it, as in a run stepped on the main thread. What a step does on the worker is
session.Session's (``work``: the step, its read-out and its transfer to the whole mesh, into the
worker's own buffers, never into Blender's mesh); the session takes the buffers once the step is
done. gauss_core's step and transfer release the GIL, so the main thread runs meanwhile.

One persistent thread per run on a proxy (woken by an Event), not one per step: a tick allocates
nothing.
"""

import threading
import time


class ProxyStepper:
    """Runs ``work()`` (one step and what goes with it) once per ``start()`` on a worker thread; what it
    writes is read only while ``idle``."""

    def __init__(self, work):
        self._work = work
        self._go = threading.Event()
        self._idle = threading.Event()
        self._idle.set()
        self._stopping = False
        self.pending = False  # a step was started and not yet taken (session.Session.take_step)
        self.error = None     # what the last step raised (taken with it)
        self.ms = 0.0         # the last step's wall time on the worker
        self._thread = threading.Thread(target=self._loop, name="Gauss proxy steps", daemon=True)
        self._thread.start()

    @property
    def idle(self):
        """No step running: the solver may be read and changed. Stays so until the next start()."""
        return self._idle.is_set()

    @property
    def done(self):
        """A step started has finished and waits to be taken."""
        return self.pending and self._idle.is_set()

    def start(self):
        """Start one step (only while idle and nothing is pending)."""
        assert self.idle and not self.pending and not self._stopping
        self.pending = True
        self._idle.clear()
        self._go.set()

    def stop(self):
        """End the worker after the step running, if any, and wait for it: the solver is the caller's
        again (a step is at most a fraction of a second, so Esc and Enter wait at most that)."""
        self._stopping = True
        self._go.set()
        self._thread.join()

    def _loop(self):
        while True:
            self._go.wait()
            self._go.clear()
            if self._stopping:
                self._idle.set()
                return
            start = time.perf_counter()
            try:
                self._work()
                self.error = None
            except BaseException as exc:  # noqa: BLE001 (the main thread raises it where it takes the step)
                self.error = exc
            self.ms = (time.perf_counter() - start) * 1000.0
            self._idle.set()

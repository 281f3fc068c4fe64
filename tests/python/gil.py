"""Does a gauss_core call release the GIL? (Blender's UI thread must not freeze while it runs.)"""
import threading
import time


def run_beside_python(call):
    """Runs ``call()`` on another thread while this one keeps executing Python.

    Returns (result, seconds the call took, longest pause of this thread). With the GIL held by the
    call, the pause would be about as long as the call itself.
    """
    outcome = {}

    def run():
        start = time.perf_counter()
        outcome["result"] = call()
        outcome["seconds"] = time.perf_counter() - start

    t = threading.Thread(target=run)
    last = time.perf_counter()
    longest_pause = 0.0
    t.start()
    while t.is_alive():
        now = time.perf_counter()
        longest_pause = max(longest_pause, now - last)
        last = now
    t.join()
    return outcome["result"], outcome["seconds"], longest_pause

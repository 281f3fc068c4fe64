"""Runs: one object's stylization (session.py), the objects a Stylize acts on (targets.py), set-ups
on a worker thread (solver_setup.py), the live run (live_run.py, modal_events.py; on a proxy, proxy_run.py, its steps on a worker thread
proxy_stepper.py) and the scripted one
(scripted_run.py), Replay (replay.py) and Follow Edits of a New Object copy (rerun.py, follow.py), pin targets as text (pin_targets.py), progress (progress.py), what a live run
is (run_interface.py), the registry of running runs (runs.py) and the undo guard (undo_guard.py). Imports view/, mesh/, settings/ and the
top-level errors.py, native.py; nothing here is an operator or a panel.
"""

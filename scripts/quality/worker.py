"""The quality matrix's worker: runs options on one mesh in its own process, one JSON line per record.

    python3 scripts/quality/worker.py MESH OPTION_NAME...

A crash (a signal, an uncaught exception) then ends this process only; runner.py records it and goes
on. Before each run it prints {"start": name}, so the runner knows which run a crash belongs to.
"""
import json
import sys

import paths  # noqa: F401  (before the imports it makes possible)
import measure_run  # noqa: E402
import options  # noqa: E402
from mesh_files import read_mesh  # noqa: E402


def _emit(record):
    print(json.dumps(record), flush=True)


def main(mesh, names):
    try:
        V, F = read_mesh(mesh)
        pairs_in = measure_run.crossing_pairs(V, F)
        about = {"vertices": len(V), "faces": len(F), "kind": measure_run.mesh_kind(V, F)}
    except (OSError, ValueError, TypeError) as error:
        for name in names:
            _emit({"option": name, "error": f"the input: {type(error).__name__}: {error}"})
        return
    for name in names:
        _emit(dict(about, start=name))
        _emit(dict(measure_run.run_option(options.by_name(name), V, F, pairs_in), **about))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])

"""The quality matrix's thresholds: made from a run with a margin, kept in tests/quality_thresholds.json
(hand-editable), and checked against a run.

Per mesh and option, a threshold holds any of:
  "min_share":       the share may not fall below it;
  "max_new_pairs":   at most this many crossing pairs the input did not have;
  "finite_bounded":  true: every coordinate finite and the result within measure_run.BOUND diagonals;
  "must_converge":   true: reldV fell below the tolerance within the step cap, with no vertex held back
                     in the last step (a run the guard stopped is not converged);
  "error":           true: the run was refused with a clean error when the thresholds were made, and
                     still may be (a result is fine too; a crash never is).
A run in which a step ran away (Solver.runaway_steps, docs/robustness.md) fails whatever its threshold.
"""
import json
import math

SHARE_MARGIN = 0.02
PAIRS_MARGIN = 1.25  # times the new pairs measured, plus 2; none measured allows none


def converged_clean(record):
    """Stopped below the tolerance and the solver says converged (not held back by the guard)."""
    return bool(record.get("stopped") and record.get("converged")) and not record.get("held_back")


def make(record):
    """The threshold a record passes with a margin."""
    if "crash" in record:
        raise ValueError(f"{record['mesh']} / {record['option']} crashed; fix it before making thresholds")
    if "error" in record:
        return {"error": True}
    threshold = {"finite_bounded": bool(record["bounded"]), "must_converge": converged_clean(record)}
    if record["share"] is not None:
        threshold["min_share"] = round(max(0.0, record["share"] - SHARE_MARGIN), 3)
    if "new_pairs" in record:
        new = record["new_pairs"]
        threshold["max_new_pairs"] = 0 if new == 0 else math.ceil(PAIRS_MARGIN * new) + 2
    return threshold


def violations(record, threshold):
    """What a record breaks of its threshold: a list of messages."""
    where = f"{record['mesh']} / {record['option']}"
    if "crash" in record:
        return [f"{where}: crashed ({record['crash']})"]
    if "error" in record:
        return [] if threshold.get("error") else [f"{where}: error '{record['error']}', expected a result"]
    broken = []
    if record.get("runaway"):  # bounded only thanks to the fallback: never a pass, whatever the threshold
        broken.append(f"{where}: {record['runaway']} steps ran away (redone as plain ARAP)")
    if threshold.get("finite_bounded") and not record["bounded"]:
        broken.append(f"{where}: finite_bounded: result {'not bounded' if record['finite'] else 'not finite'}")
    if threshold.get("must_converge") and not converged_clean(record):
        why = "stopped by the guard" if record.get("stopped") else f"not within {record['steps']} steps"
        broken.append(f"{where}: must_converge: {why}")
    if "min_share" in threshold and (record["share"] is None or record["share"] < threshold["min_share"]):
        share = "n/a" if record["share"] is None else f"{record['share']:.3f}"
        broken.append(f"{where}: min_share: share {share} < {threshold['min_share']}")
    if "max_new_pairs" in threshold and record.get("new_pairs", math.inf) > threshold["max_new_pairs"]:
        broken.append(f"{where}: max_new_pairs: {record.get('new_pairs')} new crossing pairs > "
                      f"{threshold['max_new_pairs']}")
    return broken


def check(records, table):
    """Every violation of `table` ({mesh: {option: threshold}}) by `records`; the runs that have no
    threshold are named in one message."""
    found, missing = [], []
    for r in records:
        threshold = table.get(r["mesh"], {}).get(r["option"])
        if threshold is None and "crash" not in r:
            missing.append(f"{r['mesh']} / {r['option']}")
        else:
            found += violations(r, threshold or {})
    if missing:
        found.append(f"{len(missing)} runs have no threshold ({', '.join(missing[:3])}{', ...' * (len(missing) > 3)});"
                     " make them with scripts/quality_matrix.py --write-thresholds")
    return found


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        return {}


def write(path, records):
    """Makes the thresholds of `records` and merges them into the file (other cells are kept)."""
    table = load(path)
    for r in records:
        table.setdefault(r["mesh"], {})[r["option"]] = make(r)
    with open(path, "w") as f:
        json.dump({m: dict(sorted(table[m].items())) for m in sorted(table)}, f, indent=1)
        f.write("\n")

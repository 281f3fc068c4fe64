"""The quality matrix's table (printed and in docs/quality.md) and the findings it lists: what fails
the quality criteria (docs/quality.md) on today's code, apart from the thresholds (which only say what got worse)."""
import options

GUARD_SHARE_DROP = 0.05  # a guarded run's share within 0.05 of the plain run's
# a 0-to-1 gradient gives 0.3 more share at the heavy end than the light one (judged where
# the style unpainted gains more than that)
GRADIENT_GAIN = 0.3
# a uniform weight w gives a share within 0.1 of share(0) + w (share(1) - share(0)); weight 0
# leaves the mesh as it is (no face styled), so share(0) is the input's
LINEAR_RESPONSE = 0.1

COLUMNS = ("mesh", "kind", "V", "option", "steps", "conv", "share in>out", "vs plain", "pairs in>out (new)",
           "held max", "finite, bounded", "ms/step (cpu)")


def _plain_share(record, by_cell):
    plain = options.by_name(record["option"]).plain
    other = by_cell.get((record["mesh"], plain))
    if plain and other and other.get("share") is not None and record.get("share") is not None:
        return record["share"] - other["share"]
    return None


def _yes(flag):
    return "yes" if flag else "NO"


def _conv(r):
    if not r.get("stopped"):
        return "no"
    return "held" if r.get("held_back") else "yes" if r.get("converged") else "stopped"


def row(record, by_cell):
    """The table's cells of one record."""
    head = [record["mesh"], record.get("kind", "?"), str(record.get("vertices", "?")), record["option"]]
    if "crash" in record or "error" in record:
        what = f"CRASH {record['crash']}" if "crash" in record else f"error: {record['error']}"
        return head + [what] + [""] * (len(COLUMNS) - len(head) - 1)
    drop = _plain_share(record, by_cell)
    share = "n/a" if record["share"] is None else f"{record['share_in']:.3f}>{record['share']:.3f}"
    if "share_heavy" in record:
        share += f" (light {record['share_light']:.2f}, heavy {record['share_heavy']:.2f})"
    pairs = f"{record['pairs_in']}>{record['pairs_out']} ({record['new_pairs']})" if "pairs_out" in record else "n/a"
    return head + [str(record["steps"]), _conv(record), share, "" if drop is None else f"{drop:+.3f}", pairs,
                   str(record["held_max"]), f"{_yes(record['finite'])}, {_yes(record['bounded'])}",
                   f"{record['ms_per_step']:.1f} ({record['cpu_ms_per_step']:.1f})"]


def _cells(records):
    return {(r["mesh"], r["option"]): r for r in records}


def text_table(records):
    by_cell = _cells(records)
    rows = [COLUMNS] + [row(r, by_cell) for r in records]
    widths = [max(len(r[i]) for r in rows if i < len(r)) for i in range(len(COLUMNS))]
    widths[4] = len(COLUMNS[4])  # an error's text runs on past its column
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows)


def markdown_table(records):
    by_cell = _cells(records)
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for r in records:
        cells = [c.replace("|", "/") for c in row(r, by_cell)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _plain_new_pairs(r, by_cell):
    """The crossing pairs the same run without the guard made (None where it has no such record)."""
    plain = by_cell.get((r["mesh"], options.by_name(r["option"]).plain), {})
    return plain.get("new_pairs")


def _held_at_a_contact(r, by_cell):
    """A guarded run that stopped held back where the plain run passes through the surface: the guard
    doing its job (the issue's status rule: reported as held, never as converged), not a failure."""
    return bool(r.get("stopped") and r.get("held_back") and _plain_new_pairs(r, by_cell))


def _guard_findings(r, by_cell):
    found = []
    if r["stopped"] and r.get("held_back") and not _held_at_a_contact(r, by_cell):
        where = ("where the plain run crosses nowhere" if _plain_new_pairs(r, by_cell) is not None
                 else "(no plain run to compare with)")
        found.append(f"the guard stopped the run {where} ({r['held_last']} vertices held back in its last step)")
    if r["converged"] and r.get("unguarded_still") is False:
        found.append(f"it reports converged with {r['held_last']} vertices held back in its last step, but a step "
                     f"without the guard then moves reldV {r['unguarded_reldv']:.2g}")
    if r["held_max"] >= r["vertices"]:
        found.append(f"the guard held every vertex ({r['held_max']}) back at some step")
    if r.get("new_pairs"):
        sliding = r.get("new_pairs_sliding", 0)
        found.append(f"{r['new_pairs']} new crossing pairs" + (
            f" ({'all' if sliding == r['new_pairs'] else sliding} in the crossing region that slid on from the "
            f"input's {r['pairs_in']}, which the guard allows)" if sliding else ""))
    drop = _plain_share(r, by_cell)
    if r.get("kind") == "closed" and drop is not None and drop < -GUARD_SHARE_DROP:
        found.append(f"share {r['share']:.3f}, {-drop:.3f} below the plain run's (the criterion: within {GUARD_SHARE_DROP})")
    return found


def _paint_findings(r, by_cell):
    found = []
    plain = by_cell.get((r["mesh"], options.by_name(r["option"]).plain), {})
    if plain.get("share") is None or r["share"] is None:
        return found
    if "uniform_weight" in r:
        linear = r["share_in"] + r["uniform_weight"] * (plain["share"] - r["share_in"])
        if abs(r["share"] - linear) > LINEAR_RESPONSE:
            found.append(f"share {r['share']:.3f}, a linear response gives {linear:.3f} (the criterion: within "
                         f"{LINEAR_RESPONSE})")
    reachable = plain["share"] - plain["share_in"] > GRADIENT_GAIN
    if "share_heavy" in r and reachable and r["share_heavy"] - r["share_light"] < GRADIENT_GAIN:
        found.append(f"heavy end {r['share_heavy']:.3f} vs light end {r['share_light']:.3f} (the criterion: at least "
                     f"{GRADIENT_GAIN} more)")
    return found


def findings(records):
    """What fails the quality criteria (or any run's basics): {heading: [sentence naming mesh and option]}."""
    by_cell = _cells(records)
    found = {"Crashes, refusals, results not finite or not bounded": [], "Avoid Self-Intersections": [],
             "Painted strength": [], "Not converged within the step cap": []}
    for r in records:
        where = f"{r['mesh']} / {r['option']}"
        basics = found["Crashes, refusals, results not finite or not bounded"]
        if "crash" in r:
            basics.append(f"{where}: crashed ({r['crash']})")
            continue
        if "error" in r:
            if r.get("kind") != "broken":
                basics.append(f"{where}: refused ({r['error']})")
            continue
        if not r["bounded"]:
            basics.append(f"{where}: result {'not bounded' if r['finite'] else 'not finite'}")
        if r.get("runaway"):
            basics.append(f"{where}: {r['runaway']} steps ran away (redone as plain ARAP, docs/robustness.md)")
        if not r["stopped"]:
            found["Not converged within the step cap"].append(f"{where}: {r['steps']} steps")
        tags = options.by_name(r["option"]).tags
        if "guard" in tags:
            found["Avoid Self-Intersections"] += [f"{where}: {f}" for f in _guard_findings(r, by_cell)]
        if "paint" in tags:
            found["Painted strength"] += [f"{where}: {f}" for f in _paint_findings(r, by_cell)]
    return found


def held_at_contacts(records):
    """Guarded runs that ended held back where the plain run makes crossings: sentences naming mesh and
    option, the plain run's new pairs and the share against it (listed apart from the failures)."""
    by_cell = _cells(records)
    found = []
    for r in records:
        if "guard" in options.by_name(r["option"]).tags and "crash" not in r and "error" not in r \
                and _held_at_a_contact(r, by_cell):
            drop = _plain_share(r, by_cell)
            found.append(f"{r['mesh']} / {r['option']}: held ({r['held_last']} vertices in its last step) where the "
                         f"plain run makes {_plain_new_pairs(r, by_cell)} crossing pairs; share "
                         f"{'n/a' if drop is None else f'{drop:+.3f}'} against it")
    return found


def converged_note():
    return ("conv: yes (reldV below the tolerance and the solver says converged), no (the step cap came "
            "first), held (the solver says held_back: reldV below the tolerance only because the guard "
            "holds vertices back), stopped (reldV below the tolerance, the solver says neither)")


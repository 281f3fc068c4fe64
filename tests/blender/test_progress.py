"""Progress of set-ups and scripted runs: nothing for short jobs,
and in background mode a line at least every 10% of a longer one."""

import re

import helpers


def _percentages(out, what):
    return [int(m.group(1)) for m in re.finditer(r"Gauss Stylize: %s.*?(\d+)%%" % what, out)]


def test_a_run_over_half_a_second_prints_progress_every_tenth(addon, monkeypatch, capfd):
    monkeypatch.setattr(addon.run.progress, "SHOW_AFTER", 0.0)  # every run counts as long
    helpers.suzanne(levels=1)
    capfd.readouterr()
    assert helpers.stylize(40) == {'FINISHED'}
    out = capfd.readouterr().out
    assert "Gauss Stylize: Preparing 2,012 vertices" in out, out
    steps = _percentages(out, "Stylizing 'Suzanne': step")
    assert steps and steps[-1] == 100, out
    assert all(later - earlier <= 10 for earlier, later in zip([0] + steps, steps)), steps
    assert "Gauss Stylize: done in" in out


def test_a_short_run_prints_nothing(capfd):
    helpers.suzanne(levels=0)
    capfd.readouterr()
    assert helpers.stylize(2) == {'FINISHED'}
    assert "Gauss Stylize" not in capfd.readouterr().out


def test_progress_text():
    from gauss_stylization.run.progress import progress_text
    assert progress_text("Preparing 501,128 vertices", 0.4) == "Preparing 501,128 vertices... 40%"
    assert progress_text("Preparing 501,128 vertices") == "Preparing 501,128 vertices..."


def test_the_set_up_of_several_objects_names_each(addon):
    a = helpers.suzanne(levels=0)
    a.name = "A"
    b = helpers.uv_sphere()
    b.name = "B"
    helpers.add_slot(a, 'CUBE')
    helpers.add_slot(b, 'CUBE')
    plans = [addon.run.session.Plan(a), addon.run.session.Plan(b)]
    setup = addon.run.solver_setup.SolverSetup(plans)
    assert setup.text() in ("Preparing 'A' (1 of 2): 507 vertices", "Preparing 'B' (2 of 2): 482 vertices")
    results = setup.wait()
    assert all(result is not None and not isinstance(result, Exception) for result in results)
    assert setup.fraction == 1.0 and setup.text() == "Preparing 'B' (2 of 2): 482 vertices"

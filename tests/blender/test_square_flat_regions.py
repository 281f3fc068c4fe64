"""Square Flat Regions in the add-on: the Solver panel's checkbox (off by default, the solver's default)
reaches the solver, and Stylize with it squares the round cap of a capped 32-sided cylinder
(docs/styles.md#square-flat-regions)."""

import helpers
from measures import squareness

FIELD = "square_flat_regions"


def test_the_checkbox_is_off_by_default_and_reaches_the_solver(addon):
    assert addon.native.facts().defaults[FIELD] is False
    obj = helpers.capped_cylinder()
    helpers.add_slot(obj, 'CUBE')
    assert getattr(obj.gauss_stylization, FIELD) is False
    assert FIELD in [f.name for f in addon.settings.schema.OBJECT
                     if f.panel is addon.settings.fields.Panel.SOLVER]
    for value in (True, False):
        setattr(obj.gauss_stylization, FIELD, value)
        run = addon.run.session.Session(obj)
        try:
            assert getattr(run.solver, FIELD) is value
        finally:
            run.cancel()


def test_stylize_squares_the_cap(addon):
    obj = helpers.capped_cylinder()
    helpers.add_slot(obj, 'CUBE')
    rest = helpers.coords(obj)
    tris = helpers.triangles(obj)[0]
    results = {}
    for value in (False, True):
        helpers.mesh_io.write_vertex_coords(obj.data, rest)
        assert helpers.stylize(0, method='CUBIC', cubic_lambda=0.2, **{FIELD: value}) == {'FINISHED'}
        results[value] = squareness(helpers.coords(obj), tris)
    assert results[False] < 0.9 <= results[True], results

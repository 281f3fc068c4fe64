"""The Gauss sphere overlay's content, headless (tests/blender/windowed_interactive.py
draws and clicks it in a real window): geometry, pixels <-> directions, colours,
the face-normal sample and the style's look."""

import numpy as np
import pytest

import helpers


def test_the_icosphere_is_unit_and_faces_outwards(addon):
    vertices, triangles = addon.sphere.gauss_sphere.icosphere()
    assert vertices.shape == (2562, 3) and triangles.shape == (5120, 3)
    assert np.allclose(np.linalg.norm(vertices, axis=1), 1.0)
    corners = vertices[triangles]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert (np.einsum("ij,ij->i", normals, corners.mean(axis=1)) > 0).all()


def test_pixels_and_directions_correspond(addon):
    sphere = addon.sphere.gauss_sphere
    where = sphere.frame(800, 600, left_inset=40, ui_scale=1.0)
    assert where.x - where.radius >= 40 and where.y - where.radius > 0  # clear of the toolbar and the edge
    rng = np.random.default_rng(3)
    directions = rng.normal(size=(50, 3))
    directions[:, 2] = np.abs(directions[:, 2])
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    for direction, (x, y) in zip(directions, sphere.to_pixels(directions, where)):
        back, on_sphere = sphere.from_pixel(x, y, where)
        assert on_sphere and np.allclose(back, direction, atol=1e-9)
    rim, on_sphere = sphere.from_pixel(where.x + 3 * where.radius, where.y, where)
    assert not on_sphere and np.allclose(rim, (1, 0, 0))
    small = sphere.frame(200, 150)
    assert small.radius <= sphere.MAX_RADIUS_SHARE * 150  # never more than a corner of a small view


def test_heat_colours_brighten_with_g_and_clip(addon):
    colours = addon.sphere.gauss_sphere.heat_colours([-1.0, 0.0, 0.5, 0.9, 1.0, 2.0])
    brightness = colours[:, :3].sum(axis=1)
    assert (np.diff(brightness[1:5]) > 0).all()
    assert np.array_equal(colours[0], colours[1]) and np.array_equal(colours[4], colours[5])
    assert (colours[:, 3] == 1.0).all()


def test_the_facing_half_is_drawn_alone(addon):
    vertices, triangles = addon.sphere.gauss_sphere.icosphere(2)
    front = addon.sphere.gauss_sphere.facing(vertices, triangles)
    assert 0.45 < len(front) / len(triangles) < 0.55
    assert (vertices[front].mean(axis=1)[:, 2] > 0).all()


def test_face_normal_sample_is_bounded_area_weighted_and_follows_a_run(addon):
    overlay = addon.sphere.sphere_overlay
    obj = helpers.suzanne(levels=2)  # 15,744 triangles
    helpers.add_slot(obj, 'CUBE')
    sample = overlay.face_normal_sample(obj)
    assert len(sample) == overlay.MAX_POINTS and np.allclose(np.linalg.norm(sample, axis=1), 1.0)
    # Area-weighted: a slab's two big faces get nearly all samples.
    slab = helpers.uv_sphere(8, 4)
    slab.data.transform(np.diag([4.0, 4.0, 0.02, 1.0]).tolist())
    up = np.abs(overlay.face_normal_sample(slab)[:, 2]) > 0.9
    assert up.mean() > 0.9
    helpers.activate(obj)
    run = addon.run.session.Session(obj)
    try:
        addon.run.runs.start([obj], _Run(run))
        before = overlay.face_normal_sample(obj)
        run.step(20)
        after = overlay.face_normal_sample(obj)
        # The same triangles, now turned towards the cube's axes.
        share = lambda normals: (np.abs(normals).max(axis=1) > np.cos(np.radians(10))).mean()
        assert len(after) == len(before) and share(after) > share(before) + 0.2
    finally:
        addon.run.runs.forget(addon.run.runs.running[obj.as_pointer()])
        run.cancel()


class _Run:
    """What runs.running holds for a live run, as far as the overlay asks: its sessions."""

    def __init__(self, session):
        self.sessions = [session]


def test_style_look_follows_the_slot(addon):
    overlay = addon.sphere.sphere_overlay
    gauss_core = addon.native.core()
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUBE')
    colours, normals = overlay.style_look(gauss_core, obj, slot)
    assert len(normals) == 6 and colours.shape == (2562, 4)
    slot.sigma = 20.0  # narrower bumps: most of the sphere darker
    sharper, _ = overlay.style_look(gauss_core, obj, slot)
    assert sharper[:, :3].sum() < colours[:, :3].sum()
    slot.orientation = (0.0, 0.0, 0.5)
    _, turned = overlay.style_look(gauss_core, obj, slot)
    assert not np.allclose(turned, normals)
    slot.preset = 'CUSTOM'
    with pytest.raises(addon.errors.SettingsError, match="has no normals"):
        overlay.style_look(gauss_core, obj, slot)


def test_show_gauss_sphere_is_an_object_setting_off_by_default(addon):
    obj = helpers.suzanne(levels=0)
    assert obj.gauss_stylization.show_gauss_sphere is False
    assert addon.settings_io.to_dict(obj.gauss_stylization)["show_gauss_sphere"] is False
    assert addon.sphere.sphere_overlay.shown_object(_Context(obj)) is None
    obj.gauss_stylization.show_gauss_sphere = True
    assert addon.sphere.sphere_overlay.shown_object(_Context(obj)) == obj


class _Context:
    def __init__(self, obj):
        self.active_object = obj

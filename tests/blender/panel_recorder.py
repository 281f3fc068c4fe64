"""A stand-in for Blender's UILayout that records what a panel draws, so tests can read a
panel's rows (headless: test_panel.py; in a real sidebar: windowed_panel.py).

    rows = draw(addon.ui.VIEW3D_PT_gauss_styles)   # [("label", text, icon), ("prop", name, text, index), ...]
"""

import bpy


class Layout:
    """Records labels, props, operators and lists in drawing order (``rows``, shared by every
    nested column, row, box and split)."""

    def __init__(self, rows=None):
        self.rows = [] if rows is None else rows

    def label(self, text="", icon='NONE', **_options):
        self.rows.append(("label", text, icon))

    def prop(self, owner, name, text=None, index=-1, **_options):
        self.rows.append(("prop", name, text, index))

    def prop_search(self, owner, name, *_args, text=None, **_options):
        self.rows.append(("prop", name, text, -1))

    def operator(self, idname, **_options):
        self.rows.append(("operator", idname))
        return type("Properties", (), {})()

    def template_list(self, list_type, *_args, **_options):
        self.rows.append(("list", list_type))

    def separator(self, **_options):
        pass

    def _nested(self, *_args, **_options):
        return Layout(self.rows)

    column = row = box = split = _nested


def draw(panel, context=None):
    """The rows ``panel`` (a Panel class) draws in ``context`` (default: bpy.context)."""
    layout = Layout()
    panel.draw(type("Panel", (), {"layout": layout})(), context or bpy.context)
    return layout.rows


def labels(rows):
    return [row[1] for row in rows if row[0] == "label"]


def props(rows):
    return [row[1] for row in rows if row[0] == "prop"]

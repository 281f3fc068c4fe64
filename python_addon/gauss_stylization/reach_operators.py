"""Style Reach's operators: the faces' angles to what their styles prefer (sphere/style_reach.py) as a
face attribute, for rendering (an Attribute node) and for the spreadsheet, and the faces the style has
not reached selected, to work on them."""

import bpy
import numpy as np
from bpy.props import FloatProperty

from .errors import NativeModuleError, SettingsError
from .mesh import crossings
from .run import runs
from .settings.validation import inspect_problem, poll_result
from .sphere import reach_overlay, style_reach

ATTRIBUTE = "gauss_style_angle"  # FACE float: degrees; UNSTYLED_VALUE where no slot stylizes the face
UNSTYLED_VALUE = -1.0


def _problem(context):
    problem = inspect_problem(context)
    if problem is not None:
        return problem
    obj = context.active_object
    if runs.is_running(obj):
        return "Keep or cancel the live run first (the overlay shows it meanwhile)"
    if not obj.gauss_stylization.styles:
        return "'%s' has no style slot to measure against" % obj.name
    return None


def polygon_angles(obj):
    """(#P,) degrees of ``obj``'s polygons (the area-weighted mean of their triangles'), NaN where no
    slot stylizes one. Raises SettingsError, NativeModuleError, ValueError."""
    if obj.mode == 'EDIT':
        obj.update_from_editmode()
    surface = reach_overlay.surface_of(obj)
    coords, triangles, tri_polygon = surface
    angles = reach_overlay.angles_of(obj, surface)
    corners = np.asarray(coords, np.float64)[triangles]
    areas = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    return style_reach.polygon_angles(angles, areas, tri_polygon, len(obj.data.polygons))


def _measured(operator, obj):
    try:
        return polygon_angles(obj)
    except (SettingsError, NativeModuleError, ValueError) as exc:
        operator.report({'ERROR'}, "Cannot measure '%s': %s" % (obj.name, exc))
        return None


class OBJECT_OT_gauss_store_style_angles(bpy.types.Operator):
    """Write each face's angle to its style's preferred normal (degrees; -1 where no style acts) into the
    face attribute 'gauss_style_angle', for an Attribute node in a material or the spreadsheet"""
    bl_idname = "object.gauss_store_style_angles"
    bl_label = "Store Style Angles"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _problem(context))

    def execute(self, context):
        obj = context.active_object
        edit = obj.mode == 'EDIT'
        angles = _measured(self, obj)
        if angles is None:
            return {'CANCELLED'}
        if edit:  # attributes of the mesh data: written in Object Mode, or Edit Mode would overwrite them
            bpy.ops.object.mode_set(mode='OBJECT')
        mesh = obj.data
        attribute = mesh.attributes.get(ATTRIBUTE)
        if attribute is not None and (attribute.data_type != 'FLOAT' or attribute.domain != 'FACE'):
            mesh.attributes.remove(attribute)
            attribute = None
        if attribute is None:
            attribute = mesh.attributes.new(ATTRIBUTE, 'FLOAT', 'FACE')
        values = np.where(np.isfinite(angles), angles, UNSTYLED_VALUE).astype(np.float32)
        attribute.data.foreach_set("value", values)
        mesh.update()
        if edit:
            bpy.ops.object.mode_set(mode='EDIT')
        styled = values[values >= 0]
        self.report({'INFO'}, "Face attribute '%s' written: %d faces, mean %.1f degrees, largest %.1f"
                    % (ATTRIBUTE, len(values), styled.mean() if len(styled) else 0.0,
                       styled.max() if len(styled) else 0.0))
        return {'FINISHED'}


class OBJECT_OT_gauss_select_unreached(bpy.types.Operator):
    """Select the faces at least Angle away from what their style prefers (Edit Mode shows them), to
    work on where the style is not reached"""
    bl_idname = "object.gauss_select_unreached"
    bl_label = "Select Unreached Faces"
    bl_options = {'REGISTER', 'UNDO'}

    angle: FloatProperty(name="Angle", description="Faces at least this many degrees from their style's "
                         "preferred normal are selected", default=style_reach.SCALE_DEGREES / 2.0,
                         min=0.0, max=180.0)

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _problem(context))

    def execute(self, context):
        obj = context.active_object
        angles = _measured(self, obj)
        if angles is None:
            return {'CANCELLED'}
        chosen = np.flatnonzero(np.nan_to_num(angles, nan=-1.0) >= self.angle).astype(np.int32)
        crossings.select_and_show(context, obj, chosen, running=False)
        self.report({'WARNING'} if len(chosen) else {'INFO'},
                    "%d of %d faces are %g degrees or more from their style's preferred normal%s"
                    % (len(chosen), len(angles), self.angle, "; they are selected" if len(chosen) else ""))
        return {'FINISHED'}


classes = (OBJECT_OT_gauss_store_style_angles, OBJECT_OT_gauss_select_unreached)

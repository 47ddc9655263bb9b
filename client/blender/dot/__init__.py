# SPDX-License-Identifier: AGPL-3.0-or-later
"""DOT: optimal, intersection-free triangulation of 3D polygons and hole
filling, computed by a dot-server (gRPC) through the dot_client package.

Operators (F3 search, or the menus below):
  mesh.dot_fill_loops        Edit Mode > Face: fill exactly the holes whose
                             rims are selected (FillHoles)
  mesh.dot_triangulate_loops Edit Mode > Face: a DOT patch per selected
                             loop, loose edges too (Triangulate)
  mesh.dot_fill_holes        Object/Edit Mode: fill every hole (FillHoles)
  mesh.dot_select_holes      Edit Mode: select the rims of the holes Fill Holes
                             would fill, and report their sizes (dry run)
  mesh.dot_triangulate_curve Object Mode: a closed curve -> a surface
  mesh.dot_surface_curves    Object Mode: a network of curves (splines whose
                             ends meet) -> one surface (SurfaceNetwork)
"""

bl_info = {
    "name": "DOT: Optimal Triangulation and Hole Filling",
    "author": "The dot authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Edit Mode > Face > Fill Loops (DOT), Triangulate Loops "
                "(DOT); Object > Fill Holes (DOT); Object > Convert > "
                "Triangulate Curve (DOT), Surface Curve Network (DOT)",
    "description": "Delaunay-restricted optimal triangulation (DOT) of hole "
                   "boundaries and curves, hole filling, and curve networks "
                   "into surfaces, by a dot-server",
    "category": "Mesh",
}

if "bpy" in locals():  # Reload Scripts (F8)
    import importlib
    for _m in (connection, geometry, operators, preferences):  # noqa: F821
        importlib.reload(_m)

import bpy  # noqa: E402

from . import connection, geometry, operators, preferences  # noqa: E402,F401


def _menu_edit_faces(self, context):
    self.layout.separator()
    self.layout.operator(operators.MESH_OT_dot_fill_loops.bl_idname)
    self.layout.operator(operators.MESH_OT_dot_triangulate_loops.bl_idname)
    self.layout.operator(operators.MESH_OT_dot_fill_holes.bl_idname)
    self.layout.operator(operators.MESH_OT_dot_select_holes.bl_idname)


def _menu_object(self, context):
    self.layout.separator()
    self.layout.operator(operators.MESH_OT_dot_fill_holes.bl_idname)


def _menu_convert(self, context):
    self.layout.operator(operators.MESH_OT_dot_triangulate_curve.bl_idname)
    self.layout.operator(operators.MESH_OT_dot_surface_curves.bl_idname)


_menus = (("VIEW3D_MT_edit_mesh_faces", _menu_edit_faces),
          ("VIEW3D_MT_object", _menu_object),
          ("VIEW3D_MT_object_convert", _menu_convert))


def register():
    bpy.utils.register_class(preferences.DotPreferences)
    for cls in operators.classes:
        bpy.utils.register_class(cls)
    for menu, draw in _menus:
        getattr(bpy.types, menu).append(draw)


def unregister():
    for menu, draw in reversed(_menus):
        getattr(bpy.types, menu).remove(draw)
    for cls in reversed(operators.classes):
        bpy.utils.unregister_class(cls)
    bpy.utils.unregister_class(preferences.DotPreferences)
    connection.close_all()

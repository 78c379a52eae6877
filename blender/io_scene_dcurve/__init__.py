"""dcurve (.dcrv) import and export: compressed vertex animation within a max error."""

bl_info = {
    "name": "dcurve (.dcrv)",
    "author": "dcurve",
    "version": (0, 4, 0),
    "blender": (3, 4, 0),
    "location": "File > Import-Export",
    "description": "Export an animated mesh (modifiers, shape keys, cloth and soft bodies) to a compressed .dcrv "
                   "file within a max error, and import .dcrv files as shape-key animation",
    "category": "Import-Export",
}

import bpy

from . import export_dcrv, import_dcrv


def menu_export(self, context):
    self.layout.operator(export_dcrv.ExportDcurve.bl_idname, text="dcurve (.dcrv)")


def menu_import(self, context):
    self.layout.operator(import_dcrv.ImportDcurve.bl_idname, text="dcurve (.dcrv)")


classes = (export_dcrv.ExportDcurve, import_dcrv.ImportDcurve)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.TOPBAR_MT_file_export.append(menu_export)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)

"""What `cmake --install` wrote works in Blender (scripts/test.sh runs this):
blender -b --factory-startup --python-exit-code 1 --python check_install.py -- ZIP
installs the add-on from the zip into the user's add-ons (HOME), enables it, and checks that
its operators are registered and that it loads the compiled module it ships."""

import os
import sys

import addon_utils
import bpy

zip_path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.preferences.addon_install(filepath=zip_path)
addon_utils.enable("io_scene_dcurve", default_set=True, handle_error=None)
bpy.ops.export_scene.dcurve.get_rna_type()  # raises when the operator is missing
bpy.ops.import_scene.dcurve.get_rna_type()
from io_scene_dcurve import module  # noqa: E402

shipped = os.path.dirname(module.__file__)
loaded = module.load().__file__
assert os.path.dirname(loaded) == shipped, "the add-on loaded %s, not its own copy in %s" % (loaded, shipped)
print("installed add-on: operators registered, module", loaded)

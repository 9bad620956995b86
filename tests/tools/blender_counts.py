# Imports a .glb into Blender (its own glTF importer, headless) and prints one JSON line: mesh
# objects, vertices, triangles and the world-space bounds of the vertices.
# Usage: blender -b --factory-startup --python blender_counts.py -- FILE.glb
import json
import sys

import bpy
import numpy as np

if not hasattr(np, "bool"):
    np.bool = bool  # Blender 3.4's importer still says np.bool, which numpy 1.24 removed

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=sys.argv[sys.argv.index("--") + 1])
meshes = vertices = triangles = 0
lo, hi = [1e300] * 3, [-1e300] * 3
for o in bpy.context.scene.objects:
    if o.type != "MESH":
        continue
    meshes += 1
    vertices += len(o.data.vertices)
    triangles += sum(len(p.vertices) - 2 for p in o.data.polygons)
    for v in o.data.vertices:
        w = o.matrix_world @ v.co
        lo = [min(a, b) for a, b in zip(lo, w)]
        hi = [max(a, b) for a, b in zip(hi, w)]
print("BLENDER " + json.dumps({"meshes": meshes, "vertices": vertices, "triangles": triangles, "min": lo, "max": hi}))

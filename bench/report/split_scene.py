#!/usr/bin/python3
"""A synthetic scene with each triangle of its (degraded) mesh split in two
at the midpoint of its longest edge: the same surface with twice the faces,
so that the rendered photos still fit (as bench/scale does for its city).
Arguments: the synth project's scene.json, the folder to write the split
mesh and scene.json into."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ply_mesh import read_ply, split_longest_edge, write_ply  # noqa: E402


def main():
    src, out = sys.argv[1:3]
    scene = json.load(open(src))
    base = os.path.dirname(os.path.abspath(src))
    verts, faces = read_ply(os.path.join(base, scene["mesh"]))
    verts, faces = split_longest_edge(verts, faces)
    os.makedirs(out, exist_ok=True)
    write_ply(os.path.join(out, "mesh.ply"), verts, faces, "bench/report")
    scene["mesh"] = os.path.abspath(os.path.join(out, "mesh.ply"))
    for v in scene["views"]:
        if v.get("image"):
            v["image"] = os.path.join(base, v["image"])
    json.dump(scene, open(os.path.join(out, "scene.json"), "w"), indent=1)
    print(len(faces))


if __name__ == "__main__":
    main()

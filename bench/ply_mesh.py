"""Triangle meshes as binary little-endian PLY, for the benchmark scripts
(bench/scale, bench/report): read as MeshNBV writes them, write, and split
each triangle in two (the same surface with twice the faces)."""
import numpy as np


def read_ply(path, fields=False):
    """Vertices and faces (and with `fields` the face properties) of a binary
    little-endian PLY written by MeshNBV."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    nv = nf = 0
    coord = "f4"
    face_props = []
    element = None
    for line in header:
        w = line.split()
        if w[0] == "element":
            element = w[1]
            if element == "vertex":
                nv = int(w[2])
            if element == "face":
                nf = int(w[2])
        elif w[0] == "property" and element == "vertex" and w[-1] == "x":
            coord = "f8" if w[1] == "double" else "f4"
        elif w[0] == "property" and element == "face" and w[1] != "list":
            face_props.append(("u1" if w[1] == "uchar" else "f4", w[2]))
    at = end
    verts = np.frombuffer(data, dtype="<" + coord, count=3 * nv, offset=at).reshape(nv, 3).astype(np.float64)
    at += 3 * nv * np.dtype(coord).itemsize
    fields_of = [("n", "u1"), ("v", "<i4", 3)] + [(name, "<" + t) for t, name in face_props]
    faces = np.frombuffer(data, dtype=np.dtype(fields_of), count=nf, offset=at)
    if fields:
        return faces
    return verts, np.array(faces["v"], dtype=np.int32)


def write_ply(path, verts, faces, comment="bench"):
    head = ("ply\nformat binary_little_endian 1.0\ncomment %s\nelement vertex %d\n"
            "property double x\nproperty double y\nproperty double z\nelement face %d\n"
            "property list uchar int vertex_indices\nend_header\n" % (comment, len(verts), len(faces)))
    rec = np.zeros(len(faces), dtype=np.dtype([("n", "u1"), ("v", "<i4", 3)]))
    rec["n"] = 3
    rec["v"] = faces
    with open(path, "wb") as f:
        f.write(head.encode())
        f.write(np.ascontiguousarray(verts, dtype="<f8").tobytes())
        f.write(rec.tobytes())


def split_longest_edge(verts, faces):
    """Each triangle into two at the midpoint of its longest edge (the same surface)."""
    a, b, c = (verts[faces[:, k]] for k in range(3))
    lengths = np.stack([np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1),
                        np.linalg.norm(a - c, axis=1)], axis=1)
    e = np.argmax(lengths, axis=1)
    # Each face rotated so that its longest edge is (r0, r1), orientation kept.
    idx = np.arange(len(faces))
    r = np.stack([faces[idx, e], faces[idx, (e + 1) % 3], faces[idx, (e + 2) % 3]], axis=1)
    # One midpoint per undirected edge, shared by the two faces on it.
    lo, hi = np.minimum(r[:, 0], r[:, 1]), np.maximum(r[:, 0], r[:, 1])
    keys = lo.astype(np.int64) * len(verts) + hi
    uniq, inverse = np.unique(keys, return_inverse=True)
    mids = 0.5 * (verts[uniq // len(verts)] + verts[uniq % len(verts)])
    m = len(verts) + inverse
    new_faces = np.concatenate([np.stack([r[:, 0], m, r[:, 2]], 1), np.stack([m, r[:, 1], r[:, 2]], 1)])
    return np.concatenate([verts, mids]), new_faces.astype(np.int32)

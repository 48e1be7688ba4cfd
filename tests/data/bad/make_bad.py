#!/usr/bin/env python3
"""Writes the generated files of tests/data/bad/ (binary PLYs, PNGs, scene
folders). The hand-written ones (face_index_out_of_range.ply, huge_count.off,
huge_vertex_count.ply, malformed_header.ply, nan_vertex.ply,
truncated_binary.ply, wrong_magic.ply) are not touched. README.md lists what
each file is and the error it must give; tests/cli/bad_input.sh checks them."""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

PYRAMID_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
PYRAMID_F = [(0, 3, 2), (0, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]


def write(name, data):
    path = os.path.join(HERE, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def png(width, height, seed=0):
    """An 8-bit grey PNG with some texture."""
    rows = b"".join(b"\0" + bytes(((x * 37 + y * 91 + seed) * 7) % 256 for x in range(width))
                    for y in range(height))

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def ply_header(fmt, nv, nf, index_type="int", comment=None):
    h = "ply\nformat %s 1.0\n" % fmt
    if comment:
        h += "comment %s\n" % comment
    h += "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % nv
    h += "element face %d\nproperty list uchar %s vertex_indices\nend_header\n" % (nf, index_type)
    return h.encode()


def ply_body(endian, vertices=PYRAMID_V, faces=PYRAMID_F):
    body = b"".join(struct.pack(endian + "3f", *v) for v in vertices)
    body += b"".join(struct.pack(endian + "B3i", 3, *f) for f in faces)
    return body


def meshes():
    # ascii file that ends inside the vertex list
    write("truncated_ascii.ply",
          ply_header("ascii", 5, 6, comment="ends after the third vertex") +
          b"0 0 0\n1 0 0\n1 1 0\n")
    # header declares 4 vertices, the data holds 3: the first face line is
    # then read as a vertex and has one value too many
    write("wrong_count.ply",
          ply_header("ascii", 4, 1, comment="declares 4 vertices, holds 3") +
          b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    # binary, 10^12 faces declared: must be refused before allocating
    write("huge_face_count.ply",
          ply_header("binary_little_endian", 5, 10**12, comment="claims 10^12 faces") +
          ply_body("<"))
    # a face whose list length (uint) says 4294967295 indices
    h = (b"ply\nformat binary_little_endian 1.0\ncomment a face list of 2^32-1 indices\n"
         b"element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         b"element face 1\nproperty list uint int vertex_indices\nend_header\n")
    write("huge_list_length.ply",
          h + ply_body("<", PYRAMID_V[:3], []) + struct.pack("<I3i", 0xFFFFFFFF, 0, 1, 2))
    # big-endian data under a little-endian header, and the reverse
    write("wrong_endianness.ply",
          ply_header("binary_little_endian", 5, 6, comment="big-endian data, little-endian header")
          + ply_body(">"))
    write("wrong_endianness_be.ply",
          ply_header("binary_big_endian", 5, 6, comment="little-endian data, big-endian header")
          + ply_body("<"))
    # every face has zero area (all vertices on one line, or repeated)
    write("zero_area_faces.ply",
          ply_header("ascii", 4, 3, comment="every face has zero area") +
          b"0 0 0\n1 0 0\n2 0 0\n3 0 0\n3 0 1 2\n3 1 2 3\n3 0 0 1\n")
    write("nan_vertex.obj", "# a NaN coordinate\nv 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n")
    write("out_of_range.obj", "# face refers to vertex 9 of 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    write("truncated.off", "OFF\n# ends inside the vertex list\n4 2 0\n0 0 0\n1 0 0\n")
    write("nan_vertex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n")


CAM = ('"width": 8, "height": 6, "fx": 8, "fy": 8, "cx": 3.5, "cy": 2.5, '
       '"R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]')


def json_scene(views, mesh='"pyramid.ply"'):
    return '{"format": "meshnbv-scene", "version": 1, "mesh": %s, "views": [\n%s\n]}\n' % (
        mesh, ",\n".join(views))


def view(label, image, t, extra=""):
    img = "null" if image is None else '"%s"' % image
    return ' {"label": "%s", "image": %s, "camera": {%s, "t": %s%s}}' % (label, img, CAM, t, extra)


def scenes():
    write("scenes/pyramid.ply", ply_header("binary_little_endian", 5, 6) + ply_body("<"))
    write("scenes/view_a.png", png(8, 6, 1))
    write("scenes/view_b.png", png(8, 6, 2))
    write("scenes/big.png", png(16, 12, 3))
    write("scenes/unreadable.png", "this is not a PNG image\n")
    # cameras 3 units in front of the pyramid (looking along +z at it)...
    front_a = "[-0.5, -0.5, 3]"
    front_b = "[-0.4, -0.5, 3]"
    write("scenes/image_missing.json",
          json_scene([view("a", "view_a.png", front_a), view("b", "missing.png", front_b)]))
    write("scenes/image_unreadable.json",
          json_scene([view("a", "view_a.png", front_a), view("b", "unreadable.png", front_b)]))
    write("scenes/image_wrong_size.json",
          json_scene([view("a", "view_a.png", front_a), view("b", "big.png", front_b)]))
    # ...and cameras placed so that the pyramid is behind them (t_z < 0)
    write("scenes/cameras_facing_away.json",
          json_scene([view("a", "view_a.png", "[-0.5, -0.5, -3]"),
                      view("b", "view_b.png", "[-0.4, -0.5, -3]"),
                      view("c", None, "[-0.5, -0.5, -4]")]))
    write("scenes/zero_area_mesh.json",
          json_scene([view("a", "view_a.png", front_a), view("b", "view_b.png", front_b)],
                     '"../zero_area_faces.ply"'))
    write("scenes/missing_mesh.json", json_scene([view("a", "view_a.png", front_a)], '"gone.ply"'))
    write("scenes/nan_camera.json", json_scene([view("a", "view_a.png", "[NaN, 0, 3]")]))
    write("scenes/huge_camera.json", json_scene([view("a", "view_a.png", front_a).replace(
        '"width": 8', '"width": 1e300')]))
    write("scenes/wrong_type.json",
          '{"format": "meshnbv-scene", "version": "1", "mesh": null, "views": []}\n')
    write("scenes/truncated.json", json_scene([view("a", "view_a.png", front_a)])[:150])
    write("scenes/not_utf8.json",
          b'{"format": "meshnbv-scene", "version": 1, "mesh": "caf\xe9.ply", "views": []}\n')
    vcg = ('<VCGCamera TranslationVector="0.5 0.5 -3 1" RotationMatrix="1 0 0 0 0 -1 0 0 0 0 -1 0 '
           '0 0 0 1" CameraType="0" BinaryData="0" FocalMm="%s" LensDistortion="0 0" '
           'PixelSizeMm="0.0369161 0.0369161" ViewportPx="%s" CenterPx="4 3"/>')
    raster = '<MLRaster label="a">%s<Plane fileName="view_a.png"/></MLRaster>'
    project = ('<?xml version="1.0"?>\n<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n'
               ' <MeshGroup><MLMesh label="m" filename="%s"/></MeshGroup>\n'
               ' <RasterGroup>%s</RasterGroup>\n</MeshLabProject>\n')
    write("scenes/malformed.mlp", (project % ("pyramid.ply", raster % (vcg % ("0.3", "8 6"))))[:200])
    write("scenes/nan_camera.mlp", project % ("pyramid.ply", raster % (vcg % ("nan", "8 6"))))
    write("scenes/huge_viewport.mlp", project % ("pyramid.ply", raster % (vcg % ("0.3", "1e300 6"))))
    write("scenes/missing_mesh.mlp", project % ("gone.ply", raster % (vcg % ("0.3", "8 6"))))
    write("scenes/not_utf8.mlp",
          (project % ("caf\xe9.ply", raster % (vcg % ("0.3", "8 6")))).encode("latin-1"))
    write("scenes/binary_camera_garbage.mlp", project % (
        "pyramid.ply", '<MLRaster label="a"><VCGCamera BinaryData="1" TranslationVector="////////'
        '////////////////" RotationMatrix="!!" FocalMm="AAAA" LensDistortion="AAAAAAAAAAA=" '
        'PixelSizeMm="AAAAAAAAAAA=" ViewportPx="AAAAAAAAAAA=" CenterPx="AAAAAAAAAAA="/></MLRaster>'))

    line = "%s 8 0 3.5 0 8 2.5 0 0 1 1 0 0 0 1 0 0 0 1 -0.5 -0.5 3\n"
    write("middlebury_count/set_par.txt", "3\n" + line % "a.png" + line % "b.png")
    write("middlebury_count/a.png", png(8, 6, 1))
    write("middlebury_huge_count/set_par.txt", "99999999999999\n" + line % "a.png")
    write("middlebury_short_line/set_par.txt",
          "2\n" + line % "a.png" + "b.png 8 0 3.5 0 8 2.5 0 0 1 1 0 0 0 1\n")
    write("middlebury_no_images/set_par.txt", "2\n" + line % "a.png" + line % "b.png")
    write("middlebury_unreadable_image/set_par.txt", "1\n" + line % "a.png")
    write("middlebury_unreadable_image/a.png", "not a PNG\n")

    cameras = "1 PINHOLE 8 6 8 8 4 3\n"
    write("colmap_unknown_camera/cameras.txt", cameras)
    write("colmap_unknown_camera/images.txt", "1 1 0 0 0 -0.5 -0.5 3 9 a.png\n\n")
    write("colmap_truncated/cameras.txt", cameras)
    write("colmap_truncated/images.txt", "1 1 0 0 0 -0.5 -0.5\n")
    write("colmap_bad_model/cameras.txt", "1 FISHEYE 8 6 8 4 3 0.1\n")
    write("colmap_bad_model/images.txt", "1 1 0 0 0 -0.5 -0.5 3 1 a.png\n\n")
    write("colmap_zero_quaternion/cameras.txt", cameras)
    write("colmap_zero_quaternion/images.txt", "1 0 0 0 0 -0.5 -0.5 3 1 a.png\n\n")

    # Binary models (COLMAP's little-endian layout, docs/formats.md).
    def cameras_bin(model_id, params):
        return (struct.pack("<Q", 1) + struct.pack("<IiQQ", 1, model_id, 8, 6) +
                struct.pack("<%dd" % len(params), *params))
    image_bin = (struct.pack("<Q", 1) + struct.pack("<I7dI", 1, 1, 0, 0, 0, -0.5, -0.5, 3, 1) +
                 b"a.png\0" + struct.pack("<Q", 0))
    write("colmap_bin_truncated/cameras.bin", cameras_bin(1, [8, 8, 4, 3]))
    write("colmap_bin_truncated/images.bin", image_bin[:40])
    write("colmap_bin_unknown_model/cameras.bin", cameras_bin(42, [8, 8, 4, 3]))
    write("colmap_bin_unknown_model/images.bin", image_bin)
    write("colmap_bin_huge_count/cameras.bin", cameras_bin(1, [8, 8, 4, 3]))
    write("colmap_bin_huge_count/images.bin", struct.pack("<Q", 2**62) + image_bin[8:])

    cam = "8 0 0\n1 0 0\n0 1 0\n0 0 1\n-0.5 -0.5 -3\n"
    write("bundler_truncated/bundle.out", "# Bundle file v0.3\n2 0\n" + cam + "8 0 0\n1 0 0\n")
    write("bundler_truncated/list.txt", "a.png\nb.png\n")
    write("bundler_huge_count/bundle.out", "# Bundle file v0.3\n99999999999 0\n" + cam)
    write("bundler_huge_count/list.txt", "a.png\n")
    write("bundler_list_mismatch/bundle.out", "# Bundle file v0.3\n2 0\n" + cam + cam)
    write("bundler_list_mismatch/list.txt", "a.png\n")
    write("bundler_missing_image/bundle.out", "# Bundle file v0.3\n1 0\n" + cam)
    write("bundler_missing_image/list.txt", "gone.png\n")


if __name__ == "__main__":
    meshes()
    scenes()

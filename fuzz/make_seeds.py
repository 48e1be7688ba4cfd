#!/usr/bin/env python3
"""Writes the seed corpora fuzz/seeds/<target>/ (small, valid or nearly valid
inputs of every feature each reader has). Run from anywhere; rewrites the
folders. The fixture files the scenes name (mesh.ply, image.png, images/a.png,
v0.png, ...) are created by the fuzz targets themselves (fuzz_common.cpp)."""
import base64
import os
import shutil
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "tests", "data")
SEEDS = os.path.join(HERE, "seeds")

PYRAMID_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
PYRAMID_F = [(0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]


def write(target, name, data):
    folder = os.path.join(SEEDS, target)
    os.makedirs(folder, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def copy(target, src, name=None):
    with open(os.path.join(DATA, src), "rb") as f:
        write(target, name or os.path.basename(src), f.read())


def ply_binary(endian, coord="f", with_extras=True):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    ctype = "float" if coord == "f" else "double"
    h = "ply\nformat %s 1.0\ncomment seed\nelement vertex %d\n" % (fmt, len(PYRAMID_V))
    h += "".join("property %s %s\n" % (ctype, a) for a in "xyz")
    if with_extras:
        h += "property list uchar int tags\n"
    h += "element face %d\nproperty list uchar int vertex_indices\n" % len(PYRAMID_F)
    if with_extras:
        h += "property float quality\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
        h += "element material 1\nproperty list ushort float values\n"
    h += "end_header\n"
    body = b""
    for v in PYRAMID_V:
        body += struct.pack(endian + "3" + coord, *v)
        if with_extras:
            body += struct.pack(endian + "B2i", 2, 7, 8)
    for i, f in enumerate(PYRAMID_F):
        body += struct.pack(endian + "B%di" % len(f), len(f), *f)
        if with_extras:
            body += struct.pack(endian + "f3B", 0.5 * i, 255, i * 40, 0)
    if with_extras:
        body += struct.pack(endian + "H2f", 2, 1.5, -2.5)
    return h.encode() + body


def ply_seeds():
    copy("ply", "meshes/pyramid.ply")
    for name in sorted(os.listdir(os.path.join(DATA, "bad"))):
        if name.endswith(".ply"):
            copy("ply", "bad/" + name, "bad_" + name)
    write("ply", "binary_le.ply", ply_binary("<"))
    write("ply", "binary_be.ply", ply_binary(">"))
    write("ply", "binary_le_double.ply", ply_binary("<", "d", False))
    write("ply", "ascii_crlf.ply",
          "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
          "property float z\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\n"
          "property double value\r\nend_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2 nan\r\n")


def ply_binary_seeds():
    # Body bytes for each fixed header of fuzz_ply_binary.cpp; byte 0 picks it.
    tri_v = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    tri_f = [(0, 1, 2), (0, 2, 3), (0, 3, 1, 2)]
    body = b"".join(struct.pack("<3f", *v) for v in tri_v)
    body += b"".join(struct.pack("<B%di" % len(f), len(f), *f) + struct.pack("<f3B", 1.0, 1, 2, 3)
                     for f in tri_f)
    write("ply_binary", "le_float", bytes([0, 4, 3]) + body)
    body = b"".join(struct.pack(">3f", *v) for v in tri_v)
    body += b"".join(struct.pack(">B%di" % len(f), len(f), *f) + struct.pack(">f3B", 1.0, 1, 2, 3)
                     for f in tri_f)
    write("ply_binary", "be_float", bytes([1, 4, 3]) + body)
    body = b"".join(struct.pack("<3dBf h", *v, 1, 0.5, -3) for v in tri_v)
    body += b"".join(struct.pack("<i%dI" % len(f), len(f), *f) + struct.pack("<d", 2.5) for f in tri_f)
    write("ply_binary", "le_double", bytes([2, 4, 3]) + body)
    body = b"".join(struct.pack(">H%dH" % len(f), len(f), *f) + struct.pack(">i", 9) for f in tri_f)
    body += struct.pack(">I2fB", 2, 1.0, 2.0, 1) + struct.pack(">I0fB", 0, 2)
    body += b"".join(struct.pack(">bhH", *v) for v in tri_v)
    write("ply_binary", "be_faces_first", bytes([3, 4, 3]) + body)


def obj_seeds():
    copy("obj", "meshes/pyramid.obj")
    write("obj", "groups.obj",
          "# groups, smoothing, lines and points\nv 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
          "vt 0 0\nvt 1 0\nvn 0 0 1\ng a b\ns 1\nf 1/1 2/2 3/1\nusemtl m\nl 1 2\np 3\n"
          "o second\nf -4//1 -2//1 -1//1\nf 1 2 3 4\n")
    write("obj", "short_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n")
    write("obj", "out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")


def off_seeds():
    copy("off", "meshes/pyramid.off")
    copy("off", "bad/huge_count.off", "bad_huge_count.off")
    write("off", "coff_inline.off",
          "COFF 4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 1 1 1 1\n"
          "3 0 1 2 0.1 0.2 0.3\n3 0 2 3\n")
    write("off", "stnoff.off",
          "STNOFF\n# normals and texture coordinates\n3 1 3\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n"
          "0 1 0 0 0 1 0 1\n3 0 1 2\n")


VCG_TEXT = ('<VCGCamera TranslationVector="-0.5 -0.5 -3 1" RotationMatrix="1 0 0 0 0 -1 0 0 0 0 -1 0 '
            '0 0 0 1 " CameraType="0" BinaryData="0" FocalMm="0.3" LensDistortion="0 0" '
            'PixelSizeMm="0.0369161 0.0369161" ViewportPx="8 6" CenterPx="4 3"/>')


def b64(fmt, *values):
    return base64.b64encode(struct.pack(fmt, *values)).decode()


VCG_BINARY = ('<VCGCamera BinaryData="1" CameraType="0" TranslationVector="%s" RotationMatrix="%s" '
              'FocalMm="%s" LensDistortion="%s" PixelSizeMm="%s" ViewportPx="%s" CenterPx="%s"/>' % (
                  b64("<4f", -0.5, -0.5, -3, 1),
                  b64("<16f", 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1),
                  b64("<f", 0.3), b64("<2f", 0, 0), b64("<2f", 0.0369161, 0.0369161),
                  b64("<2i", 8, 6), b64("<2f", 4, 3)))


def mlp_seeds():
    identity = "<MLMatrix44>\n1 0 0 0 \n0 1 0 0 \n0 0 1 0 \n0 0 0 1 \n</MLMatrix44>"
    shifted = "<MLMatrix44>\n1 0 0 2 \n0 1 0 0 \n0 0 1 0 \n0 0 0 1 \n</MLMatrix44>"
    write("mlp", "text.mlp",
          '<?xml version="1.0"?>\n<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n <MeshGroup>\n'
          '  <MLMesh label="mesh" filename="mesh.ply" visible="1">%s</MLMesh>\n </MeshGroup>\n'
          ' <RasterGroup>\n  <MLRaster label="view_0">\n   %s\n'
          '   <Plane semantic="1" fileName="image.png"/>\n  </MLRaster>\n'
          '  <MLRaster label="candidate">\n   %s\n  </MLRaster>\n </RasterGroup>\n'
          '</MeshLabProject>\n' % (identity, VCG_TEXT, VCG_TEXT))
    write("mlp", "binary.mlp",
          '<MeshLabProject><MeshGroup><MLMesh filename="mesh.obj">%s</MLMesh>'
          '<MLMesh filename="mesh.off">%s</MLMesh></MeshGroup><RasterGroup>'
          '<MLRaster label="b">%s<Plane fileName="images/a.png"/></MLRaster></RasterGroup>'
          '</MeshLabProject>' % (identity, shifted, VCG_BINARY))
    write("mlp", "no_mesh.mlp",
          '<MeshLabProject><RasterGroup><MLRaster>%s</MLRaster></RasterGroup></MeshLabProject>'
          % VCG_TEXT)


def camera_json(fx=4.0, k=False):
    cam = ('{"width": 8, "height": 6, "fx": %s, "fy": %s, "cx": 3.5, "cy": 2.5, '
           '"R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "t": [-0.5, -0.5, 3]' % (fx, fx))
    if k:
        cam += ', "k1": -0.1, "k2": 0.01'
    return cam + "}"


def json_seeds():
    write("json", "scene.json",
          '{"format": "meshnbv-scene", "version": 1, "mesh": "mesh.ply", "views": [\n'
          ' {"label": "view_0", "image": "image.png", "used": true, "camera": %s},\n'
          ' {"label": "aside", "image": "images/a.png", "used": false, "camera": %s},\n'
          ' {"label": "candidate", "image": null, "camera": %s}]}\n'
          % (camera_json(), camera_json(k=True), camera_json(5.5)))
    write("json", "no_mesh.json",
          '{"format": "meshnbv-scene", "version": 1, "mesh": null, "views": []}')
    write("json", "obj_mesh.json",
          '{"format": "meshnbv-scene", "version": 1, "mesh": "mesh.obj", "views": '
          '[{"camera": %s}]}' % camera_json())


def middlebury_seeds():
    copy("middlebury", "middlebury/tiny/tiny_par.txt", "tiny_par.txt")
    write("middlebury", "missing_image_par.txt",
          "3\nv0.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0 0 1 0.1 -0.05 2\n"
          "gone.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0 0 1 0.1 -0.05 2\n"
          "v1.png 1000 0 63 0 1020 47 0 0 2 0 0 1 0 1 0 -1 0 0 0 0 2.5\n")


def colmap_seeds():
    cams = open(os.path.join(DATA, "colmap/handwritten/cameras.txt")).read()
    imgs = open(os.path.join(DATA, "colmap/handwritten/images.txt")).read()
    imgs = imgs.replace("rot_z90.png", "a.png").replace("identity.png", "b.png") \
               .replace("cyclic.png", "c.png")
    write("colmap", "handwritten", cams + "%%%%\n" + imgs)
    write("colmap", "models",
          "# all five models\n1 SIMPLE_PINHOLE 8 6 4 4 3\n2 PINHOLE 8 6 4 4.5 4 3\n"
          "3 SIMPLE_RADIAL 8 6 4 4 3 0.01\n4 RADIAL 8 6 4 4 3 0.01 -0.001\n"
          "5 OPENCV 8 6 4 4.5 4 3 0.01 -0.001 0 0\n%%%%\n"
          "1 1 0 0 0 0 0 3 1 a.png\n\n2 1 0 0 0 0 0 3 2 b.png\n1 2 -1\n"
          "3 0 1 0 0 0 0 3 3 images/a.png\n1 2 3 4 5 6\n4 1 0 0 0 0 0 3 4 image.png\n\n"
          "5 1 0 0 0 0 0 3 5 missing.png\n")


def bundler_seeds():
    bundle = open(os.path.join(DATA, "bundler/small/bundle.out")).read()
    lst = open(os.path.join(DATA, "bundler/small/list.txt")).read()
    write("bundler", "small", bundle + "%%%%\n" + lst)
    write("bundler", "no_header",
          "2 0\n4 0.1 0.01\n1 0 0\n0 1 0\n0 0 1\n0 0 -3\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n"
          "%%%%\nimage.png 0 4\nbroken.png\n")


def colmap_binary_seeds():
    # COLMAP's binary layout (libs/io/src/colmap_binary.cpp); the fixture
    # images a.png, b.png are 8x6.
    def cameras(entries):
        out = struct.pack("<Q", len(entries))
        for cid, model, params in entries:
            out += struct.pack("<IiQQ", cid, model, 8, 6) + struct.pack("<%dd" % len(params), *params)
        return out
    def images(entries):
        out = struct.pack("<Q", len(entries))
        for iid, cid, name, pts in entries:
            out += struct.pack("<I7dI", iid, 1, 0, 0, 0, -0.5, -0.5, 3, cid) + name + b"\0"
            out += struct.pack("<Q", len(pts))
            for x, y, pid in pts:
                out += struct.pack("<ddQ", x, y, pid)
        return out
    points = struct.pack("<Q", 1) + struct.pack("<Q3d3BdQ", 1, 0, 0, 0, 255, 0, 0, 0.5, 2) + \
        struct.pack("<IIII", 1, 0, 2, 0)
    sep = b"\n%%%%\n"
    write("colmap_binary", "opencv", cameras([(1, 4, [8, 8, 4, 3, -0.01, 0.001, 0.0001, -0.0002])]) + sep +
          images([(1, 1, b"a.png", [(4.5, 3.5, 1)]), (2, 1, b"b.png", [(4.5, 3.5, 1)])]) + sep + points)
    write("colmap_binary", "all_models", cameras([
        (1, 0, [8, 4, 3]), (2, 1, [8, 8, 4, 3]), (3, 2, [8, 4, 3, 0.01]), (4, 3, [8, 4, 3, 0.01, 0]),
        (5, 5, [8, 8, 4, 3, 0.01, 0, 0, 0]), (6, 6, [8, 8, 4, 3, 0, 0, 0, 0, 0.01, 0, 0, 0]),
        (7, 7, [8, 8, 4, 3, 0]), (8, 8, [8, 4, 3, 0.01]), (9, 9, [8, 4, 3, 0.01, 0]),
        (10, 10, [8, 8, 4, 3, 0, 0, 0, 0, 0, 0, 0, 0])]) + sep +
        images([(i, i, b"a.png", []) for i in range(1, 11)]))


def metashape_seeds():
    sensor = ('<sensor id="{i}" label="s{i}" type="{t}"><resolution width="8" height="6"/>'
              '<calibration type="{t}" class="adjusted"><resolution width="8" height="6"/>'
              '<f>8</f><cx>0.1</cx><cy>-0.1</cy><b1>0.01</b1><b2>0.02</b2><k1>-0.01</k1>'
              '<k2>0.001</k2><p1>0.0001</p1><p2>-0.0001</p2></calibration></sensor>')
    camera = ('<camera id="{i}" sensor_id="{s}" label="{l}"{c}><transform>1 0 0 0.5 0 1 0 0.5 0 0 1 -3 '
              '0 0 0 1</transform></camera>')
    fisheye = sensor.format(i=1, t="fisheye").replace("<p1>0.0001</p1><p2>-0.0001</p2>", "")
    write("metashape", "chunk",
          '<?xml version="1.0" encoding="UTF-8"?>\n<document version="1.5.0"><chunk label="c">'
          "<sensors>" + sensor.format(i=0, t="frame") + fisheye + "</sensors>"
          '<components><component id="0"><transform><rotation>1 0 0 0 1 0 0 0 1</rotation>'
          "<translation>0 0 0</translation><scale>1</scale></transform></component></components>"
          '<cameras><group id="0" label="g">' + camera.format(i=0, s=0, l="a", c="") +
          camera.format(i=1, s=1, l="b", c=' component_id="0"') + "</group>" +
          '<camera id="2" sensor_id="0" label="image"/></cameras>'
          "<transform><rotation>1 0 0 0 1 0 0 0 1</rotation><translation>1 2 3</translation>"
          "<scale>2</scale></transform></chunk></document>\n")


def openmvg_seeds():
    views = ",".join(
        '{"key": %d, "value": {"polymorphic_id": 1073741824, "ptr_wrapper": {"id": %d, "data": '
        '{"local_path": "", "filename": "%s", "width": 8, "height": 6, "id_view": %d, '
        '"id_intrinsic": %d, "id_pose": %d}}}}' % (i, 2147483649 + i, n, i, i, i)
        for i, n in enumerate(["a.png", "b.png", "c.png"]))
    intr = ('{"key": 0, "value": {"polymorphic_id": 2147483649, "polymorphic_name": "pinhole_brown_t2", '
            '"ptr_wrapper": {"id": 2147483660, "data": {"width": 8, "height": 6, "focal_length": 8, '
            '"principal_point": [4, 3], "disto_t2": [-0.01, 0.001, 0, 0.0001, -0.0001]}}}},'
            '{"key": 1, "value": {"polymorphic_id": 2147483650, "polymorphic_name": "fisheye", '
            '"ptr_wrapper": {"id": 2147483661, "data": {"width": 8, "height": 6, "focal_length": 8, '
            '"principal_point": [4, 3], "fisheye": [0.01, 0, 0, 0]}}}}')
    extr = ",".join('{"key": %d, "value": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], '
                    '"center": [0.5, 0.5, %d]}}' % (i, -3 - i) for i in range(2))
    write("openmvg", "brown_fisheye",
          '{"sfm_data_version": "0.3", "root_path": "images", "views": [%s], "intrinsics": [%s], '
          '"extrinsics": [%s], "structure": [{"key": 0, "value": {"X": [0.5, 0.5, 0], '
          '"observations": [{"key": 0, "value": {"id_feat": 1, "x": [4, 3]}}]}}], '
          '"control_points": []}\n' % (views, intr, extr))


def alicevision_seeds():
    for version, focal in (("1.0.0", '"pxFocalLength": "8"'),
                           ("1.2.5", '"focalLength": "36", "sensorWidth": "36", "pixelRatio": "1.01"')):
        pp = '["4", "3"]' if version == "1.0.0" else '["0", "0"]'
        write("alicevision", "v" + version.replace(".", "_"),
              '{"version": ["%s", "%s", "%s"], "featuresFolders": [""], "views": ['
              '{"viewId": "1", "poseId": "1", "intrinsicId": "7", "path": "C:\\\\shoot\\\\a.png", '
              '"width": "8", "height": "6"},'
              '{"viewId": "2", "poseId": "9", "intrinsicId": "7", "path": "/x/b.png"}],'
              '"intrinsics": [{"intrinsicId": "7", "width": "8", "height": "6", "type": "brown", %s, '
              '"principalPoint": %s, "distortionParams": ["-0.01", "0.001", "0", "0.0001", "0"]}],'
              '"poses": [{"poseId": "1", "pose": {"transform": {"rotation": ["1", "0", "0", "0", "1", '
              '"0", "0", "0", "1"], "center": ["0.5", "0.5", "-3"]}}}],'
              '"structure": [{"landmarkId": "0", "X": ["0.5", "0.5", "0"], "observations": '
              '[{"observationId": "1", "featureId": "3", "x": ["4", "3"]}]}]}\n'
              % (version[0], version[2], version[4], focal, pp))


def wire_seeds():
    """The messages of libs/mpi/src/wire.cpp, little endian (x86-64)."""
    def vec(fmt, values):
        return struct.pack("<Q", len(values)) + b"".join(struct.pack("<" + fmt, v) for v in values)

    def string(text):
        text = text.encode() if isinstance(text, str) else text
        return struct.pack("<Q", len(text)) + text

    def camera(fx, tx):
        head = struct.pack("<13d", fx, fx, 31.5, 23.5, 0.01, 0, 0, 0, 0, 0, 0.001, 0, 0)
        R = struct.pack("<9d", 1, 0, 0, 0, 1, 0, 0, 0, 1)
        return head + struct.pack("<3i", 64, 48, 0) + R + struct.pack("<3d", tx, 0, 3)

    xyz = [c for v in PYRAMID_V for c in v]
    tris = [(0, 3, 2), (0, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    scene = (struct.pack("<I", 0x4D4E5331) + vec("d", xyz) + struct.pack("<Q", len(tris)) +
             b"".join(struct.pack("<3i", *t) for t in tris) + string("mesh.ply") + string("scene.json") +
             struct.pack("<Q", 1 << 30) + struct.pack("<Q", 2))
    scene += string("v0") + camera(50, 0) + string("v0.png") + struct.pack("<BB", 1, 0)
    pixels = bytes(range(48)) * 2
    scene += string("v1") + camera(50, 0.5) + string("") + struct.pack("<BB", 1, 1)
    scene += struct.pack("<3i", 8, 4, 3) + string(pixels)
    write("wire", "scene.bin", scene)
    # Field by field, unpadded (offset measure, 4 views per face).
    options = (struct.pack("<I", 0x4D4E4F31) + struct.pack("<i", 2) + struct.pack("<i", 0) +
               struct.pack("<i", 4) + struct.pack("<B", 0) + struct.pack("<i", 0) + struct.pack("<d", 1e-6) +
               struct.pack("<d", 80) + struct.pack("<B", 1) + struct.pack("<d", 0.5) + struct.pack("<d", 4) +
               struct.pack("<d", 3) + struct.pack("<i", 4) + struct.pack("<i", 1) + struct.pack("<d", 1e-4) +
               struct.pack("<d", 1e-6))
    write("wire", "options.bin", options)
    write("wire", "faces.bin", struct.pack("<I", 0x4D4E4631) + vec("I", [0, 2, 5]))
    part = (vec("I", [1, 4]) + vec("f", [0.5, float("nan")]) + vec("i", [3, 1]) + vec("B", [0, 1]) +
            vec("i", [3, 0]) + vec("i", [6, 6]) + vec("f", [0.1, float("nan")]) + vec("Q", [12345, 678]) +
            vec("f", [0.25, float("nan")]) + vec("f", [2, 0]) + vec("f", [0.01, 0]) + struct.pack("<4Q", 2, 2, 1, 0))
    empty = b"".join(vec(f, []) for f in "IfiBiifQfff") + struct.pack("<4Q", 2, 0, 0, 0)
    write("wire", "parts.bin", struct.pack("<I", 0x4D4E5031) + struct.pack("<Q", 2) + part + empty)
    points = lambda pts: vec("d", [c for p in pts for c in p])
    score = (struct.pack("<I", 0x4D4E4A31) + struct.pack("<QB", 77, 1) + vec("d", xyz) +
             struct.pack("<Q", len(tris)) + b"".join(struct.pack("<3i", *t) for t in tris) +
             vec("i", [2, 3]) + vec("i", [1, 2, 3, 4]) + points([(0, 0, 1)] * 4) + struct.pack("<3d", 0.5, 0.7, 0.5) +
             struct.pack("<3d", 0, 0.6, 0.8) + points([(0.5, 0.5, -3), (1.5, 0.5, -3)]) +
             struct.pack("<4d", 0.6, 1.6, 2.1, 0.6) + struct.pack("<6d", -10, 0.33, 55, 15, 1e-4, 1e-6) +
             struct.pack("<Q", 2) + camera(50, 0) + camera(40, 1))
    write("wire", "score.bin", score)
    write("wire", "score_same_mesh.bin", struct.pack("<I", 0x4D4E4A31) + struct.pack("<QB", 77, 0) +
          vec("i", []) + vec("i", []) + points([]) + struct.pack("<6d", 0, 0, 0, 0, 0, 1) + points([]) +
          struct.pack("<4d", 0.6, 1.6, 2.1, 0.6) + struct.pack("<6d", -10, 0.33, 55, 15, 1e-4, 1e-6) +
          struct.pack("<Q", 0))
    write("wire", "energies.bin", struct.pack("<I", 0x4D4E4531) + struct.pack("<Q", 2) +
          struct.pack("<10d", 1, 2, 3, 4, 10, -10, 0, 0, 0, -10))


def main():
    shutil.rmtree(SEEDS, ignore_errors=True)
    ply_seeds()
    ply_binary_seeds()
    obj_seeds()
    off_seeds()
    mlp_seeds()
    json_seeds()
    middlebury_seeds()
    colmap_seeds()
    bundler_seeds()
    colmap_binary_seeds()
    metashape_seeds()
    openmvg_seeds()
    alicevision_seeds()
    wire_seeds()


if __name__ == "__main__":
    main()

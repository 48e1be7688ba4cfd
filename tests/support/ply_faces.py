"""Per-face scalar properties of a PLY as `meshnbv` writes it (binary little
endian or ASCII), in plain Python (no numpy), for the CLI tests.

    from ply_faces import read_face_properties
    names, faces = read_face_properties("pri.ply")  # faces: list of {name: value}
"""
import struct

TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
         "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
         "float": "f", "float32": "f", "double": "d", "float64": "d"}


def _header(data):
    end = data.index(b"end_header\n") + len(b"end_header\n")
    fmt, elements = None, []
    for line in data[:end].decode("ascii").splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property" and words[1] == "list":
            elements[-1][2].append((words[4], TYPES[words[2]], TYPES[words[3]]))
        elif words[0] == "property":
            elements[-1][2].append((words[2], TYPES[words[1]], None))
    return fmt, elements, end


def read_face_properties(path):
    """(the face properties' names in file order, one {name: value} per face);
    list properties are left out."""
    with open(path, "rb") as f:
        data = f.read()
    fmt, elements, at = _header(data)
    if fmt == "ascii":
        tokens = iter(data[at:].split())
    elif fmt != "binary_little_endian":
        raise ValueError(path + ": format " + str(fmt))

    def take(code):
        nonlocal at
        if fmt == "ascii":
            text = next(tokens).decode()
            return float(text) if code in "fd" else int(text)
        value = struct.unpack_from("<" + code, data, at)[0]
        at += struct.calcsize(code)
        return value

    for name, count, props in elements:
        rows = []
        for _ in range(count):
            row = {}
            for prop, code, item in props:
                if item is None:
                    row[prop] = take(code)
                else:
                    for _ in range(take(code)):
                        take(item)
            rows.append(row)
        if name == "face":
            return [p for p, _, item in props if item is None], rows
    raise ValueError(path + ": no face element")

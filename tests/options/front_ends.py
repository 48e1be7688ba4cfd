"""Every option of every front end against the core's option tables (#20).

The tables (`meshnbv options --json`, libs/core/src/options.cpp) give each
option's name, type, default and range. This test lists what each front end
really offers and fails on any difference of name, type, default or range:

- command line: `--help` of pri, suggest, run and loop (flag, type, default;
  booleans as --x / --no-x), and for every number its range: the value just
  outside each end is refused with the table's range in the message, the
  ends themselves and the special values are accepted;
- JSON: the "options" object of `meshnbv pri --json` and of suggestions.json
  holds exactly the table's names, at their defaults;
- MeshLab (when built): the parameters the plugin declares, as
  meshnbv_write_filter_scripts writes them (name, Rich type, default);
  ranges are checked in-process by meshlab/FilterOptions.*;
- VTK (when built): Get/Set<VtkName> of vtkMeshNBVPRIFilter,
  vtkMeshNBVNextBestViewFilter and vtkMeshNBVMissionWriter, their defaults, PrintSelf, and for every
  number the value just outside its range reported as an error naming it.

Usage: front_ends.py --cli MESHNBV --scene SCENE --work DIR
                     [--meshlab-scripts-tool TOOL] [--vtk]
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def text_of(value):
    """The table's text of a default (option_value_text)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value) if isinstance(value, float) else str(value)


def same_number(a, b):
    return float(a) == float(b) or math.isclose(float(a), float(b), rel_tol=1e-6, abs_tol=0.0)


def outside_and_inside(option):
    """Values just outside the range (refused) and at its ends (accepted)."""
    lo, hi = option["min"], option["max"]
    specials = [s["value"] for s in option["specials"]]
    step = 1 if option["type"] == "int" else None
    outside, inside = [], list(specials)

    def nudge(x, direction):
        if step:
            return x + direction * step
        return x + direction * max(abs(x) * 1e-6, 1e-6)

    if lo is not None:
        if option["min_open"]:
            outside.append(lo)
            inside.append(nudge(lo, +1))
        else:
            inside.append(lo)
            below = nudge(lo, -1)
            while below in specials:
                below = nudge(below, -1)
            outside.append(below)
    if hi is not None:
        if option["max_open"]:
            outside.append(hi)
            inside.append(nudge(hi, -1))
        else:
            inside.append(hi)
            outside.append(nudge(hi, +1))
    if not step:
        outside.append(float("nan"))  # ints refuse it as "not a whole number"
    if step:
        inside = [int(x) for x in inside]
        outside = [x if isinstance(x, float) and math.isnan(x) else int(x) for x in outside]
    return outside, inside


def number_text(x):
    if isinstance(x, float) and math.isnan(x):
        return "nan"
    return repr(x) if isinstance(x, float) else str(x)


# ---------------------------------------------------------------- command line


def cli_flags(cli, command):
    """{flag: (negation, type label, default)} from `meshnbv COMMAND --help`."""
    out = {}
    for line in run([cli, command, "--help"]).stdout.splitlines():
        m = re.match(r"^\s+(--[a-z0-9-]+)(,--no-[a-z0-9-]+)?(\{false\})?\s*([A-Za-z|]+)?=?(\S+)?", line)
        if not m:
            continue
        flag, negation, _, label, default = m.groups()
        if negation:  # "--x,--no-x{false}=true": the default follows '='
            d = re.search(r"\}=(\S+)", line)
            default, label = (d.group(1) if d else None), "FLAG"
        out[flag] = (negation, label, default)
    return out


def check_cli(cli, tables, work):
    scene = os.path.join(work, "no_such_scene.json")
    commands = {
        "pri": [("pri", [])],
        "suggest": [("pri", []), ("suggest", [])],
        "run": [("pri", []), ("suggest", []), ("mission", [])],
        "loop": [("pri", []), ("suggest", ["candidates"])],
        "mission": [("mission", [])],
    }
    base = {
        "pri": ["--out", os.path.join(work, "p.ply")],
        "suggest": ["--out", os.path.join(work, "s.json")],
        "run": ["--out", os.path.join(work, "run")],
        "loop": ["--out", os.path.join(work, "loop")],
        "mission": ["--out", os.path.join(work, "mission"), "--suggestions", os.path.join(work, "s.json")],
    }
    checked = 0
    for command, uses in commands.items():
        flags = cli_flags(cli, command)
        for table, skip in uses:
            for o in tables[table]:
                if o["name"] in skip:
                    if o["cli"] in flags:
                        fail(f"{command}: {o['cli']} should not be offered (the command sets it)")
                    continue
                where = f"{command} {o['cli']}"
                if o["cli"] not in flags:
                    fail(f"{where}: missing from --help")
                    continue
                negation, label, default = flags[o["cli"]]
                want_label = {"int": "INT", "real": "REAL", "bool": "FLAG",
                              "choice": "|".join(o.get("choices", []))}[o["type"]]
                if label != want_label:
                    fail(f"{where}: type {label}, table {want_label}")
                if o["type"] == "bool" and negation != ",--no-" + o["cli"][2:]:
                    fail(f"{where}: no --no- form")
                want = text_of(o["default"])
                if default is None or (default != want and not (
                        o["type"] in ("int", "real") and same_number(default, o["default"]))):
                    fail(f"{where}: default {default}, table {want}")
                checked += 1
                # Ranges: refused outside with the table's words, accepted inside.
                if o["type"] in ("int", "real"):
                    outside, inside = outside_and_inside(o)
                    for x in outside:
                        r = run([cli, command, scene, *base[command], o["cli"], number_text(x)])
                        expected = f"{o['cli']} must be {o['range']}"
                        if r.returncode != 1 or expected not in r.stderr:
                            fail(f"{where} {number_text(x)}: expected '{expected}', got "
                                 f"{r.returncode}: {r.stderr.strip()[:200]}")
                    for x in inside:
                        r = run([cli, command, scene, *base[command], o["cli"], number_text(x)])
                        if o["cli"] + " " in r.stderr or o["cli"] + ":" in r.stderr:
                            fail(f"{where} {number_text(x)} (in range) refused: {r.stderr.strip()[:200]}")
                if o["type"] == "choice":
                    r = run([cli, command, scene, *base[command], o["cli"], "no-such-word"])
                    words = o["choices"]
                    expected = f"{o['cli']} must be {', '.join(words[:-1])} or {words[-1]}"
                    if r.returncode != 1 or expected not in r.stderr:
                        fail(f"{where}: a wrong word gives {r.stderr.strip()[:200]}")
    return checked


def check_json(cli, tables, scene, work):
    pri_json = os.path.join(work, "pri.json")
    r = run([cli, "pri", scene, "--out", os.path.join(work, "pri.ply"), "--json", pri_json,
             "--overwrite", "--quiet"])
    if r.returncode != 0:
        fail("pri on the sample scene: " + r.stderr)
        return
    options = json.load(open(pri_json))["options"]
    compare_json("pri --json", options, tables["pri"], extra=set())
    s_json = os.path.join(work, "s.json")
    r = run([cli, "suggest", scene, "--pri", os.path.join(work, "pri.ply"), "--out", s_json,
             "--overwrite", "--quiet", "--directions", "16"])
    if r.returncode != 0:
        fail("suggest on the sample scene: " + r.stderr)
        return
    options = json.load(open(s_json))["options"]
    compare_json("suggestions.json", options, tables["suggest"], extra={"distance_factors"},
                 changed={"directions": 16})


def compare_json(where, options, table, extra, changed=None):
    changed = changed or {}
    names = {o["name"] for o in table}
    if set(options) != names | extra:
        fail(f"{where}: options {sorted(set(options) ^ (names | extra))} differ from the table")
    for o in table:
        want = changed.get(o["name"], o["default"])
        got = options.get(o["name"])
        if o["type"] in ("int", "real"):
            ok = got is not None and same_number(got, want)
        else:
            ok = got == want
        if not ok:
            fail(f"{where}: {o['name']} = {got}, table {want}")


# -------------------------------------------------------------------- MeshLab
RICH = {"int": "RichInt", "real": "RichFloat", "bool": "RichBool", "choice": "RichEnum"}


def check_meshlab(tool, tables, work):
    out = os.path.join(work, "mlx")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    r = run([tool, out])
    if r.returncode != 0:
        fail("meshnbv_write_filter_scripts: " + r.stderr)
        return 0
    filters = {
        "compute_pri.mlx": (tables["pri"], None, {}),
        "suggest_next_view.mlx": (tables["suggest"], None, {"use_face_quality", "add_frustum_layer"}),
        "select_worst_faces.mlx": (tables["suggest"], {"worst_faces"}, {}),
    }
    checked = 0
    for script, (table, only, own) in filters.items():
        params = {p.get("name"): p for p in ET.parse(os.path.join(out, script)).iter("Param")}
        wanted = [o for o in table if only is None or o["name"] in only]
        if set(params) != {o["name"] for o in wanted} | set(own):
            fail(f"MeshLab {script}: parameters {sorted(set(params) ^ ({o['name'] for o in wanted} | set(own)))} "
                 "differ from the table")
        for o in wanted:
            p = params.get(o["name"])
            if p is None:
                continue
            where = f"MeshLab {script} {o['name']}"
            if p.get("type") != RICH[o["type"]]:
                fail(f"{where}: type {p.get('type')}, table {RICH[o['type']]}")
            value = p.get("value")
            if o["type"] == "choice":
                words = [p.get(f"enum_val{i}") for i in range(int(p.get("enum_cardinality")))]
                if words != o["choices"] or words[int(value)] != o["default"]:
                    fail(f"{where}: {words} at {value}, table {o['choices']} at {o['default']}")
            elif o["type"] == "bool":
                if value != text_of(o["default"]):
                    fail(f"{where}: default {value}, table {o['default']}")
            elif not same_number(value, o["default"]):
                fail(f"{where}: default {value}, table {o['default']}")
            if p.get("description") != o["label"]:
                fail(f"{where}: label {p.get('description')!r}, table {o['label']!r}")
            checked += 1
    return checked


# ------------------------------------------------------------------------ VTK
def check_vtk(tables, scene, work):
    from vtkmodules.vtkCommonCore import vtkStringOutputWindow, vtkOutputWindow

    from meshnbv.vtk import (vtkMeshNBVMissionWriter, vtkMeshNBVNextBestViewFilter, vtkMeshNBVPRIFilter,
                             vtkMeshNBVSceneReader)

    # The VTK tests' own error collector.
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "filters"))
    from test_pipeline import watch_errors

    window = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(window)  # errors are collected, not printed
    reader = vtkMeshNBVSceneReader()
    reader.SetFileName(scene)
    pri, nbv = vtkMeshNBVPRIFilter(), vtkMeshNBVNextBestViewFilter()
    for upstream, algorithm in ((reader, pri), (pri, nbv)):  # mesh from upstream, views from the reader
        algorithm.SetInputConnection(upstream.GetOutputPort(0))
        algorithm.SetViewsConnection(reader.GetViewsOutputPort())
    pri.Update()
    if pri.GetOutput().GetCellData().GetArray("PRI") is None:
        fail("VTK: the PRI filter failed on the sample scene: " + window.GetOutput())
        return 0

    # The mission writer: its range errors come when writing.
    mission = vtkMeshNBVMissionWriter()
    mission.SetInputConnection(nbv.GetOutputPort(1))
    mission.SetViewsConnection(reader.GetViewsOutputPort())
    mission.SetMeshConnection(reader.GetOutputPort(0))
    mission.SetOutputDirectory(os.path.join(work, "vtk_mission"))

    checked = 0
    for table, algorithm, klass in (("pri", pri, vtkMeshNBVPRIFilter),
                                    ("suggest", nbv, vtkMeshNBVNextBestViewFilter),
                                    ("mission", mission, vtkMeshNBVMissionWriter)):
        run_it = algorithm.Write if table == "mission" else algorithm.Update
        fresh = klass()
        printed = str(fresh)
        messages = watch_errors(algorithm)
        for o in tables[table]:
            where = f"VTK {klass.__name__}.{o['vtk']}"
            get = getattr(fresh, "Get" + o["vtk"], None)
            set_ = getattr(algorithm, "Set" + o["vtk"], None)
            if get is None or set_ is None:
                fail(f"{where}: no Get/Set")
                continue
            value = get()
            if o["type"] == "choice":
                ok = value == o["choices"].index(o["default"])
                shown = o["default"]
            elif o["type"] == "bool":
                ok = bool(value) == o["default"]
                shown = text_of(o["default"])
            else:
                ok = same_number(value, o["default"])
                shown = text_of(o["default"])
            if not ok:
                fail(f"{where}: default {value}, table {o['default']}")
            if f"{o['vtk']}: {shown}" not in printed:
                fail(f"{where}: PrintSelf lacks '{o['vtk']}: {shown}'")
            checked += 1
            if o["type"] not in ("int", "real"):
                continue
            original = getattr(algorithm, "Get" + o["vtk"])()
            outside, _ = outside_and_inside(o)
            for x in outside:
                if o["type"] == "int" and isinstance(x, float):
                    continue  # NaN has no int property
                del messages[:]
                set_(x)
                run_it()
                expected = f"{o['name']} must be {o['range']}"
                if not any(expected in m for m in messages):
                    fail(f"{where} = {number_text(x)}: expected an error '{expected}', got {messages}")
            set_(original)
            algorithm.Modified()
    return checked


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--meshlab-scripts-tool")
    ap.add_argument("--vtk", action="store_true")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    tables = json.loads(run([a.cli, "options", "--json"]).stdout)
    if len(tables["pri"]) < 9 or len(tables["suggest"]) < 17:
        fail(f"the tables are short: {len(tables['pri'])} PRI and {len(tables['suggest'])} suggest options")
    n = check_cli(a.cli, tables, a.work)
    print(f"command line: {n} option listings checked")
    check_json(a.cli, tables, a.scene, a.work)
    print("JSON: pri.json and suggestions.json options checked")
    if a.meshlab_scripts_tool:
        print(f"MeshLab: {check_meshlab(a.meshlab_scripts_tool, tables, a.work)} parameters checked")
    if a.vtk:
        print(f"VTK: {check_vtk(tables, a.scene, a.work)} properties checked")
    if failures:
        print(f"{len(failures)} difference(s)")
        return 1
    print("every front end matches the option tables")
    return 0


if __name__ == "__main__":
    sys.exit(main())

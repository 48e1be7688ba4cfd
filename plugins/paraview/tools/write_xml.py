"""Writes the MeshNBV plugin's server-manager XML from its template.

The template (plugin/MeshNBV.xml.in) holds the proxies' structure: inputs,
outputs, file names, hints. Each line `<!--@options TABLE@-->` in it becomes
one property per option of that table of `meshnbv options --json`, so that
the panels of Compute PRI and Suggest Next View carry the names (CamelCase,
the VTK filters' setters), defaults, ranges and help of the core's option
tables, as the command line, JSON, VTK and MeshLab do (tests/options).

Usage: write_xml.py TEMPLATE OPTIONS_JSON OUT_XML
"""
import json
import math
import os
import re
import sys
from xml.sax.saxutils import escape, quoteattr


def number(x, integer):
    if integer:
        return str(int(x))
    return repr(float(x))


def documentation(option):
    text = option["help"].rstrip(".")
    if option["type"] in ("int", "real"):
        unit = f" ({option['unit']})" if option.get("unit") else ""
        text += f". Range: {option['range']}{unit}."
    else:
        text += "."
    return f"<Documentation>{escape(text)}</Documentation>"


def range_domain(option):
    """A range domain over the option's range and its special values.

    ParaView's domains are closed intervals without special values: the
    domain spans both (e.g. 0 = automatic below [2, 64] gives [0, 64]) and
    the documentation gives the exact range, which the filter enforces
    (a value outside is an error naming the option).
    """
    integer = option["type"] == "int"
    lo, hi = option["min"], option["max"]
    specials = [s["value"] for s in option["specials"]]
    if specials:
        lo = min([lo] + specials) if lo is not None else None
        hi = max([hi] + specials) if hi is not None else None
    attrs = ""
    if lo is not None and math.isfinite(lo):
        attrs += f' min="{number(lo, integer)}"'
    if hi is not None and math.isfinite(hi):
        attrs += f' max="{number(hi, integer)}"'
    if not attrs:
        return ""
    kind = "IntRangeDomain" if integer else "DoubleRangeDomain"
    return f'<{kind} name="range"{attrs}/>'


def property_xml(option, indent):
    name = option["vtk"]
    # No label: ParaView then shows the name in words ("Samples Per Side")
    # and pvpython spells the property as the VTK filters do.
    head = f'name="{name}" command="Set{name}" number_of_elements="1"'
    t = option["type"]
    if t == "bool":
        body = ['<BooleanDomain name="bool"/>']
        default = "1" if option["default"] else "0"
        kind = "IntVectorProperty"
    elif t == "int":
        body = [range_domain(option)]
        default = str(option["default"])
        kind = "IntVectorProperty"
    elif t == "real":
        body = [range_domain(option)]
        default = repr(float(option["default"]))
        kind = "DoubleVectorProperty"
    elif t == "choice":
        # The filters take a choice as its position in the table's list
        # (vtkMeshNBVPRIFilter::MeasureType, ...::CandidatesType).
        entries = "".join(f'<Entry value="{i}" text={quoteattr(w)}/>'
                          for i, w in enumerate(option["choices"]))
        body = [f'<EnumerationDomain name="enum">{entries}</EnumerationDomain>']
        default = str(option["choices"].index(option["default"]))
        kind = "IntVectorProperty"
    else:
        raise SystemExit(f"write_xml.py: option {option['name']}: unknown type {t}")
    body.append(documentation(option))
    pad = " " * indent
    inner = "".join(f"\n{pad}  {b}" for b in body if b)
    return f'{pad}<{kind} {head} default_values="{default}">{inner}\n{pad}</{kind}>'


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    template_path, options_path, out_path = sys.argv[1:]
    template = open(template_path, encoding="utf-8").read()
    tables = json.load(open(options_path, encoding="utf-8"))
    used = set()

    def replace(m):
        indent, table = len(m.group(1)), m.group(2)
        if table not in tables:
            raise SystemExit(f"write_xml.py: no option table '{table}' (have {', '.join(tables)})")
        used.add(table)
        return "\n".join(property_xml(o, indent) for o in tables[table])

    out = re.sub(r"^( *)<!--@options (\w+)@-->$", replace, template, flags=re.M)
    if "<!--@" in out:
        raise SystemExit("write_xml.py: a placeholder of the template was not replaced")
    tmp = out_path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(out)
    os.replace(tmp, out_path)


if __name__ == "__main__":
    main()

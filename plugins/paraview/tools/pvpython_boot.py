"""Runs a script in pvpython with ParaView's Python modules first on the path.

pvpython puts the dist-packages folder next to its libraries
(/usr/lib/python3/dist-packages) first on sys.path; there, Debian's
python3-vtk9 holds VTK 9.1's `vtkmodules`, which crash ParaView. The folder
of the unpacked python3-paraview ($MESHNBV_PARAVIEW_PYTHONPATH) goes before
it, then the script runs as __main__ with its own arguments.
"""
import os
import runpy
import sys

first = os.environ["MESHNBV_PARAVIEW_PYTHONPATH"]
sys.path[:] = [first] + [p for p in sys.path if p and os.path.realpath(p) != os.path.realpath(first)]
if len(sys.argv) < 2:
    sys.exit("pvpython: no script given")
script = sys.argv[1]
sys.argv = sys.argv[1:]
sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
runpy.run_path(script, run_name="__main__")

#!/usr/bin/env bash
# Checks that built libraries stay inside their component boundaries
# (issue #20, docs/design.md): the hosts that compute (the MeshLab plugin,
# the VTK Filters module) and meshnbv::core must not link, directly or
# through another library, CGAL (gmp, mpfr), Boost.Graph, pugixml, OpenMesh
# or the other MeshNBV components; nor carry their code (symbols).
# Usage: check_links.sh LIBRARY...
set -uo pipefail
status=0
fail() { echo "FAIL: $*"; status=1; }
# Needed directly (readelf): CGAL's number types (gmp, mpfr) count here.
forbidden_direct='libpugixml|libgmp|libmpfr|libOpenMesh|libtinyobjloader|libmeshnbv_(io|synth|eval|report)'
# Anywhere in the closure: gmp is not listed, because OpenCV's imgcodecs
# reaches it through GDAL and GnuTLS, which has nothing to do with CGAL.
forbidden_closure='libpugixml|libmpfr|libOpenMesh|libtinyobjloader|libmeshnbv_(io|synth|eval|report)'
forbidden_symbols='CGAL::|boost::|pugi::|OpenMesh::|tinyobj::'
for lib in "$@"; do
  [ -f "$lib" ] || { fail "$lib: no such library"; continue; }
  name=$(basename "$lib")
  needed=$(readelf -d "$lib" | grep NEEDED)
  bad=$(grep -E -o "($forbidden_direct)[^] ]*" <<<"$needed" | sort -u | tr '\n' ' ')
  [ -z "$bad" ] || fail "$name needs $bad"
  # The whole closure of shared objects the dynamic loader would map.
  closure=$(ldd "$lib" 2>&1) || { fail "$name: ldd failed: $closure"; continue; }
  bad=$(grep -E -o "($forbidden_closure)[^ ]*" <<<"$closure" | sort -u | tr '\n' ' ')
  [ -z "$bad" ] || fail "$name links $bad"
  # Code from those libraries compiled in (header-only CGAL/Boost included):
  # any symbol, defined or not, of their namespaces.
  symbols=$( (nm -C "$lib" 2>/dev/null; nm -C -D "$lib" 2>/dev/null) | grep -E -o "($forbidden_symbols)[A-Za-z_]*" | sort -u | head -5 | tr '\n' ' ')
  [ -z "$symbols" ] || fail "$name carries symbols of $symbols"
  # The check itself must see something: a library with no symbols at all
  # would pass vacuously.
  count=$(nm -D --defined-only "$lib" 2>/dev/null | wc -l)
  [ "$count" -gt 0 ] || fail "$name: no dynamic symbols (is it a shared library?)"
  [ $status -eq 0 ] && echo "ok: $name ($count exported symbols; closure: $(grep -c '=>' <<<"$closure") libraries)"
done
exit $status

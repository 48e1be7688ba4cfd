#!/usr/bin/env bash
# A private MeshLab prefix that loads this build's plugin without touching
# system folders (meshlab and meshlabserver have no plugin-folder option:
# they load <binary dir>/../<libdir>/meshlab/plugins).
#
#   make-meshlab-prefix.sh PREFIX MESHLAB_LIB_DIR PLUGIN [PLUGIN...]
#
# PREFIX/bin/meshlab, PREFIX/bin/meshlabserver  copies (a symlink would make
#                                               them look next to the target)
# PREFIX/<libdir>/meshlab/libmeshlab-common.so  symlink to the system's
# PREFIX/<libdir>/meshlab/plugins/              symlinks to the system's
#                                               plugins and to PLUGIN...
set -euo pipefail
PREFIX=${1:?usage: make-meshlab-prefix.sh PREFIX MESHLAB_LIB_DIR PLUGIN...}
LIBDIR=${2:?missing MESHLAB_LIB_DIR}
shift 2
case "$LIBDIR" in                        # /usr/lib/x86_64-linux-gnu/meshlab -> /usr
  */lib/*/meshlab) root=${LIBDIR%/lib/*/meshlab} ;;
  */lib/meshlab) root=${LIBDIR%/lib/meshlab} ;;
  *) echo "make-meshlab-prefix: unexpected MeshLab library folder $LIBDIR" >&2; exit 1 ;;
esac
rel=${LIBDIR#"$root"/}                   # lib/x86_64-linux-gnu/meshlab

rm -rf "$PREFIX.tmp"
mkdir -p "$PREFIX.tmp/bin" "$PREFIX.tmp/$rel/plugins"
for exe in meshlabserver meshlab; do
  if [ -x "$root/bin/$exe" ]; then cp "$root/bin/$exe" "$PREFIX.tmp/bin/$exe"; fi
done
ln -s "$LIBDIR/libmeshlab-common.so" "$PREFIX.tmp/$rel/libmeshlab-common.so"
for p in "$LIBDIR"/plugins/*.so; do
  ln -s "$p" "$PREFIX.tmp/$rel/plugins/$(basename "$p")"
done
for p in "$@"; do
  ln -sf "$(realpath "$p")" "$PREFIX.tmp/$rel/plugins/$(basename "$p")"
done
rm -rf "$PREFIX"
mv "$PREFIX.tmp" "$PREFIX"

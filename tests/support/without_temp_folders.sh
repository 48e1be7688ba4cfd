#!/usr/bin/env bash
# Runs a command with no writable temporary folder, so that a program that
# writes a temporary file (mkstemp, std::filesystem::temp_directory_path,
# QTemporaryDir/QTemporaryFile, ~/.cache) fails:
#   without_temp_folders.sh FOLDER COMMAND [ARGS...]
# - TMPDIR, TMP, TEMP, HOME and the XDG cache/config/data folders all point
#   to FOLDER, made read-only (0555).
# - Where a private mount namespace is allowed (unshare -m; root on the CI
#   machines), /tmp and /var/tmp are also read-only for the command (bind
#   mounts visible to it only), so a hard-coded /tmp fails too. The build
#   tree the test runs in (the nearest folder above the working directory
#   that holds CMakeCache.txt, else the working directory) stays writable
#   even when it lies under /tmp, as a clean clone's may.
# - Root ignores permission bits, so as root the command runs without
#   CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH and CAP_FOWNER (setpriv).
# Before the command starts, writes into FOLDER (and /tmp when it was made
# read-only) are tried: if one succeeds the script fails (exit 97) rather
# than test nothing.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 FOLDER COMMAND [ARGS...]" >&2; exit 2; }
if [ -z "${MESHNBV_IN_TMP_NAMESPACE:-}" ]; then
  mkdir -p "$1"
  chmod 0555 "$1"
fi
if [ -z "${MESHNBV_IN_TMP_NAMESPACE:-}" ] && unshare -m true 2> /dev/null; then
  export MESHNBV_IN_TMP_NAMESPACE=1
  build=$PWD
  while [ "$build" != / ] && [ ! -f "$build/CMakeCache.txt" ]; do build=$(dirname "$build"); done
  [ -f "$build/CMakeCache.txt" ] || build=$PWD
  export MESHNBV_KEEP_WRITABLE=$build
  # The build tree is bound onto itself after /tmp is made read-only: the new
  # mount is writable (a bind mount has its own flags).
  exec unshare -m --propagation private -- bash -c \
    'mount --bind -o ro /tmp /tmp && mount --bind -o ro /var/tmp /var/tmp &&
     case "$MESHNBV_KEEP_WRITABLE" in /tmp/*|/var/tmp/*) mount --bind "$MESHNBV_KEEP_WRITABLE" "$MESHNBV_KEEP_WRITABLE" &&
       mount -o remount,bind,rw "$MESHNBV_KEEP_WRITABLE";; esac &&
     exec "$0" "$@"' "$0" "$@"
fi
folder=$1
shift
export TMPDIR=$folder TMP=$folder TEMP=$folder TEMPDIR=$folder HOME=$folder
export XDG_CACHE_HOME=$folder/.cache XDG_CONFIG_HOME=$folder/.config XDG_DATA_HOME=$folder/.local/share
unprivileged=()
if [ "$(id -u)" = 0 ]; then
  unprivileged=(setpriv --bounding-set -dac_override,-dac_read_search,-fowner --inh-caps -all --)
fi
probes=("$folder")
[ -n "${MESHNBV_IN_TMP_NAMESPACE:-}" ] && probes+=(/tmp /var/tmp)
for dir in "${probes[@]}"; do
  probe=$dir/meshnbv-probe.$$
  if "${unprivileged[@]}" sh -c ': > "$1" || exit 1; rm -f "$1"' sh "$probe" 2> /dev/null; then
    echo "$0: $dir is still writable: cannot run without temporary folders" >&2
    exit 97
  fi
done
exec "${unprivileged[@]}" "$@"

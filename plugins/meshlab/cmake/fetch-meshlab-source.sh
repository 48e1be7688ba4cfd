#!/usr/bin/env bash
# Gets the plugin-facing headers of MeshLab (src/common and vcglib) from
# Debian's source package of the installed `meshlab`, so that the plugin is
# compiled against exactly the sources Debian built its binaries from.
#
#   fetch-meshlab-source.sh DEST CACHE
#
# DEST   folder that receives src/common and vcglib/ (the build folder's copy: the primary cache).
# CACHE  folder keeping the downloaded orig tarball and .dsc across build
#        folders (default $HOME/.cache/meshnbv/meshlab-source); CI starts
#        from a fresh build folder each time.
#
# Fast path: DEST/.complete names the version -> nothing to do. Else the
# tarball is taken from CACHE when its SHA-256 matches the .dsc; else it is
# downloaded with `apt-get source --download-only` (signed by Debian's
# archive keys). When apt has no deb-src entry, one is added for Debian's
# own archive (a copy of the `deb` entries, Types: deb-src) in
# /etc/apt/sources.list.d/meshnbv-deb-src.sources and apt-get update runs. Needs root (or sudo) for that step only.
set -euo pipefail

DEST=${1:?usage: fetch-meshlab-source.sh DEST [CACHE]}
CACHE=${2:-${HOME:-/tmp}/.cache/meshnbv/meshlab-source}
say() { echo "meshlab-source: $*"; }
die() { echo "meshlab-source: error: $*" >&2; exit 1; }

version=$(dpkg-query -W -f='${Version}' meshlab 2>/dev/null) || true
[ -n "$version" ] || die "the Debian package 'meshlab' is not installed (scripts/install-deps.sh installs it)"
upstream=${version#*:}
upstream=${upstream%-*}          # 2020.09+dfsg1
case "$upstream" in
  2020.09*) ;;
  *) die "meshlab $version is installed; this plugin is written for MeshLab 2020.09" ;;
esac

if [ -f "$DEST/.complete" ] && [ "$(cat "$DEST/.complete")" = "$version" ]; then
  exit 0
fi

tarball="meshlab_${upstream}.orig.tar.xz"
dsc="meshlab_${version#*:}.dsc"

# SHA-256 of the tarball as listed in the .dsc (Checksums-Sha256 section).
expected_sha() {
  awk -v f="$tarball" '/^Checksums-Sha256:/ {s=1; next} /^[^ ]/ {s=0} s && $3 == f {print $1}' "$1"
}
cache_ok() {
  [ -f "$CACHE/$tarball" ] && [ -f "$CACHE/$dsc" ] || return 1
  local want have
  want=$(expected_sha "$CACHE/$dsc")
  have=$(sha256sum "$CACHE/$tarball" | cut -d' ' -f1)
  [ -n "$want" ] && [ "$want" = "$have" ]
}

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then sudo "$@"
  else die "need root (or password-less sudo) to run: $*
  Alternatively put $tarball and $dsc into $CACHE by hand."
  fi
}

# (Not `| grep -q`: with pipefail, grep's early exit fails the pipeline.)
has_source() {
  local out
  out=$(apt-cache showsrc meshlab 2>/dev/null) || return 1
  grep -qx "Version: $version" <<<"$out"
}

# Adds a deb-src entry for Debian's archive when apt has none for meshlab.
ensure_deb_src() {
  if has_source; then return 0; fi
  local list=/etc/apt/sources.list.d/meshnbv-deb-src.sources
  if [ ! -f "$list" ]; then
    local entries=""
    if [ -f /etc/apt/sources.list.d/debian.sources ]; then
      # deb822: copy every stanza that has Types: deb, as Types: deb-src.
      entries=$(awk 'BEGIN{RS=""; ORS="\n\n"} /(^|\n)Types:[^\n]*deb([ \n]|$)/ {
                       gsub(/Types:[^\n]*/, "Types: deb-src"); print }' /etc/apt/sources.list.d/debian.sources)
    elif [ -f /etc/apt/sources.list ]; then
      # One-line format: deb URI SUITE COMPONENTS... -> a deb822 stanza each.
      entries=$(awk '$1 == "deb" { i = 2; if ($2 ~ /^\[/) { while ($i !~ /\]$/) i++; i++ }
                     uri = $i; suite = $(i+1); comps = ""; for (j = i+2; j <= NF; j++) comps = comps " " $j;
                     printf "Types: deb-src\nURIs: %s\nSuites: %s\nComponents:%s\n\n", uri, suite, comps }' /etc/apt/sources.list)
    fi
    [ -n "$entries" ] || die "no Debian 'deb' entry found in /etc/apt to derive a deb-src entry from"
    say "adding $list (deb-src entries for Debian's archive)"
    printf '# Added by MeshNBV (plugins/meshlab/cmake/fetch-meshlab-source.sh) to get MeshLab headers.\n%s' \
      "$entries" > "$CACHE/deb-src.sources.new"
    as_root install -m 644 "$CACHE/deb-src.sources.new" "$list"
    rm -f "$CACHE/deb-src.sources.new"
  fi
  say "apt-get update"
  as_root apt-get -o DPkg::Lock::Timeout=600 update -qq >/dev/null
  has_source || die "apt still knows no source package meshlab=${version#*:} after adding $list"
}

mkdir -p "$CACHE"
if ! cache_ok; then
  ensure_deb_src
  work=$(mktemp -d "$CACHE/download.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  say "downloading Debian's source package meshlab=${version#*:} (about 11 MB)"
  # As root, apt downloads as the _apt user, which cannot enter a root-only
  # $HOME: download as root instead (the files are still checked against
  # the signed Sources index).
  sandbox=()
  [ "$(id -u)" -ne 0 ] || sandbox=(-o APT::Sandbox::User=root)
  (cd "$work" && apt-get "${sandbox[@]}" source --download-only -qq "meshlab=${version#*:}") ||
    die "apt-get source --download-only meshlab=${version#*:} failed"
  mv -f "$work/$tarball" "$work/$dsc" "$CACHE/"
  cache_ok || die "$tarball does not match the SHA-256 in $dsc"
fi

say "extracting headers into $DEST"
rm -rf "$DEST.tmp"
mkdir -p "$DEST.tmp"
# Only what a filter plugin includes: src/common and vcglib
# (Debian removed vcglib/eigenlib: Eigen comes from /usr/include/eigen3).
tar -xJf "$CACHE/$tarball" -C "$DEST.tmp" --strip-components=1 --wildcards \
  '*/src/common/*' '*/vcglib/*' ||
  die "could not extract $CACHE/$tarball"
[ -f "$DEST.tmp/src/common/interfaces.h" ] || die "$tarball has no src/common/interfaces.h"
rm -rf "$DEST"
mv "$DEST.tmp" "$DEST"
echo "$version" > "$DEST/.complete"
say "MeshLab $version headers ready"

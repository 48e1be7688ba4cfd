# Shared by the CLI tests: sourced, not run.
set -u
MESHNBV=$1
ROOT=$2
TMP=$3
SHARED=$4
rm -rf "$TMP"
mkdir -p "$TMP"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# expect_error "fragment" command...: non-zero exit, one line on stderr holding
# fragment (besides the reader's "warning: ..." lines, which are not errors).
expect_error() {
  local fragment=$1; shift
  local err
  if err=$("$@" 2>&1 >/dev/null); then fail "expected failure: $*"; return; fi
  err=$(printf '%s\n' "$err" | grep -av '^warning: ')
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "expected one line of error, got: $err"
  case "$err" in *"$fragment"*) ;; *) fail "error '$err' lacks '$fragment'";; esac
}
finish() {
  if [ "$failures" -ne 0 ]; then echo "$failures failure(s)"; exit 1; fi
  echo "all checks passed"
}

# Extreme option values (issue #20): every numeric flag of pri, suggest,
# run, loop, synth, evaluate and mission -- found in their --help (INT, UINT, FLOAT, REAL,
# BOOLEAN), so flags added later are covered -- and the number-list flags,
# with negative, zero, tiny, huge, beyond-int, NaN and infinite values. Each
# run must end with exit code 0, or exit code 1 and one line
# "meshnbv: error: ..." on stderr; never a signal, an abort, an uncaught
# exception ("internal error", "terminate"), a sanitizer report or a hang
# (timeout). A value a check refuses must be named with its range.
source "$(dirname "$0")/lib.bash"
S=$ROOT/sample_projects/building/project.mlp
# MESHNBV_EXTREME_VALUES (space-separated) replaces the list: the sanitizer
# step runs a subset (scripts/test-sanitizers.sh).
if [ -n "${MESHNBV_EXTREME_VALUES:-}" ]; then
  read -r -a VALUES <<<"$MESHNBV_EXTREME_VALUES"
else
  VALUES=(-1 0 1e-308 2147483648 99999999999999999999 1e308 -1e308 nan inf -inf)
fi
LIMIT=${MESHNBV_EXTREME_TIMEOUT:-300}
runs=0 successes=0

# survives label command...: the contract above.
survives() {
  local label=$1; shift
  runs=$((runs + 1))
  local start=${EPOCHREALTIME/[.,]/}
  timeout -k 10 "$LIMIT" "$@" >"$TMP/out.txt" 2>"$TMP/err.txt"
  local rc=$? err
  err=$(cat "$TMP/err.txt")
  # Every outcome, for reading: label, exit code, milliseconds, message.
  local now=${EPOCHREALTIME/[.,]/}
  printf '%s\t%s\t%s\t%s\n' "$label" "$rc" "$(((now - start) / 1000))" \
    "$(head -c 300 "$TMP/err.txt")" >>"$TMP/outcomes.tsv"
  case "$err" in
    *terminate*|*Aborted*|*Assertion*|*Segmentation*|*"core dumped"*|*Sanitizer*|*"runtime error"*|*"internal error"*)
      fail "$label: crash or uncaught exception: $(head -c 400 "$TMP/err.txt")"; return;;
  esac
  if [ $rc -eq 0 ]; then
    successes=$((successes + 1))
    [ -z "$err" ] || fail "$label: success with output on stderr (--quiet): $(head -c 300 "$TMP/err.txt")"
  elif [ $rc -eq 1 ]; then
    [ "$(wc -l <"$TMP/err.txt")" -eq 1 ] || fail "$label: expected one line of error, got: $(head -c 400 "$TMP/err.txt")"
    case "$err" in "meshnbv: error: "*) ;; *) fail "$label: error without 'meshnbv: error: ': $err";; esac
  elif [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    fail "$label: no answer within $LIMIT s (hang)"
  else
    fail "$label: exit code $rc (a signal or an unexpected code): $(head -c 300 "$TMP/err.txt")"
  fi
}

# The numeric flags of a subcommand, from its --help (first name of each).
numeric_flags() {
  "$MESHNBV" "$1" --help | sed -nE 's/^ +(--[a-z0-9-]+)(,--[a-z0-9-]+)* +(INT|UINT|FLOAT|REAL|BOOLEAN)\b.*/\1/p'
}

# vary label flag command...: the command with flag=value for every value
# (the flag and its value taken out of the command first, if there).
vary() {
  local label=$1 flag=$2; shift 2
  local args=() skip=0 a
  for a in "$@"; do
    if [ $skip = 1 ]; then skip=0; continue; fi
    if [ "$a" = "$flag" ]; then skip=1; continue; fi
    case "$a" in "$flag="*) continue;; esac
    args+=("$a")
  done
  local v
  for v in "${VALUES[@]}"; do
    survives "$label $flag=$v" "${args[@]}" "$flag=$v"
  done
}

# each_value command-name command...: every numeric flag x every value
# (but those in $EXCEPT, space-separated).
each_value() {
  local name=$1; shift
  local flags flag
  flags=$(numeric_flags "$name")
  [ -n "$flags" ] || fail "no numeric flag found in '$name --help'"
  for flag in $flags; do
    case " ${EXCEPT:-} " in *" $flag "*) continue;; esac
    vary "$name" "$flag" "$@"
  done
}

# A PRI file for suggest (so that its runs do not all compute the PRI).
"$MESHNBV" pri "$S" --out "$TMP/pri.ply" --quiet >/dev/null || fail "pri"
# A tiny synthetic project for run (its report renders views at its size).
"$MESHNBV" synth building --out "$TMP/small" --views 4 --size 64x48 --samples-per-pixel 1 --quiet >/dev/null \
  || fail "synth small"
SMALL=$TMP/small/project.mlp

# pri: everything computes (0.1 s on the sample).
each_value pri "$MESHNBV" pri "$S" --out "$TMP/pri_x.ply" --json "$TMP/pri_x.json" --overwrite --quiet
# suggest: sampled mode, and refined mode (where --refine-* matter).
each_value suggest "$MESHNBV" suggest "$S" --pri "$TMP/pri.ply" --out "$TMP/s.json" --overwrite --quiet
for flag in --refine-best --refine-iterations --top; do
  vary "suggest refined" "$flag" "$MESHNBV" suggest "$S" --pri "$TMP/pri.ply" --candidates refined \
    --refine-best 2 --refine-iterations 20 --out "$TMP/s.json" --overwrite --quiet
done
# run: PRI, suggestions and the report; its mission flags are mission's
# (below), where a mission is planned. MESHNBV_EXTREME_OWN_FLAGS=1 (the
# sanitizer step) also leaves out, for run and loop, the flags pri and
# suggest vary above: the same option tables and checks. There each run
# that computes takes 15 s (1.7 s in Release), and each loop run that
# stops at its missing dataset 0.5 s (0.15 s).
RUN_EXCEPT=$(numeric_flags mission | tr '\n' ' ')
LOOP_EXCEPT=
if [ "${MESHNBV_EXTREME_OWN_FLAGS:-0}" = 1 ]; then
  LOOP_EXCEPT="$(numeric_flags pri | tr '\n' ' ') $(numeric_flags suggest | tr '\n' ' ')"
  RUN_EXCEPT="$RUN_EXCEPT $LOOP_EXCEPT"
fi
EXCEPT=$RUN_EXCEPT each_value run "$MESHNBV" run "$SMALL" --out "$TMP/run" --overwrite --quiet
# mission: two suggestions placed by a georeference file.
"$MESHNBV" suggest "$S" --pri "$TMP/pri.ply" --top 2 --out "$TMP/s2.json" --quiet >/dev/null || fail "suggest for mission"
echo '{"crs": "EPSG:32632", "transform": [1,0,0,500000, 0,1,0,5000000, 0,0,1,100, 0,0,0,1]}' > "$TMP/georef.json"
each_value mission "$MESHNBV" mission "$S" --suggestions "$TMP/s2.json" --georef "$TMP/georef.json" \
  --out "$TMP/mission" --overwrite
# loop: every check comes before COLMAP is run; the dataset does not exist,
# so a run whose options pass ends at "scene not found" (or "COLMAP not found").
EXCEPT=$LOOP_EXCEPT each_value loop "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/loop" --cache "$TMP/cache" --quiet
# synth: two tiny views.
each_value synth "$MESHNBV" synth building --out "$TMP/synth" --overwrite --views 2 --size 16x16 \
  --samples-per-pixel 1 --quiet
# evaluate: a unit square against itself.
/usr/bin/python3 - "$TMP" <<'PY' || fail "prepare plane"
import sys
with open(sys.argv[1] + "/plane.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n")
    f.write("element face 2\nproperty list uchar int vertex_indices\nend_header\n")
    f.write("0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
PY
each_value evaluate "$MESHNBV" evaluate "$TMP/plane.ply" "$TMP/plane.ply" --json "$TMP/e.json" --overwrite

# Number lists.
for b in "1e308,0,1" "-1,0,1" "nan,0,1" "99999999999,0,1" "0.5,1,2" "0,1" "0,0,0" ""; do
  survives "loop --bootstrap-views=$b" "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/loop" --quiet \
    "--bootstrap-views=$b"
done
for t in "1e308" "nan" "-1" "0" "1e-308" "inf" "1,-inf" "1e-308,1e308"; do
  survives "evaluate --thresholds=$t" "$MESHNBV" evaluate "$TMP/plane.ply" "$TMP/plane.ply" "--thresholds=$t"
  survives "loop --thresholds=$t" "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/loop" --quiet "--thresholds=$t"
done
for p in "0" "100" "1e308" "nan" "-1" "1e-308" "50,inf"; do
  survives "evaluate --percentiles=$p" "$MESHNBV" evaluate "$TMP/plane.ply" "$TMP/plane.ply" "--percentiles=$p"
  survives "loop --percentiles=$p" "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/loop" --quiet "--percentiles=$p"
done
for size in 0x0 -1x-1 100000x100000 2147483648x16 1e308x16 nanxnan 16x99999 16x16 8192x1; do
  survives "synth --size=$size" "$MESHNBV" synth building --out "$TMP/synth" --overwrite --views 2 \
    --samples-per-pixel 1 --quiet "--size=$size"
done
for d in noise:1e308 noise:-1 dent:nan hole:0:1e308 hole:0:1 decimate:0.999999 decimate:0.99999999 bump:1:1 \
         noise:1:1e-308 dent:1e-308:1e-308; do
  survives "synth --degrade=$d" "$MESHNBV" synth building --out "$TMP/synth" --overwrite --views 2 --size 16x16 \
    --samples-per-pixel 1 --quiet "--degrade=$d"
done

# Out-of-range values are named with their range.
expect_error "--samples-per-side must be 0 (automatic) or in [2, 64], got 1000" \
  "$MESHNBV" pri "$S" --out "$TMP/p.ply" --samples-per-side 1000
expect_error "--threads must be 0 (all cores) or in [1, 1024], got -1" "$MESHNBV" pri "$S" --out "$TMP/p.ply" --threads -1
expect_error "--edge-margin must be in [0, 16] pixels, got nan" "$MESHNBV" pri "$S" --out "$TMP/p.ply" --edge-margin nan
expect_error "--incidence-sigma must be in [0.1, 180] degrees, got 0" \
  "$MESHNBV" suggest "$S" --pri "$TMP/pri.ply" --out "$TMP/s2.json" --incidence-sigma 0
expect_error "top must be in [1, 100], got 2147483647" \
  "$MESHNBV" suggest "$S" --pri "$TMP/pri.ply" --out "$TMP/s2.json" --top 2147483647
expect_error "directions must be in [1, 65536], got 100000000" \
  "$MESHNBV" run "$SMALL" --out "$TMP/r2" --directions 100000000
expect_error "--weight-occlusion must be in [0, 1000], got 1e+308" \
  "$MESHNBV" run "$SMALL" --out "$TMP/r2" --weight-occlusion 1e308
expect_error "views must be in [2, 1000], got 1000000000" "$MESHNBV" synth city --out "$TMP/s3" --views 1000000000
expect_error "image width must be in [16, 8192] pixels, got 100000" \
  "$MESHNBV" synth city --out "$TMP/s3" --size 100000x100000
expect_error "edge length must be 0 (the scene's default, 0.8) or in [0.2, 100] metres for 'city', got 1e-09" \
  "$MESHNBV" synth city --out "$TMP/s3" --edge-length 1e-9
expect_error "strength is a share of the bounding-box diagonal and must be in [0, 1], got 1e+300" \
  "$MESHNBV" synth city --out "$TMP/s3" --degrade noise:1e300
expect_error "loop bootstrap must be in [2, 1000] (at least 2 views), got 1000000" \
  "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/l2" --bootstrap 1000000
expect_error "the degradations removed every face" "$MESHNBV" synth building --out "$TMP/s4" --views 2 --size 16x16 \
  --degrade hole:0:1
expect_error "poisson depth must be in [4, 14], got 99" "$MESHNBV" loop "$TMP/no_dataset" --out "$TMP/l2" --poisson-depth 99
echo "$runs runs, $successes succeeded"
[ "$successes" -gt 20 ] || fail "only $successes of $runs runs succeeded: the base commands may be broken"
finish

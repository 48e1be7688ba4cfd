# meshnbv-mpi (MPI build): the same outputs as meshnbv, bit for bit, on 1, 2
# and 4 ranks (oversubscribed) for the sample project and a 215k-face
# scene; incremental PRI through it; a rank's error ends the job with one
# line and no output file.
source "$(dirname "$0")/lib.bash"
MPI="$(dirname "$MESHNBV")/meshnbv-mpi"
[ -x "$MPI" ] || { echo "FAIL: $MPI not built (configure with -DMESHNBV_BUILD_MPI=ON)"; exit 1; }
# Open MPI refuses root unless told; CI containers run as root.
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
run_mpi() { local n=$1; shift; mpirun -q --oversubscribe -np "$n" "$MPI" "$@"; }
S="$ROOT/sample_projects/building/project.mlp"

"$MESHNBV" pri "$S" --out "$TMP/one.ply" --quiet >/dev/null || fail "meshnbv pri"
for n in 1 2 4; do
  err=$(run_mpi $n pri "$S" --out "$TMP/np$n.ply" --progress none 2>&1 >/dev/null) || fail "np $n: $err"
  cmp -s "$TMP/one.ply" "$TMP/np$n.ply" || fail "np $n: PLY differs from meshnbv's"
done
# The per-rank line: every rank took tiles and decoded only its images.
err=$(run_mpi 2 pri "$S" --out "$TMP/np2b.ply" --progress json 2>&1 >/dev/null) || fail "np 2 json: $err"
grep -q '^meshnbv-mpi: PRI on 2 ranks: rank 0 [1-9][0-9]* tiles, .* threads; rank 1 [1-9][0-9]* tiles, .* threads$' <<<"$err" ||
  fail "per-rank line: $err"
grep -q '"stage": "pri"' <<<"$err" || fail "no progress lines: $err"
# Other measures and options travel to the ranks.
"$MESHNBV" pri "$S" --measure offset --max-views-per-face 4 --out "$TMP/off1.ply" --quiet >/dev/null || fail "offset"
run_mpi 2 pri "$S" --measure offset --max-views-per-face 4 --out "$TMP/off2.ply" --quiet >/dev/null || fail "mpi offset"
cmp -s "$TMP/off1.ply" "$TMP/off2.ply" || fail "offset: PLY differs"

# A 215k-face scene (8 views of 320x240). MESHNBV_MPI_LARGE_SCENE=0 (the
# sanitizer step, where it took over half of this test) leaves it out: the
# same code as the sample's runs above, on more tiles.
if [ "${MESHNBV_MPI_LARGE_SCENE:-1}" = 1 ]; then
  "$MESHNBV" synth building --views 8 --size 320x240 --edge-length 0.075 --out "$TMP/big" --quiet >/dev/null ||
    fail "synth big"
  "$MESHNBV" pri "$TMP/big/project.mlp" --out "$TMP/big1.ply" --quiet | grep -q "faces 215684:" || fail "big pri"
  run_mpi 2 pri "$TMP/big/project.mlp" --out "$TMP/big2.ply" --quiet >/dev/null || fail "big mpi"
  cmp -s "$TMP/big1.ply" "$TMP/big2.ply" || fail "215k faces: PLY differs"
fi

# Incremental through meshnbv-mpi: a view added, the rest reused.
/usr/bin/python3 - "$ROOT/sample_projects/building/scene.json" "$TMP/eleven.json" <<'PY' || fail "eleven views"
import json, os, sys
s = json.load(open(sys.argv[1]))
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for key in ("mesh",):
    s[key] = os.path.join(base, s[key])
for v in s["views"]:
    v["image"] = os.path.join(base, v["image"])
s["views"] = s["views"][:11]
json.dump(s, open(sys.argv[2], "w"))
PY
"$MESHNBV" pri "$TMP/eleven.json" --out "$TMP/eleven.ply" --quiet >/dev/null || fail "eleven pri"
out=$(run_mpi 2 pri "$S" --previous "$TMP/eleven.ply" --out "$TMP/inc.ply" --quiet) || fail "mpi incremental"
grep -q "incremental: recomputed [1-9][0-9]* of 14188 faces" <<<"$out" || fail "incremental line: $out"
cmp -s "$TMP/one.ply" "$TMP/inc.ply" || fail "incremental PLY differs from a full computation"

# run: the same PRI mesh as meshnbv run.
"$MESHNBV" run "$S" --out "$TMP/run1" --quiet >/dev/null || fail "meshnbv run"
run_mpi 2 run "$S" --out "$TMP/run2" --quiet >/dev/null || fail "mpi run"
cmp -s "$TMP/run1/pri.ply" "$TMP/run2/pri.ply" || fail "run: pri.ply differs"
/usr/bin/python3 - "$TMP/run1/suggestions.json" "$TMP/run2/suggestions.json" <<'PY' || fail "run: suggestions differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
for s in (a, b):
    s.pop("seconds", None)  # the time taken
assert a == b, "suggestions differ"
PY

# suggest: the candidates scored on 3 ranks, the same suggestions (sampled,
# refined, given).
for mode in sampled refined given; do
  args=("$S" --candidates $mode)
  # given: the 12 views of the sample are the candidates of its first 11.
  [ $mode = given ] && args=("$TMP/eleven.json" --candidates given --candidates-from "$S")
  "$MESHNBV" suggest "${args[@]}" --out "$TMP/s1_$mode.json" --quiet >/dev/null || fail "suggest $mode"
  run_mpi 3 suggest "${args[@]}" --out "$TMP/s3_$mode.json" --quiet >/dev/null || fail "mpi suggest $mode"
  /usr/bin/python3 - "$TMP/s1_$mode.json" "$TMP/s3_$mode.json" <<'PY' || fail "suggest $mode: suggestions differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
for s in (a, b):
    s.pop("seconds", None)
assert a == b and a["suggestions"], "suggestions differ"
PY
done

# A rank that cannot decode an image: one line naming the rank, no output.
cp -r "$ROOT/sample_projects/building" "$TMP/bad"
echo "not a png" > "$TMP/bad/images/view_006.png"
expect_error "does not decode" run_mpi 2 pri "$TMP/bad/project.mlp" --out "$TMP/bad.ply" --quiet
err=$(run_mpi 2 pri "$TMP/bad/project.mlp" --out "$TMP/bad.ply" --quiet 2>&1 >/dev/null)
grep -q '^meshnbv-mpi: error: rank [01]: .*view_006.png' <<<"$err" || fail "error names no rank: $err"
[ ! -e "$TMP/bad.ply" ] || fail "a partial output was left"
ls "$TMP" | grep -q '\.tmp' && fail "temporary files left: $(ls "$TMP")"
# Bad arguments end every rank.
expect_error "run with --help" run_mpi 2 pri --no-such-flag
finish

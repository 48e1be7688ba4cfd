# Fixture of the VTK tests: a small synthetic project made by the CLI
# (building, 8 orbit views at 320x240) and the CLI's PRI for three option
# sets, which the tests compare with the filters.
# -DMESHNBV=<meshnbv binary> -DOUT=<folder>
file(REMOVE_RECURSE "${OUT}")
function(run)
  execute_process(COMMAND "${MESHNBV}" ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "meshnbv ${ARGN} failed (${rc})")
  endif()
endfunction()
run(synth building --out "${OUT}" --views 8 --size 320x240 --layout orbit --quiet)
run(pri "${OUT}/project.mlp" --out "${OUT}/pri_ssd.ply" --quiet)
run(pri "${OUT}/project.mlp" --out "${OUT}/pri_ncc.ply" --measure ncc --samples-per-side 4
    --max-views-per-face 3 --quiet)
run(pri "${OUT}/project.mlp" --out "${OUT}/pri_offset.ply" --measure offset --support-radius 3
    --offset-range 3 --offset-steps 3 --quiet)

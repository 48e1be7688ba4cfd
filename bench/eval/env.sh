# Sourced by the evaluation scripts (run.sh, experiment.sh, dense.sh,
# tune_gain.sh) with the build folder as "$1": the repository, the build's
# meshnbv, the shared data and the scratch folder (COLMAP caches and the
# synthetic datasets, shared by the scripts).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[1]:-$0}")/../.." && pwd)
BUILD=${1:-$ROOT/build}
MESHNBV=$BUILD/apps/meshnbv
SHARED=${MESHNBV_SHARED_DATA:-$ROOT/../shared/data}
WORK=${MESHNBV_EVAL_WORK:-$ROOT/../eval-work}

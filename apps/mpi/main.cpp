// meshnbv-mpi: the meshnbv commands with PRI computed by every MPI rank
// (docs/scale.md). `mpirun -np N meshnbv-mpi pri SCENE --out pri.ply`
// writes what `meshnbv pri SCENE --out pri.ply` writes, bit for bit.
#include <cstring>
#include <iostream>
#include <string>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/mpi/distributed.h"

namespace {

// --quiet or --progress none also silence the per-rank summary line.
bool quiet(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quiet") == 0) return true;
    if (std::strcmp(argv[i], "--progress") == 0 && i + 1 < argc && std::strcmp(argv[i + 1], "none") == 0)
      return true;
    if (std::strcmp(argv[i], "--progress=none") == 0) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    meshnbv::mpi::Session session(&argc, &argv);
    if (session.rank() != 0) return meshnbv::mpi::serve_jobs();
    const bool silent = quiet(argc, argv);
    meshnbv::cli::set_pri_engine([silent](const meshnbv::Scene& scene, const meshnbv::PriOptions& options,
                                          const meshnbv::ProgressCallback& progress,
                                          const meshnbv::PriPrevious* previous) {
      return meshnbv::mpi::distributed_pri(scene, options, progress, previous, silent);
    });
    meshnbv::cli::set_candidate_scorer(meshnbv::mpi::distributed_scores);
    const int code = meshnbv::cli::run_main(argc, argv, "meshnbv-mpi");
    meshnbv::mpi::stop_workers();
    return code;
  } catch (const std::exception& e) {
    std::cerr << "meshnbv-mpi: error: " << e.what() << std::endl;
    return 1;
  }
}

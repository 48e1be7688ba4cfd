// PRI over MPI ranks (docs/scale.md). Rank 0 runs the command line as
// meshnbv does; where a command computes PRI, rank 0 sends the job (the
// scene, the options, the faces to compute) to every rank, the ranks take
// tiles of faces (pri_tiles) one at a time from rank 0 until none is left,
// each decoding only the images of the views its tiles see, and rank 0
// gathers the parts into the result one process would compute, bit for
// bit. The other ranks serve jobs until rank 0 stops them.
#pragma once

#include <string>

#include "meshnbv/energy.h"
#include "meshnbv/pri.h"

namespace meshnbv::mpi {

// MPI_Init_thread (MPI_THREAD_SERIALIZED: rank 0's dispatcher thread makes
// the MPI calls of the tile phase) on construction, MPI_Finalize on
// destruction. Throws Error when MPI cannot give that thread level.
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

// Rank 0: compute_pri's result, computed by every rank. A rank's failure
// (an image that does not decode in its tile) ends the job on every rank
// and throws Error("rank R: <its message>") here; nothing is written by
// the job itself. Prints one line per rank to stderr unless `quiet`
// (tiles, faces, images decoded, seconds, peak memory).
PriResult distributed_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                          const PriPrevious* previous, bool quiet);

// Rank 0: suggest_views' CandidateScorer over every rank. The candidates
// are cut into one contiguous share per rank; the ranks keep the mesh (and
// its ray caster) from one scoring job to the next, so it is sent once per
// mesh. The energies equal energy.evaluate(c), bit for bit.
std::vector<EnergyTerms> distributed_scores(const TriangleMesh& mesh, const EnergyEvaluator& energy,
                                            const EnergyOptions& options,
                                            const std::vector<PinholeCamera>& candidates);

// Ranks > 0: serve jobs until rank 0 calls stop_workers(). Returns 0.
int serve_jobs();
// Rank 0: ends serve_jobs() on every other rank.
void stop_workers();

}  // namespace meshnbv::mpi

// What meshnbv-mpi's ranks send each other, as bytes (docs/scale.md): the
// scene (mesh, cameras, image paths or in-memory pixels), the PRI options,
// a list of faces, and per-face PRI results (PriPart). The bytes go between
// processes of one build, so they are in the machine's byte order; the
// readers still check every size and value, and throw Error on truncated
// or inconsistent input (fuzz/wire). No MPI here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/energy.h"
#include "meshnbv/pri.h"
#include "meshnbv/scene.h"

namespace meshnbv::mpi {

std::string write_scene(const Scene& scene);
Scene read_scene(const std::string& bytes);

std::string write_pri_options(const PriOptions& options);
PriOptions read_pri_options(const std::string& bytes);

std::string write_faces(const std::vector<std::uint32_t>& faces);
std::vector<std::uint32_t> read_faces(const std::string& bytes);

// Any number of parts, one after the other.
std::string write_pri_parts(const std::vector<PriPart>& parts);
std::vector<PriPart> read_pri_parts(const std::string& bytes);

// Scoring candidate poses (suggest_views' CandidateScorer): the mesh (or
// only its key, when the ranks hold it from the last job), the region, the
// existing views' centres, the energy options and the candidates.
struct ScoreJob {
  std::uint64_t mesh_key = 0;
  bool has_mesh = false;
  TriangleMesh mesh;
  WorstRegion region;
  std::vector<Vec3> existing;
  EnergyOptions options;
  std::vector<PinholeCamera> cameras;
};
std::string write_score_job(const ScoreJob& job);
ScoreJob read_score_job(const std::string& bytes);
std::string write_energies(const std::vector<EnergyTerms>& energies);
std::vector<EnergyTerms> read_energies(const std::string& bytes);
// A 64-bit key of a mesh's vertices and faces.
std::uint64_t mesh_key(const TriangleMesh& mesh);

}  // namespace meshnbv::mpi

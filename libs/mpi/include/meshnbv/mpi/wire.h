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

}  // namespace meshnbv::mpi

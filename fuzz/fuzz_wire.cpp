// The messages between meshnbv-mpi's ranks (libs/mpi, wire.h): scene, PRI
// options, faces, PRI parts, candidate scoring jobs and their energies. Each reader accepts its own kind only and
// either returns what its writer gives back byte for byte, or throws Error.
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mpi/wire.h"

namespace {

// 1 when `read` accepts the bytes (and `write` gives them back exactly), 0
// when it throws Error.
template <class Read, class Write>
int round_trip(const std::string& bytes, Read read, Write write) {
  try {
    FUZZ_CHECK(write(read(bytes)) == bytes);
    return 1;
  } catch (const meshnbv::Error&) {
    return 0;
  }
}

}  // namespace

MESHNBV_FUZZ_TARGET(wire) {
  using namespace meshnbv;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const int accepted = round_trip(bytes, mpi::read_scene, mpi::write_scene) +
                       round_trip(bytes, mpi::read_pri_options, mpi::write_pri_options) +
                       round_trip(bytes, mpi::read_faces, mpi::write_faces) +
                       round_trip(bytes, mpi::read_pri_parts, mpi::write_pri_parts) +
                       round_trip(bytes, mpi::read_score_job, mpi::write_score_job) +
                       round_trip(bytes, mpi::read_energies, mpi::write_energies);
  FUZZ_CHECK(accepted <= 1);  // the kinds never overlap
  return 0;
}

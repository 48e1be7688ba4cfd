// The messages between meshnbv-mpi's ranks (libs/mpi, wire.h): scene, PRI
// options, faces, PRI parts, candidate scoring jobs and their energies. Each reader accepts its own kind only and
// either returns what its writer gives back byte for byte, or throws Error.
#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/mpi/wire.h"

MESHNBV_FUZZ_TARGET(wire) {
  using namespace meshnbv;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  int accepted = 0;
  try {
    const Scene s = mpi::read_scene(bytes);
    FUZZ_CHECK(mpi::write_scene(s) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  try {
    FUZZ_CHECK(mpi::write_pri_options(mpi::read_pri_options(bytes)) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  try {
    FUZZ_CHECK(mpi::write_faces(mpi::read_faces(bytes)) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  try {
    FUZZ_CHECK(mpi::write_pri_parts(mpi::read_pri_parts(bytes)) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  try {
    FUZZ_CHECK(mpi::write_score_job(mpi::read_score_job(bytes)) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  try {
    FUZZ_CHECK(mpi::write_energies(mpi::read_energies(bytes)) == bytes);
    ++accepted;
  } catch (const Error&) {
  }
  FUZZ_CHECK(accepted <= 1);  // the kinds never overlap
  return 0;
}

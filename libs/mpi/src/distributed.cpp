#include "meshnbv/mpi/distributed.h"

#include <mpi.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <mutex>
#include <thread>

#include "meshnbv/error.h"
#include "meshnbv/mpi/wire.h"
#include "meshnbv/raycaster.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace meshnbv::mpi {

namespace {

constexpr int kTagRequest = 11, kTagTile = 12, kTagPartsSize = 13, kTagParts = 14;
enum Job : std::int64_t { kJobStop = 0, kJobPri = 1, kJobScore = 2 };
// A worker's message to rank 0's dispatcher: its next tile, or that it failed.
enum Request : std::int64_t { kNext = 0, kFailed = 1 };
// At most this many faces per tile, and at least this many tiles per rank
// (so that a rank that finishes early takes another: dynamic balance).
constexpr std::size_t kMaxTileFaces = 262144;
constexpr std::size_t kTilesPerRank = 4;
// Messages of at most 1 GiB (MPI counts are int).
constexpr std::size_t kChunk = std::size_t(1) << 30;

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw Error(std::string("MPI: ") + what + ": " + std::string(text, std::size_t(length)));
  }
}

int comm_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int comm_size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

// Waits for a request without spinning a core: the ranks of one machine
// share it (oversubscribed), and a rank that waits must leave it to those
// that compute.
void wait_idle(MPI_Request* request) {
  int done = 0;
  auto pause = std::chrono::microseconds(50);
  for (;;) {
    check(MPI_Test(request, &done, MPI_STATUS_IGNORE), "test");
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(5000));
  }
}

// Bytes from `root` to every rank (everyone calls it).
void broadcast(std::string* bytes, int root) {
  std::uint64_t size = bytes->size();
  MPI_Request r;
  check(MPI_Ibcast(&size, 1, MPI_UINT64_T, root, MPI_COMM_WORLD, &r), "broadcast");
  wait_idle(&r);
  bytes->resize(std::size_t(size));
  for (std::size_t at = 0; at < bytes->size(); at += kChunk) {
    const int n = int(std::min(kChunk, bytes->size() - at));
    check(MPI_Ibcast(&(*bytes)[at], n, MPI_CHAR, root, MPI_COMM_WORLD, &r), "broadcast");
    wait_idle(&r);
  }
}

void send_bytes(const std::string& bytes, int to) {
  std::uint64_t size = bytes.size();
  MPI_Request r;
  check(MPI_Isend(&size, 1, MPI_UINT64_T, to, kTagPartsSize, MPI_COMM_WORLD, &r), "send");
  wait_idle(&r);
  for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
    const int n = int(std::min(kChunk, bytes.size() - at));
    check(MPI_Isend(const_cast<char*>(bytes.data() + at), n, MPI_CHAR, to, kTagParts, MPI_COMM_WORLD, &r), "send");
    wait_idle(&r);
  }
}

std::string receive_bytes(int from) {
  std::uint64_t size = 0;
  check(MPI_Recv(&size, 1, MPI_UINT64_T, from, kTagPartsSize, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
  std::string bytes(std::size_t(size), '\0');
  for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
    const int n = int(std::min(kChunk, bytes.size() - at));
    check(MPI_Recv(&bytes[at], n, MPI_CHAR, from, kTagParts, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
  }
  return bytes;
}

double peak_megabytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

// What each rank did in one job, for the summary line.
struct RankStats {
  double tiles = 0, faces = 0, images = 0, seconds = 0, peak_mb = 0, threads = 0;
};

// Rank 0's side of the tile queue: hands tile indices to the other ranks
// from the same queue rank 0 takes its own tiles from, until every other
// rank has been told "none left" or has failed. The tiles (in Morton order)
// are cut into one run per rank, so that a rank's tiles lie together and
// need few of the photos; a rank whose run is done takes the last tile of
// the run before its own (beside its first tiles), else of the longest run
// left (dynamic balance, locality kept).
class Dispatcher {
 public:
  Dispatcher(std::size_t tiles, int ranks) : ranks_(ranks), busy_(std::size_t(ranks), 0) {
    for (int r = 0; r < ranks; ++r)
      runs_.push_back({tiles * std::size_t(r) / std::size_t(ranks), tiles * std::size_t(r + 1) / std::size_t(ranks)});
    if (ranks_ > 1) thread_ = std::thread([this] { run(); });
  }
  ~Dispatcher() { join(); }
  void join() {
    if (thread_.joinable()) thread_.join();
  }
  // The next tile for rank 0, or -1.
  std::int64_t take() { return next(0); }
  void finished_own() { ++finished_; }
  void fail() { failed_ = true; }
  std::size_t finished() const { return finished_.load(); }
  std::string error() const { return error_; }

 private:
  std::int64_t next(int rank) {
    if (failed_) return -1;
    std::lock_guard<std::mutex> lock(mutex_);
    auto& own = runs_[std::size_t(rank)];
    if (own.first < own.second) return std::int64_t(own.first++);
    // The run before this rank's ends where this rank's began: its last
    // tile lies beside the tiles this rank did first.
    auto& before = runs_[std::size_t((rank + ranks_ - 1) % ranks_)];
    if (before.first < before.second) return std::int64_t(--before.second);
    auto longest = std::max_element(runs_.begin(), runs_.end(), [](const auto& a, const auto& b) {
      return a.second - a.first < b.second - b.first;
    });
    if (longest->first == longest->second) return -1;
    return std::int64_t(--longest->second);
  }
  void run() {
    try {
      int open = ranks_ - 1;
      while (open > 0) {
        std::int64_t request = 0;
        MPI_Request r;
        MPI_Status status;
        check(MPI_Irecv(&request, 1, MPI_INT64_T, MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &r), "receive");
        int done = 0;
        auto pause = std::chrono::microseconds(50);
        while (!done) {
          check(MPI_Test(&r, &done, &status), "test");
          if (!done) {
            std::this_thread::sleep_for(pause);
            pause = std::min(pause * 2, std::chrono::microseconds(2000));
          }
        }
        const int from = status.MPI_SOURCE;
        if (busy_[std::size_t(from)]) ++finished_;
        if (request == kFailed) {
          failed_ = true;
          busy_[std::size_t(from)] = 0;
          --open;
          continue;
        }
        std::int64_t tile = next(from);
        busy_[std::size_t(from)] = tile >= 0;
        check(MPI_Send(&tile, 1, MPI_INT64_T, from, kTagTile, MPI_COMM_WORLD), "send");
        if (tile < 0) --open;
      }
    } catch (const std::exception& e) {
      error_ = e.what();
      failed_ = true;
    }
  }

  const int ranks_;
  std::vector<char> busy_;  // per rank: holds a tile (dispatcher thread only)
  std::mutex mutex_;
  std::vector<std::pair<std::size_t, std::size_t>> runs_;  // per rank: [first, end) of its tiles left
  std::atomic<std::size_t> finished_{0};
  std::atomic<bool> failed_{false};
  std::string error_;
  std::thread thread_;
};

// Worker side of the queue.
std::int64_t request_tile(Request what) {
  std::int64_t request = what, tile = -1;
  MPI_Request r;
  check(MPI_Isend(&request, 1, MPI_INT64_T, 0, kTagRequest, MPI_COMM_WORLD, &r), "send");
  wait_idle(&r);
  if (what == kFailed) return -1;
  check(MPI_Irecv(&tile, 1, MPI_INT64_T, 0, kTagTile, MPI_COMM_WORLD, &r), "receive");
  wait_idle(&r);
  return tile;
}

// Every rank: throws Error on every rank when any rank's `error` is not
// empty, with the first such rank's message.
void agree(const std::string& error) {
  const int rank = comm_rank(), ranks = comm_size();
  int first_failed = error.empty() ? INT_MAX : rank, any = INT_MAX;
  MPI_Request r;
  check(MPI_Iallreduce(&first_failed, &any, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &r), "reduce");
  wait_idle(&r);
  if (any == INT_MAX) return;
  std::string message = error;
  broadcast(&message, any);
  throw Error(ranks > 1 ? "rank " + std::to_string(any) + ": " + message : message);
}

// The mesh a scoring job refers to, kept between jobs (rank 0: the key the
// other ranks hold).
struct ScoringMesh {
  std::uint64_t key = 0;
  std::unique_ptr<TriangleMesh> mesh;
  std::unique_ptr<RayCaster> caster;
};
ScoringMesh& scoring_mesh() {
  static ScoringMesh m;
  return m;
}

std::vector<EnergyTerms> evaluate_share(const EnergyEvaluator& energy, const std::vector<PinholeCamera>& cameras,
                                        std::size_t begin, std::size_t end) {
  std::vector<EnergyTerms> out(end - begin);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) out[i - begin] = energy.evaluate(cameras[i]);
  });
  return out;
}

std::pair<std::size_t, std::size_t> share(std::size_t n, int rank, int ranks) {
  return {n * std::size_t(rank) / std::size_t(ranks), n * std::size_t(rank + 1) / std::size_t(ranks)};
}

// A worker's side of one scoring job.
void serve_score_job() {
  const int rank = comm_rank(), ranks = comm_size();
  std::string bytes;
  broadcast(&bytes, 0);
  std::string error, energies;
  try {
    mpi::ScoreJob job = read_score_job(bytes);
    ScoringMesh& held = scoring_mesh();
    if (job.has_mesh) {
      held.key = 0;
      held.caster.reset();
      held.mesh = std::make_unique<TriangleMesh>(std::move(job.mesh));
      held.caster = std::make_unique<RayCaster>(*held.mesh);
      held.key = job.mesh_key;
    } else if (!held.mesh || held.key != job.mesh_key) {
      throw Error("no mesh for the candidate scoring job (not sent)");
    }
    const std::size_t V = held.mesh->num_vertices(), F = held.mesh->num_faces();
    for (int v : job.region.vertices)
      if (v < 0 || std::size_t(v) >= V) throw Error("a region vertex is not in the mesh");
    for (int f : job.region.faces)
      if (f < 0 || std::size_t(f) >= F) throw Error("a region face is not in the mesh");
    const EnergyEvaluator energy(*held.mesh, *held.caster, job.region, job.existing, job.options);
    const auto [begin, end] = share(job.cameras.size(), rank, ranks);
    energies = write_energies(evaluate_share(energy, job.cameras, begin, end));
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  }
  agree(error);
  send_bytes(energies, 0);
}

// One PRI job on every rank, from the broadcast inputs to the gathered
// parts (rank 0: returned; others: empty). Throws Error on every rank when
// any rank failed, naming the first such rank and its message.
std::vector<PriPart> run_pri_job(std::string scene_bytes, std::string options_bytes, std::string faces_bytes,
                                 const ProgressCallback& progress, RankStats* stats_out,
                                 std::vector<RankStats>* all_stats) {
  const int rank = comm_rank(), ranks = comm_size();
  broadcast(&scene_bytes, 0);
  broadcast(&options_bytes, 0);
  broadcast(&faces_bytes, 0);
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  std::vector<PriPart> parts;
  RankStats stats;
  std::unique_ptr<Dispatcher> dispatcher;
  bool told = false;  // this rank has told rank 0 that it takes no more tiles
  try {
    const Scene scene = read_scene(scene_bytes);
    scene_bytes.clear();
    scene_bytes.shrink_to_fit();
    const PriOptions options = read_pri_options(options_bytes);
    const std::vector<std::uint32_t> faces = read_faces(faces_bytes);
    const std::size_t n = faces.empty() ? scene.mesh.num_faces() : faces.size();
    const std::size_t count =
        std::max(kTilesPerRank * std::size_t(ranks), (n + kMaxTileFaces - 1) / kMaxTileFaces);
    const std::vector<std::vector<std::uint32_t>> tiles = pri_tiles(scene.mesh, count, faces);
    if (rank == 0) dispatcher = std::make_unique<Dispatcher>(tiles.size(), ranks);
    const RayCaster caster(scene.mesh);
    const std::size_t loads_before = scene.images->loads();
    try {
      for (;;) {
        const std::int64_t t = rank == 0 ? dispatcher->take() : request_tile(kNext);
        if (t < 0) {
          told = true;
          break;
        }
        const auto& tile = tiles[std::size_t(t)];
        ProgressCallback within;
        if (rank == 0 && progress)
          within = [&](double fraction, const std::string& stage) {
            if (stage != "pri") return true;
            return progress((double(dispatcher->finished()) + fraction) / double(tiles.size()), "pri");
          };
        const PriViewSelection selection = select_pri_views(scene, options, within, tile, &caster);
        parts.push_back(compute_pri_part(scene, options, selection, within));
        stats.tiles += 1;
        stats.faces += double(tile.size());
        if (rank == 0) {
          dispatcher->finished_own();
          report_progress(progress, double(dispatcher->finished()) / double(tiles.size()), "pri");
        }
      }
    } catch (...) {
      if (rank == 0) dispatcher->fail();
      throw;
    }
    stats.images = double(scene.images->loads() - loads_before);
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  }
  // Whatever failed and where, the queue must end on every rank: rank 0
  // answers "none left" to every request, a failed worker says so.
  if (!error.empty()) {
    if (rank == 0 && !dispatcher) dispatcher = std::make_unique<Dispatcher>(0, ranks);
    if (rank == 0) dispatcher->fail();
    if (rank != 0 && !told) request_tile(kFailed);
  }
  if (dispatcher) {
    dispatcher->join();
    if (error.empty() && !dispatcher->error().empty()) error = dispatcher->error();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.peak_mb = peak_megabytes();
  stats.threads = double(tbb::this_task_arena::max_concurrency());

  // Did every rank succeed? The first that failed tells its message.
  agree(error);
  MPI_Request r;
  // Gather the parts and the statistics on rank 0.
  std::vector<double> mine = {stats.tiles, stats.faces, stats.images, stats.seconds, stats.peak_mb, stats.threads};
  std::vector<double> every(mine.size() * std::size_t(ranks));
  check(MPI_Igather(mine.data(), int(mine.size()), MPI_DOUBLE, every.data(), int(mine.size()), MPI_DOUBLE, 0,
                    MPI_COMM_WORLD, &r),
        "gather");
  wait_idle(&r);
  if (rank != 0) {
    send_bytes(write_pri_parts(parts), 0);
    return {};
  }
  for (int from = 1; from < ranks; ++from)
    for (PriPart& p : read_pri_parts(receive_bytes(from))) parts.push_back(std::move(p));
  *stats_out = stats;
  for (int k = 0; k < ranks; ++k) {
    const double* v = &every[std::size_t(k) * mine.size()];
    all_stats->push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  return parts;
}

void broadcast_job(Job job) {
  std::int64_t j = job;
  MPI_Request r;
  check(MPI_Ibcast(&j, 1, MPI_INT64_T, 0, MPI_COMM_WORLD, &r), "broadcast");
  wait_idle(&r);
}

}  // namespace

Session::Session(int* argc, char*** argv) {
  int provided = 0;
  check(MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided), "init");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  rank_ = comm_rank();
  size_ = comm_size();
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw Error("this MPI library does not support MPI_THREAD_SERIALIZED, which meshnbv-mpi needs");
  }
}

Session::~Session() { MPI_Finalize(); }

PriResult distributed_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                          const PriPrevious* previous, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<PriPart> parts;
  std::vector<std::uint32_t> faces;  // empty = all
  std::size_t reselected = 0;
  if (previous) {
    // The reuse is decided here, on the whole mesh's view selection; the
    // ranks compute the changed faces.
    PriReuse reuse = plan_incremental_pri(scene, options, *previous, progress);
    reselected = reuse.selected;
    parts.push_back(std::move(reuse.reused));
    faces = std::move(reuse.changed.face_ids);
    if (faces.empty()) {
      PriResult result = assemble_pri(scene, options, parts);
      result.views_used = reuse.changed.image_views.size();
      result.view_keys = reuse.changed.view_keys;
      result.options_key = reuse.changed.options_key;
      result.reselected = reselected;
      result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return result;
    }
  } else {
    options.check();
  }
  // The readers' checks on rank 0 before any rank starts.
  scene.mesh.validate(scene.mesh_path);
  broadcast_job(kJobPri);
  RankStats own;
  std::vector<RankStats> stats;
  std::vector<PriPart> computed =
      run_pri_job(write_scene(scene), write_pri_options(options), write_faces(faces), progress, &own, &stats);
  for (PriPart& p : computed) parts.push_back(std::move(p));
  PriResult result = assemble_pri(scene, options, parts);
  result.view_keys = pri_view_keys(scene);
  result.options_key = pri_options_key(options);
  result.reselected = previous ? reselected : scene.mesh.num_faces();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_progress(progress, 1.0, "pri");
  if (!quiet) {
    std::ostringstream line;
    line << "meshnbv-mpi: PRI on " << stats.size() << " rank" << (stats.size() > 1 ? "s" : "") << ":";
    for (std::size_t k = 0; k < stats.size(); ++k)
      line << (k ? ";" : "") << " rank " << k << " " << std::llround(stats[k].tiles) << " tiles, "
           << std::llround(stats[k].faces) << " faces, " << std::llround(stats[k].images) << " images decoded, "
           << std::lround(stats[k].seconds * 100) / 100.0 << " s, peak " << std::lround(stats[k].peak_mb) << " MB, "
           << std::llround(stats[k].threads) << " threads";
    std::cerr << line.str() << std::endl;
  }
  return result;
}

int serve_jobs() {
  for (;;) {
    std::int64_t job = kJobStop;
    MPI_Request r;
    check(MPI_Ibcast(&job, 1, MPI_INT64_T, 0, MPI_COMM_WORLD, &r), "broadcast");
    wait_idle(&r);
    if (job == kJobStop) return 0;
    if (job == kJobScore) {
      try {
        serve_score_job();
      } catch (const Error&) {
      }
      continue;
    }
    if (job != kJobPri) throw Error("unknown job " + std::to_string(job) + " from rank 0");
    RankStats own;
    std::vector<RankStats> stats;
    try {
      run_pri_job({}, {}, {}, {}, &own, &stats);
    } catch (const Error&) {
      // Rank 0 reports it; this rank waits for the next job.
    }
  }
}

std::vector<EnergyTerms> distributed_scores(const TriangleMesh& mesh, const EnergyEvaluator& energy,
                                            const EnergyOptions& options,
                                            const std::vector<PinholeCamera>& candidates) {
  const int ranks = comm_size();
  if (ranks == 1) return evaluate_share(energy, candidates, 0, candidates.size());
  ScoreJob job;
  job.mesh_key = mesh_key(mesh);
  ScoringMesh& sent = scoring_mesh();
  job.has_mesh = sent.key != job.mesh_key;
  if (job.has_mesh) job.mesh = mesh;  // copied: the message needs its vertices
  job.region = energy.region();
  job.existing = energy.existing();
  job.options = options;
  job.cameras = candidates;
  std::string bytes = write_score_job(job);
  broadcast_job(kJobScore);
  sent.key = 0;  // until every rank has it
  broadcast(&bytes, 0);
  std::string error;
  std::vector<EnergyTerms> out;
  try {
    const auto [begin, end] = share(candidates.size(), 0, ranks);
    out = evaluate_share(energy, candidates, begin, end);
  } catch (const std::exception& e) {
    error = e.what();
  }
  agree(error);
  sent.key = job.mesh_key;
  for (int from = 1; from < ranks; ++from) {
    const std::vector<EnergyTerms> part = read_energies(receive_bytes(from));
    out.insert(out.end(), part.begin(), part.end());
  }
  if (out.size() != candidates.size()) throw Error("the ranks scored " + std::to_string(out.size()) + " of " +
                                                   std::to_string(candidates.size()) + " candidates");
  return out;
}

void stop_workers() { broadcast_job(kJobStop); }

}  // namespace meshnbv::mpi

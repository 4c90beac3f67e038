// SPDX-License-Identifier: BSD-3-Clause
#include "apps/cluster.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "study/parallel_runs.hpp"
#include "study/run_failure.hpp"
#include "core/errors.hpp"
#include "core/timing.hpp"

#ifdef IMCOL_MPI
#include <mpi.h>
#endif

namespace imcol::cluster {

#ifndef IMCOL_MPI

World world() { return {}; }

void run_distributed(std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                     const std::function<bool(std::size_t, std::string, int)>& done) {
  study::run_parallel(n, jobs, work, [&](std::size_t i, std::string r) { return done(i, std::move(r), 0); });
}

void share(std::string&) {}

namespace {
/// Every rank's `mine`, one after the other, on rank 0 (the identity with one rank).
std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& mine) { return mine; }
}  // namespace

Hold::Hold() : exceptions_(std::uncaught_exceptions()) {}
Hold::~Hold() = default;

#else

namespace {

// Messages: a worker sends kAsk (int64 index of the finished run, -1 for none, then its result's bytes); rank 0
// answers each with kGive (int64 index to run next, -1 for none: the worker asks for nothing more).
constexpr int kAsk = 1, kGive = 2;

bool started_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PMIX_MAPPING_SERV"})
    if (std::getenv(v)) return true;
  return false;
}

World g_world;
bool g_released = true;  // false while other ranks may wait on this one: leaving then aborts the job
int g_holds = 0;         // live Holds: the rank stays held between their steps

void at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  // A rank that leaves while the others wait for it (an error before or during the runs) would leave them hanging.
  if (!g_released) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Finalize();
}

/// A worker's round trip: the finished run (or none) out, the next index (or -1) back.
std::int64_t round_trip(std::int64_t finished, const std::string& bytes) {
  std::vector<char> msg(sizeof finished + bytes.size());
  std::memcpy(msg.data(), &finished, sizeof finished);
  std::memcpy(msg.data() + sizeof finished, bytes.data(), bytes.size());
  MPI_Send(msg.data(), static_cast<int>(msg.size()), MPI_BYTE, 0, kAsk, MPI_COMM_WORLD);
  std::int64_t next = -1;
  MPI_Recv(&next, 1, MPI_INT64_T, 0, kGive, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return next;
}

/// Ranks > 0: up to `jobs` runs at a time, each on a thread of its own; only this thread calls MPI.
void worker(int jobs, const std::function<std::string(std::size_t)>& work) {
  std::mutex mu;
  std::condition_variable cv;
  std::vector<std::pair<std::int64_t, std::string>> finished;
  std::map<std::int64_t, std::thread> running;
  bool stopped = false;
  auto start = [&](std::int64_t i) {
    running.emplace(i, std::thread([&, i] {
      std::string r = work(static_cast<std::size_t>(i));
      std::lock_guard lock(mu);
      finished.emplace_back(i, std::move(r));
      cv.notify_one();
    }));
  };
  for (;;) {
    if (!stopped && static_cast<int>(running.size()) < jobs) {
      const std::int64_t next = round_trip(-1, {});
      if (next < 0) stopped = true;
      else start(next);
      continue;
    }
    if (running.empty()) break;
    std::pair<std::int64_t, std::string> f;
    {
      std::unique_lock lock(mu);
      cv.wait(lock, [&] { return !finished.empty(); });
      f = std::move(finished.back());
      finished.pop_back();
    }
    running.at(f.first).join();
    running.erase(f.first);
    const std::int64_t next = round_trip(f.first, f.second);
    if (next >= 0) start(next);
    else stopped = true;
  }
}

/// Rank 0: `jobs` threads run indices, while this thread answers the workers (polling, so that a waiting rank 0
/// does not hold a core).
void coordinator(std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                 const std::function<bool(std::size_t, std::string, int)>& done, int size) {
  std::mutex mu;
  std::size_t next = 0;
  auto take = [&]() -> std::int64_t {
    std::lock_guard lock(mu);
    return next < n ? static_cast<std::int64_t>(next++) : -1;
  };
  auto give = [&](std::size_t i, std::string r, int rank) {
    std::lock_guard lock(mu);
    if (!done(i, std::move(r), rank)) next = n;
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j)
    threads.emplace_back([&] {
      for (std::int64_t i = take(); i >= 0; i = take()) give(static_cast<std::size_t>(i), work(static_cast<std::size_t>(i)), 0);
    });
  std::vector<bool> stopped(static_cast<std::size_t>(size), false);
  int n_stopped = 0;
  long outstanding = 0;  // handed to workers, not yet back
  std::vector<char> buf;
  while (n_stopped < size - 1 || outstanding > 0) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kAsk, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    int count = 0;
    MPI_Get_count(&st, MPI_BYTE, &count);
    buf.resize(static_cast<std::size_t>(count));
    MPI_Recv(buf.data(), count, MPI_BYTE, st.MPI_SOURCE, kAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::int64_t i = -1;
    std::memcpy(&i, buf.data(), sizeof i);
    if (i >= 0) {
      --outstanding;
      give(static_cast<std::size_t>(i), std::string(buf.data() + sizeof i, buf.size() - sizeof i), st.MPI_SOURCE);
    }
    const std::int64_t j = take();
    if (j >= 0) ++outstanding;
    else if (!stopped[static_cast<std::size_t>(st.MPI_SOURCE)]) {
      stopped[static_cast<std::size_t>(st.MPI_SOURCE)] = true;
      ++n_stopped;
    }
    MPI_Send(&j, 1, MPI_INT64_T, st.MPI_SOURCE, kGive, MPI_COMM_WORLD);
  }
  for (auto& t : threads) t.join();
}

}  // namespace

World world() {
  static const bool once = [] {
    if (!started_by_mpirun()) return true;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &g_world.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g_world.size);
    g_released = g_world.size == 1;
    std::atexit(at_exit);
    return true;
  }();
  (void)once;
  return g_world;
}

void run_distributed(std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                     const std::function<bool(std::size_t, std::string, int)>& done) {
  const World w = world();
  if (w.size == 1) return study::run_parallel(n, jobs, work, [&](std::size_t i, std::string r) { return done(i, std::move(r), 0); });
  g_released = false;
  if (w.rank == 0) coordinator(n, jobs, work, done, w.size);
  else worker(jobs, work);
  g_released = g_holds == 0;
}

void share(std::string& bytes) {
  const World w = world();
  if (w.size == 1) return;
  g_released = false;
  std::int64_t size = static_cast<std::int64_t>(bytes.size());
  MPI_Bcast(&size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(size));
  // MPI counts are int: a larger message goes in pieces.
  constexpr std::int64_t kPiece = 1 << 30;
  for (std::int64_t at = 0; at < size; at += kPiece)
    MPI_Bcast(bytes.data() + at, static_cast<int>(std::min(kPiece, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  g_released = g_holds == 0;
}

namespace {
/// Every rank's `mine` (the same size on every rank), one after the other, on rank 0; nothing on the other ranks.
std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& mine) {
  const World w = world();
  if (w.size == 1) return mine;
  g_released = false;
  std::vector<std::uint64_t> all(w.rank == 0 ? mine.size() * static_cast<std::size_t>(w.size) : 0);
  MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_UINT64_T, all.data(), static_cast<int>(mine.size()), MPI_UINT64_T, 0,
             MPI_COMM_WORLD);
  g_released = g_holds == 0;
  return all;
}
}  // namespace

Hold::Hold() : exceptions_(std::uncaught_exceptions()) {
  if (world().size == 1) return;
  ++g_holds;
  g_released = false;
}

Hold::~Hold() {
  if (world().size == 1) return;
  --g_holds;
  // Left by an exception: stay held, so that leaving the process aborts the job.
  if (std::uncaught_exceptions() == exceptions_) g_released = g_holds == 0;
}

#endif

std::uint64_t digest(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

namespace {

/// "rank 2", "ranks 1, 3 and 4".
std::string ranks_text(const std::vector<int>& ranks) {
  std::string t = ranks.size() == 1 ? "rank " : "ranks ";
  for (std::size_t i = 0; i < ranks.size(); ++i)
    t += (i == 0 ? "" : i + 1 == ranks.size() ? " and " : ", ") + std::to_string(ranks[i]);
  return t;
}

}  // namespace

int agree(const Inputs& inputs) {
  if (world().size == 1) return 0;
  constexpr const char* kParts[] = {"scene", "options", "version"};
  const std::vector<std::uint64_t> all = gather({digest(inputs.scene), digest(inputs.options), digest(IMCOL_VERSION)});
  return on_rank0([&] {
    // The ranks that differ from rank 0, grouped by what differs ("scene", "scene and options", ...).
    std::map<std::string, std::vector<int>> by_parts;
    std::vector<std::string> order;
    for (std::size_t r = 1; r * 3 < all.size(); ++r) {
      std::string parts;
      for (std::size_t k = 0; k < 3; ++k)
        if (all[3 * r + k] != all[k]) parts += std::string(parts.empty() ? "" : ", ") + kParts[k];
      if (parts.empty()) continue;
      if (!by_parts.count(parts)) order.push_back(parts);
      by_parts[parts].push_back(static_cast<int>(r));
    }
    if (order.empty()) return;
    std::string msg = "the ranks of this job were not given the same inputs, so their results cannot be put together: ";
    for (std::size_t i = 0; i < order.size(); ++i)
      msg += (i ? "; " : "") + ranks_text(by_parts[order[i]]) + " differ" + (by_parts[order[i]].size() == 1 ? "s" : "") +
             " from rank 0 in " + order[i];
    msg += " (every rank must run the same imcol version and command on the same scene: check IMCOL_DATA_DIR, the scene file, "
           "--set and the other options on every node)";
    throw InputError("mpirun", "", msg);
  });
}

int on_rank0(const std::function<void()>& step) {
  RunFailure failure;
  std::string status;  // rank 0's exit status when step threw
  if (world().rank == 0) {
    try {
      step();
    } catch (const std::exception&) {
      failure = RunFailure::current();
      status = std::to_string(failure.kind == RunFailure::input ? 2 : failure.kind == RunFailure::solver ? 3 : 1);
    }
  }
  share(status);
  if (failure.thrown) std::rethrow_exception(failure.thrown);
  return status.empty() ? 0 : std::stoi(status);
}

}  // namespace imcol::cluster

namespace imcol {

study::Executor cluster_executor(int jobs, ResultTaken taken) {
  study::Executor ex;
  ex.jobs = jobs;
  const cluster::World w = cluster::world();
  ex.rank = w.rank;
  ex.ranks = w.size;
  ex.share = [](std::string& bytes) { cluster::share(bytes); };
  ex.distribute = [taken](std::size_t n, int threads, const std::function<std::string(std::size_t)>& work,
                          const std::function<bool(std::size_t, std::string, int)>& done) {
    if (!taken) return cluster::run_distributed(n, threads, work, done);
    cluster::run_distributed(n, threads, work, [&](std::size_t i, std::string bytes, int rank) {
      const std::size_t size = bytes.size();
      const auto t0 = WallClock::now();
      const bool more = done(i, std::move(bytes), rank);
      taken(rank, size, seconds_since(t0));
      return more;
    });
  };
  return ex;
}

}  // namespace imcol

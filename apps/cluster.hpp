// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Independent runs spread over the ranks of an MPI job (docs/cluster.md): rank 0 hands out run indices on request and
// takes each finished run's result as bytes; every rank runs its share on its own threads. The only MPI code in imcol.
// Without mpirun, or built without MPI (IMCOL_MPI off), there is one rank and the runs stay on this process's threads.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "study/executor.hpp"

namespace imcol::cluster {

/// This process's rank and the job's size: {0, 1} unless started by mpirun (or srun) of an MPI build.
/// The first call starts MPI when the process was started so (MPI ends when the process exits).
struct World {
  int rank = 0, size = 1;
};
World world();

/// Runs work(i) for i in [0, n) on every rank of world(), each on `jobs` threads, indices handed out one at a time
/// as threads fall idle. Rank 0 runs done(i, work's bytes, the rank that ran it) for every index, one call at a time, in its own
/// process; done returns false to hand out no further indices (those started still finish). Ranks > 0 never
/// call done. Every rank calls this with the same n. work must not throw.
void run_distributed(std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                     const std::function<bool(std::size_t, std::string, int)>& done);

/// Makes rank 0's `bytes` every rank's (a broadcast of the size, then the bytes). Every rank calls it at the same
/// point. The identity with one rank.
void share(std::string& bytes);

/// Runs `step` on rank 0 alone (taking its output folder, say) and tells every rank whether it threw, so that no
/// rank waits on a rank 0 that has left: rank 0 rethrows the exception; the other ranks get the exit status rank 0
/// leaves with (2 for an InputError, 3 for a SolverError, else 1) and should leave with it. 0 on every rank when
/// step did not throw. Every rank calls it at the same point.
int on_rank0(const std::function<void()>& step);

/// What every rank of a job must run on alike, as text: the command's resolved scene(s) (core/scene_values.hpp) and
/// the options that decide its results (with the command's name). imcol's version is added here.
struct Inputs {
  std::string scene, options;
};

/// Compares every rank's inputs with rank 0's (64-bit digests of each part, gathered on rank 0), so that ranks
/// started on different inputs (another IMCOL_DATA_DIR, an MPMD job with another --set) cannot mix their results.
/// 0 on every rank when all agree; else rank 0 throws an InputError naming the ranks that differ and in what (scene,
/// options, version) and the other ranks get 2, which they should leave with. Every rank calls it at the same point,
/// before the first run_distributed; nothing with one rank.
int agree(const Inputs& inputs);

/// The FNV-1a 64-bit digest of `text` (agree's, the same on every machine).
std::uint64_t digest(const std::string& text);

/// Several steps in a row (run_distributed, share) during which the other ranks may wait on this one: while a Hold
/// lives, a rank that leaves by an exception or exit aborts the job instead of leaving the others waiting. Ended
/// normally (not by an exception), it releases the rank again. Nothing without MPI.
class Hold {
 public:
  Hold();
  ~Hold();
  Hold(const Hold&) = delete;
  Hold& operator=(const Hold&) = delete;

 private:
  int exceptions_;
};

}  // namespace imcol::cluster

namespace imcol {

/// What rank 0 did with one result: the rank that ran it, its size in bytes, and the seconds rank 0 spent taking it
/// in (decoding it and the study's own handling).
using ResultTaken = std::function<void(int rank, std::size_t bytes, double seconds)>;

/// A study's Executor over this job's ranks (study/executor.hpp): `jobs` threads on each (0 = all cores), the
/// results carried to rank 0 as bytes by run_distributed; world()'s rank and size. `taken`, if given, on rank 0
/// after each result is taken in.
study::Executor cluster_executor(int jobs, ResultTaken taken = {});

}  // namespace imcol

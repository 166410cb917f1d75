// Lucerna (host): one render over many MPI processes (`mpirun -np K lucerna render ...`). A layer
// around RunPasses: rank 0 hands out blocks of pass indices on request, every rank renders its
// blocks through its backend, films and counters are summed by MPI_Reduce at sync points.
#pragma once

#include <functional>

#include "lucerna/render/pass_driver.h"

namespace lu {

// True when an MPI launcher (mpirun/mpiexec of Open MPI or MPICH, srun with PMI) started this
// process, whether or not this build has MPI.
bool LaunchedByMpi();
// Whether this build has the distributed mode (CMake option LUCERNA_MPI, MPI found).
bool HaveMpi();

// MPI for the lifetime of one command: MPI_Init_thread(MPI_THREAD_MULTIPLE) when launched by MPI
// and built with it, nothing otherwise. Finish(rc) ends it: MPI_Finalize when every rank completed
// RunDistributed, else MPI_Abort(rc) so that one rank's early error (a bad scene, a bad
// checkpoint) ends the whole job with that exit code instead of leaving the others waiting.
class MpiSession {
  public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession &) = delete;
    MpiSession &operator=(const MpiSession &) = delete;
    int Finish(int rc);

    static bool Active();   // a session is open (distributed rendering is on)
    static int Rank();      // 0 when not active
    static int Size();      // 1 when not active
};

// Renders one rank's backend calls; called at most once per rank (an acceleration structure is
// built once). `film` is the rank's film; film.passes is the first pass to render.
using BackendFn = std::function<RenderStats(const RenderSettings &, FilmAccumulator &, const RenderControl &)>;

// Thrown for disagreements between ranks and MPI failures; the message names the rank.
struct DistributedError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The distributed pass loop (every rank calls it; MpiSession::Active() must hold).
// - Every rank must bring the same settings, checkpointKey, film size and film.passes (a resumed
//   film: every rank loads the same checkpoint); ranks other than 0 drop their copy of the sums.
// - Rank 0 hands out blocks [a, b) of pass indices from film.passes up to settings.spp in
//   increasing order, on request (a faster rank asks more often), sized to ~0.25 s of that rank's
//   measured pass time. Pass k is rendered with settings.ForPass(k) and sampler index k, exactly
//   as in one process.
// - Sync points (every control.syncSeconds when > 0, and the end): rank 0 stops handing out
//   blocks, each rank finishes the blocks it holds, the films are summed into rank 0's by
//   MPI_Reduce. The passes done are then always the prefix [0, P): a checkpoint stays a pass
//   count, resumable by any number of ranks. On rank 0, control.onPass(total film, stats so far)
//   runs after each periodic sync (not the final one).
// - The end: settings.spp reached, settings.timeLimit (wall-clock seconds of the whole job,
//   decided by rank 0), or *control.cancel on any rank (SIGINT/SIGTERM): no new blocks; blocks
//   in hand are finished (at most ~0.25 s or one pass per rank), then the final reduction.
// On rank 0 `film` is then the sum of every rank's passes and the result the merged statistics
// (seconds: the job's wall time); on other ranks film holds no sums and the result is local.
RenderStats RunDistributed(const RenderSettings &settings, uint64_t checkpointKey, FilmAccumulator &film,
                           const RenderControl &control, const BackendFn &backend);

// Seconds for one MPI_Reduce (sum) of `doubles` doubles into rank 0, over `repeats` repetitions
// (every rank calls it; for bench/). Returns the mean on rank 0.
double TimeFilmReduction(size_t doubles, int repeats);

}  // namespace lu

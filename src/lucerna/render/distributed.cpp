// Lucerna (host): distributed passes over MPI (render/distributed.h). Rank 0 runs a coordinator
// thread beside its own rendering; requests and replies go over one communicator, reductions over
// another, so the two threads never match each other's messages (MPI_THREAD_MULTIPLE).
#include "lucerna/render/distributed.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#if defined(LUCERNA_HAVE_MPI)
#include <mpi.h>
#endif

namespace lu {

bool LaunchedByMpi() {
    for (const char *v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
        if (std::getenv(v)) return true;
    return false;
}

#if !defined(LUCERNA_HAVE_MPI)

bool HaveMpi() { return false; }
MpiSession::MpiSession() {
    if (LaunchedByMpi())
        std::fprintf(stderr, "lucerna: warning: started by an MPI launcher, but this build has no MPI: every process "
                             "renders the whole image on its own (rebuild with libopenmpi-dev installed)\n");
}
MpiSession::~MpiSession() {}
int MpiSession::Finish(int rc) { return rc; }
bool MpiSession::Active() { return false; }
int MpiSession::Rank() { return 0; }
int MpiSession::Size() { return 1; }
RenderStats RunDistributed(const RenderSettings &, uint64_t, FilmAccumulator &, const RenderControl &, const BackendFn &) {
    throw DistributedError("this build has no MPI (configure with LUCERNA_MPI=ON and libopenmpi-dev installed)");
}
double TimeFilmReduction(size_t, int) { return 0; }

#else

namespace {

using Clock = std::chrono::steady_clock;

struct SessionState {
    bool active = false, completed = false, finished = false;
    int rank = 0, size = 1;
    MPI_Comm ctrl = MPI_COMM_NULL, data = MPI_COMM_NULL;
};
SessionState gSession;

void Check(int err, const char *what) {
    if (err == MPI_SUCCESS) return;
    char msg[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(err, msg, &len);
    throw DistributedError("rank " + std::to_string(gSession.rank) + ": " + what + " failed: " + std::string(msg, size_t(len)));
}

double Seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Waits for a request without spinning a core (Open MPI's blocking calls poll; the ranks of one
// host share its cores with the renderers).
void PoliteWait(MPI_Request *req, const char *what, int sleepMicros = 50) {
    for (;;) {
        int done = 0;
        Check(MPI_Test(req, &done, MPI_STATUS_IGNORE), what);
        if (done) return;
        usleep(useconds_t(sleepMicros));
    }
}

// ---- Protocol ----
constexpr int TagRequest = 1, TagReply = 2;
struct Request {
    double secondsPerPass = 0;   // the rank's measured render time per pass (0: not known yet)
    int32_t signalled = 0;       // the rank caught SIGINT/SIGTERM
    int32_t pad = 0;
};
enum class Kind : int32_t { Block = 0, Sync = 1, Stop = 2 };
struct Reply {
    Kind kind = Kind::Stop;
    uint32_t begin = 0, end = 0;   // Block: passes [begin, end); Sync/Stop: the passes done then are [0, end)
    int32_t interrupted = 0;       // Stop: by a signal
};

// ---- Rank 0: hands out blocks, decides syncs and the end, shows progress ----
class Coordinator {
  public:
    Coordinator(const RenderSettings &s, uint32_t firstPass, uint64_t pixels, double syncSeconds,
                const std::atomic<bool> *cancel)
        : size_(gSession.size), total_(uint32_t(std::max(s.spp, 0))), next_(firstPass), first_(firstPass),
          timeLimit_(s.timeLimit), syncSeconds_(syncSeconds), pixels_(pixels), progress_(s.progress),
          tty_(isatty(STDERR_FILENO) != 0), cancel_(cancel), given_(size_, 0), inFlight_(size_, 0),
          secondsPerPass_(size_, 0), stopped_(size_, false) {}

    void Start() {
        t0_ = Clock::now();
        lastSyncDone_.store(0);
        thread_ = std::thread([this] { Run(); });
    }
    void Join() {
        if (thread_.joinable()) thread_.join();
    }
    // Rank 0's main thread: a sync is complete (reduced, callback done) at `Elapsed()`.
    void SyncDone() {
        lastSyncDone_.store(Elapsed());
        syncPending_.store(false);
    }
    double Elapsed() const { return Seconds(t0_); }

  private:
    void Push(Kind kind, bool interrupted = false) {
        Reply r;
        r.kind = kind;
        r.end = next_;
        r.interrupted = interrupted;
        events_.push_back(r);
        if (kind == Kind::Stop) stopPushed_ = true;
        if (kind == Kind::Sync) syncPending_.store(true);
    }

    uint32_t BlockSize(int rank) const {
        uint32_t remaining = total_ - next_;
        double spp = secondsPerPass_[rank];
        uint64_t n = 1;
        if (spp > 0) {
            double budget = kBlockSeconds;
            if (timeLimit_ > 0) budget = std::min(budget, timeLimit_ - Elapsed());
            if (syncSeconds_ > 0) budget = std::min(budget, syncSeconds_);
            n = uint64_t(std::max(1.0, std::floor(budget / spp)));
        }
        // Near the end every rank should still get a share: at most half of an even split.
        n = std::min<uint64_t>(n, std::max<uint64_t>(1, remaining / (2 * uint64_t(size_))));
        return uint32_t(std::min<uint64_t>(n, remaining));
    }

    Reply Answer(int rank, const Request &req) {
        if (req.secondsPerPass > 0) secondsPerPass_[rank] = req.secondsPerPass;
        if (req.signalled && !stopPushed_) Push(Kind::Stop, true);
        inFlight_[rank] = 0;   // a request means the rank finished what it held
        if (given_[rank] < events_.size()) return events_[given_[rank]++];
        if (next_ < total_) {
            Reply r;
            r.kind = Kind::Block;
            r.begin = next_;
            r.end = next_ + BlockSize(rank);
            next_ = r.end;
            inFlight_[rank] = r.end - r.begin;
            return r;
        }
        Push(Kind::Stop);
        return events_[given_[rank]++];
    }

    void Run() {
        try {
            int stoppedRanks = 0;
            while (stoppedRanks < size_) {
                double t = Elapsed();
                if (!stopPushed_) {
                    if (cancel_ && cancel_->load(std::memory_order_relaxed)) Push(Kind::Stop, true);
                    else if (timeLimit_ > 0 && t >= timeLimit_) Push(Kind::Stop);
                    else if (syncSeconds_ > 0 && !syncPending_.load() && t - lastSyncDone_.load() >= syncSeconds_ &&
                             next_ > lastSyncPasses_) {
                        lastSyncPasses_ = next_;
                        Push(Kind::Sync);
                    }
                }
                ShowProgress(false);
                int flag = 0;
                MPI_Status status;
                Check(MPI_Iprobe(MPI_ANY_SOURCE, TagRequest, gSession.ctrl, &flag, &status), "MPI_Iprobe");
                if (!flag) {
                    usleep(500);
                    continue;
                }
                Request req;
                int rank = status.MPI_SOURCE;
                Check(MPI_Recv(&req, sizeof req, MPI_BYTE, rank, TagRequest, gSession.ctrl, MPI_STATUS_IGNORE), "MPI_Recv");
                Reply r = Answer(rank, req);
                if (r.kind == Kind::Stop) {
                    stopped_[rank] = true;
                    ++stoppedRanks;
                }
                Check(MPI_Send(&r, sizeof r, MPI_BYTE, rank, TagReply, gSession.ctrl), "MPI_Send");
            }
            ShowProgress(true);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "lucerna: error: distributed render (coordinator): %s\n", e.what());
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
    }

    void ShowProgress(bool final) {
        if (!progress_) return;
        auto now = Clock::now();
        if (!final && printed_ && std::chrono::duration<double>(now - lastPrint_).count() < (tty_ ? 0.125 : 5.0)) return;
        printed_ = true;
        lastPrint_ = now;
        uint64_t held = 0;
        for (uint32_t n : inFlight_) held += n;
        uint32_t done = uint32_t(next_ - held);
        double t = Elapsed();
        double rate = double(done - first_) * double(pixels_) / std::max(1e-9, t) * 1e-6;
        char what[96];
        if (timeLimit_ > 0 && total_ >= (1u << 24))
            std::snprintf(what, sizeof what, "pass %u  %.1f / %.0f s", done, t, timeLimit_);
        else
            std::snprintf(what, sizeof what, "pass %u/%u", done, total_);
        std::fprintf(stderr, "%s%s  %d ranks  %.2f Msamples/s  elapsed %.1fs%s", tty_ ? "\r" : "", what, size_, rate, t,
                     final ? "  (done)\n" : tty_ ? "   " : "\n");
        std::fflush(stderr);
    }

    static constexpr double kBlockSeconds = 0.25;
    int size_;
    uint32_t total_, next_, first_;
    double timeLimit_, syncSeconds_;
    uint64_t pixels_;
    bool progress_, tty_;
    const std::atomic<bool> *cancel_;
    std::vector<Reply> events_;        // syncs and the stop, in the order every rank receives them
    std::vector<size_t> given_;        // events each rank has received
    std::vector<uint32_t> inFlight_;   // passes each rank holds
    std::vector<double> secondsPerPass_;
    std::vector<bool> stopped_;
    bool stopPushed_ = false;
    uint32_t lastSyncPasses_ = 0;
    std::atomic<bool> syncPending_{false};
    std::atomic<double> lastSyncDone_{0};
    bool printed_ = false;
    Clock::time_point t0_, lastPrint_;
    std::thread thread_;
};

// Sums `n` doubles into rank 0 (in place there), in chunks of 8 MB: Open MPI's reduction allocates
// a temporary buffer of the message size per call, and glibc maps one larger than its mmap
// threshold (at most 32 MB) afresh each time; the page faults of a whole 1920x1080 film (66 MB)
// made one reduction ~2 s on the 2-core test machine, 8 MB chunks ~0.2 s (docs/benchmarks.md).
void ReduceSums(double *v, size_t n) {
    constexpr size_t kChunk = size_t(1) << 20;
    for (size_t off = 0; off < n; off += kChunk) {
        int count = int(std::min(kChunk, n - off));
        if (gSession.rank == 0)
            Check(MPI_Reduce(MPI_IN_PLACE, v + off, count, MPI_DOUBLE, MPI_SUM, 0, gSession.data), "MPI_Reduce (film)");
        else
            Check(MPI_Reduce(v + off, nullptr, count, MPI_DOUBLE, MPI_SUM, 0, gSession.data), "MPI_Reduce (film)");
    }
}

// The statistics of every rank merged into rank 0's (seconds and buildSeconds: the maximum).
RenderStats MergeStats(const RenderStats &s, int width) {
    uint64_t sums[7] = {s.samples, s.rays, s.shadowRays, s.regConnections, s.rejected, s.passesThisRun, s.mneeConnections};
    double dsums[2] = {s.regEnergy, s.totalEnergy};
    double maxes[2] = {s.seconds, s.buildSeconds};
    // The first rejected sample: the smallest (pixel, depth) key over the ranks, with its cause.
    const RejectedSample &f = s.firstRejected;
    uint64_t key = s.rejected == 0 || !f.Valid()
                       ? ~0ull
                       : RejectedSampleKey(f.x, f.y, width, f.depth, f.cause, f.badValue, f.entity);
    uint64_t outSums[7] = {}, outKey = ~0ull;
    double outD[2] = {}, outMax[2] = {};
    Check(MPI_Reduce(sums, outSums, 7, MPI_UINT64_T, MPI_SUM, 0, gSession.data), "MPI_Reduce (stats)");
    Check(MPI_Reduce(dsums, outD, 2, MPI_DOUBLE, MPI_SUM, 0, gSession.data), "MPI_Reduce (stats)");
    Check(MPI_Reduce(maxes, outMax, 2, MPI_DOUBLE, MPI_MAX, 0, gSession.data), "MPI_Reduce (stats)");
    Check(MPI_Reduce(&key, &outKey, 1, MPI_UINT64_T, MPI_MIN, 0, gSession.data), "MPI_Reduce (stats)");
    if (gSession.rank != 0) return s;
    RenderStats m = s;
    m.samples = outSums[0];
    m.rays = outSums[1];
    m.shadowRays = outSums[2];
    m.regConnections = outSums[3];
    m.rejected = outSums[4];
    m.passesThisRun = uint32_t(outSums[5]);
    m.regEnergy = outD[0];
    m.totalEnergy = outD[1];
    m.seconds = outMax[0];
    m.buildSeconds = outMax[1];
    m.mneeConnections = outSums[6];
    m.firstRejected = DecodeRejectedSampleKey(outKey, width);
    return m;
}

// One rank's side: asks for work, renders blocks through the backend, joins the syncs.
class Worker {
  public:
    Worker(const RenderSettings &s, FilmAccumulator &film, const RenderControl &control, Coordinator *coordinator)
        : settings_(s), film_(film), control_(control), coordinator_(coordinator), lastSyncPasses_(film.passes),
          firstPass_(film.passes) {}

    RenderStats Run(const BackendFn &backend) {
        RenderSettings rs = settings_;
        rs.timeLimit = 0;      // rank 0 decides the end
        rs.progress = false;   // rank 0 shows the job's progress
        RenderControl bc;      // no cancel: a block in hand is always finished (the done passes stay a prefix)
        bc.onPass = [this](const FilmAccumulator &, const RenderStats &st) {
            ++sinceSync_;
            ++passesRendered_;
            if (film_.passes < blockEnd_) return true;
            if (st.passesThisRun > 0) secondsPerPass_ = st.seconds / st.passesThisRun;
            return Take(Next());
        };
        RenderStats local;
        if (Take(Next())) local = backend(rs, film_, bc);
        if (!stop_) throw DistributedError("rank " + std::to_string(gSession.rank) + ": the backend stopped before the end");
        Sync(stopReply_, true);
        local.interrupted = stopReply_.interrupted != 0;
        RenderStats merged = MergeStats(local, film_.width);
        film_.passes = stopReply_.end;
        merged.passesThisRun = stopReply_.end - firstPass_;
        merged.interrupted = local.interrupted;
        return merged;
    }

    uint32_t PassesRendered() const { return passesRendered_; }
    uint32_t Reductions() const { return reductions_; }
    // Rank 0: the job's wall time so far, less the time in control.onPass (checkpoints).
    double Seconds() const { return coordinator_->Elapsed() - callbackSeconds_; }

  private:
    bool Take(const Reply &r) {
        if (r.kind == Kind::Stop) {
            stop_ = true;
            stopReply_ = r;
            return false;
        }
        film_.passes = r.begin;   // RunPasses renders pass film.passes next
        blockEnd_ = r.end;
        return true;
    }

    // The next block, or the stop; joins the syncs that come first.
    Reply Next() {
        for (;;) {
            Request req;
            req.secondsPerPass = secondsPerPass_;
            req.signalled = control_.cancel && control_.cancel->load() ? 1 : 0;
            Reply r;
            MPI_Request recv;
            Check(MPI_Irecv(&r, sizeof r, MPI_BYTE, 0, TagReply, gSession.ctrl, &recv), "MPI_Irecv");
            Check(MPI_Send(&req, sizeof req, MPI_BYTE, 0, TagRequest, gSession.ctrl), "MPI_Send");
            PoliteWait(&recv, "waiting for rank 0");
            if (r.kind != Kind::Sync) return r;
            Sync(r, false);
        }
    }

    // Sums every rank's film into rank 0's; the passes done are then [0, r.end) on every rank.
    void Sync(const Reply &r, bool final) {
        MPI_Request barrier;   // every rank arrives (finishing its blocks) before the reduction
        Check(MPI_Ibarrier(gSession.data, &barrier), "MPI_Ibarrier");
        PoliteWait(&barrier, "waiting for the other ranks", 200);
        uint64_t count = sinceSync_, total = 0;
        Check(MPI_Reduce(&count, &total, 1, MPI_UINT64_T, MPI_SUM, 0, gSession.data), "MPI_Reduce (pass count)");
        ReduceSums(film_.xyzw.data(), film_.xyzw.size());
        sinceSync_ = 0;
        ++reductions_;
        if (gSession.rank != 0) {
            std::fill(film_.xyzw.begin(), film_.xyzw.end(), 0.0);   // now in rank 0's sums
            return;
        }
        if (total != uint64_t(r.end - lastSyncPasses_))
            throw DistributedError("rank 0: the ranks rendered " + std::to_string(total) + " passes since pass " +
                                   std::to_string(lastSyncPasses_) + ", expected " +
                                   std::to_string(r.end - lastSyncPasses_));
        lastSyncPasses_ = r.end;
        if (!final && control_.onPass) {
            auto c0 = Clock::now();
            uint32_t next = film_.passes;
            film_.passes = r.end;
            RenderStats so;
            so.passesThisRun = r.end - firstPass_;
            so.samples = uint64_t(so.passesThisRun) * uint64_t(film_.width) * uint64_t(film_.height);
            so.seconds = Seconds();
            control_.onPass(film_, so);
            film_.passes = next;
            callbackSeconds_ += lu::Seconds(c0);
        }
        coordinator_->SyncDone();
    }

    const RenderSettings &settings_;
    FilmAccumulator &film_;
    const RenderControl &control_;
    Coordinator *coordinator_;   // rank 0 only
    uint32_t blockEnd_ = 0, lastSyncPasses_, firstPass_;
    uint64_t sinceSync_ = 0;     // passes this rank committed since the last sync
    uint32_t passesRendered_ = 0, reductions_ = 0;
    double secondsPerPass_ = 0, callbackSeconds_ = 0;
    bool stop_ = false;
    Reply stopReply_;
};

}  // namespace

bool HaveMpi() { return true; }

MpiSession::MpiSession() {
    if (!LaunchedByMpi()) return;
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS) {
        std::fprintf(stderr, "lucerna: error: MPI_Init_thread failed\n");
        std::exit(1);
    }
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &gSession.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &gSession.size);
    if (provided < MPI_THREAD_MULTIPLE) {
        if (gSession.rank == 0)
            std::fprintf(stderr, "lucerna: error: this MPI library does not provide MPI_THREAD_MULTIPLE (rank 0 "
                                 "coordinates in a thread beside its rendering)\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &gSession.ctrl);
    MPI_Comm_dup(MPI_COMM_WORLD, &gSession.data);
    MPI_Comm_set_errhandler(gSession.ctrl, MPI_ERRORS_RETURN);
    MPI_Comm_set_errhandler(gSession.data, MPI_ERRORS_RETURN);
    gSession.active = true;
}

MpiSession::~MpiSession() { Finish(1); }

int MpiSession::Finish(int rc) {
    if (!gSession.active || gSession.finished) return rc;
    gSession.finished = true;
    if (!gSession.completed) {   // this rank left before (or during) the distributed render
        std::fflush(stdout);
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, rc == 0 ? 1 : rc);
    }
    MPI_Comm_free(&gSession.ctrl);
    MPI_Comm_free(&gSession.data);
    MPI_Finalize();
    return rc;
}

bool MpiSession::Active() { return gSession.active && !gSession.finished; }
int MpiSession::Rank() { return gSession.rank; }
int MpiSession::Size() { return gSession.size; }

RenderStats RunDistributed(const RenderSettings &settings, uint64_t checkpointKey, FilmAccumulator &film,
                           const RenderControl &control, const BackendFn &backend) {
    if (!MpiSession::Active()) throw DistributedError("no MPI session");
    // ---- Every rank renders the same image from the same pass ----
    uint64_t mine[5] = {checkpointKey, film.passes, uint64_t(film.width), uint64_t(film.height),
                        uint64_t(std::max(settings.spp, 0))};
    uint64_t root[5];
    std::memcpy(root, mine, sizeof mine);
    Check(MPI_Bcast(root, 5, MPI_UINT64_T, 0, gSession.data), "MPI_Bcast");
    int differs = std::memcmp(root, mine, sizeof mine) != 0, anyDiffers = 0;
    Check(MPI_Allreduce(&differs, &anyDiffers, 1, MPI_INT, MPI_MAX, gSession.data), "MPI_Allreduce");
    if (anyDiffers) {
        const char *what = root[0] != mine[0] ? "scene, settings or seed"
                           : root[1] != mine[1]                     ? "first pass (resumed checkpoint)"
                           : root[4] != mine[4]                     ? "pass count"
                                                                    : "film size";
        throw DistributedError(differs ? "rank " + std::to_string(gSession.rank) + " has another " + what + " than rank 0"
                                       : "another rank disagrees with rank 0 (its message names it)");
    }
    if (gSession.rank != 0) std::fill(film.xyzw.begin(), film.xyzw.end(), 0.0);   // rank 0 holds the resumed sums

    std::unique_ptr<Coordinator> coordinator;
    if (gSession.rank == 0)
        coordinator = std::make_unique<Coordinator>(settings, film.passes, uint64_t(film.width) * uint64_t(film.height),
                                                    control.syncSeconds, control.cancel);
    Check(MPI_Barrier(gSession.data), "MPI_Barrier");
    if (coordinator) coordinator->Start();
    Worker worker(settings, film, control, coordinator.get());
    RenderStats stats;
    try {
        stats = worker.Run(backend);
    } catch (const std::exception &e) {   // the others cannot finish without this rank: end the job
        std::fprintf(stderr, "lucerna: error: distributed render: %s\n", e.what());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (coordinator) stats.seconds = worker.Seconds();
    // Load balance, for the log: the passes each rank rendered.
    std::vector<uint32_t> perRank(size_t(gSession.size), 0);
    uint32_t mineDone = worker.PassesRendered();
    Check(MPI_Gather(&mineDone, 1, MPI_UINT32_T, perRank.data(), 1, MPI_UINT32_T, 0, gSession.data), "MPI_Gather");
    if (coordinator && settings.progress) {
        std::string list;
        for (uint32_t n : perRank) {
            list += ' ';
            list += std::to_string(n);
        }
        std::fprintf(stderr, "mpi: %d ranks, passes per rank%s, %u reductions\n", gSession.size, list.c_str(),
                     worker.Reductions());
    }
    if (coordinator) coordinator->Join();
    gSession.completed = true;
    return stats;
}

double TimeFilmReduction(size_t doubles, int repeats) {
    if (!MpiSession::Active()) throw DistributedError("no MPI session");
    gSession.completed = true;   // a whole collective exchange: MpiSession::Finish may finalize
    std::vector<double> v(doubles, 1.0);
    double sum = 0;
    for (int i = 0; i < repeats; ++i) {
        Check(MPI_Barrier(gSession.data), "MPI_Barrier");
        auto t0 = Clock::now();
        ReduceSums(v.data(), v.size());
        Check(MPI_Barrier(gSession.data), "MPI_Barrier");   // the root has every rank's data
        sum += Seconds(t0);
    }
    return sum / std::max(1, repeats);
}

#endif  // LUCERNA_HAVE_MPI

}  // namespace lu

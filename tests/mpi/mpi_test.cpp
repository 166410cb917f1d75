// Lucerna distributed rendering tests (render/distributed.h): `mpirun -np 2 lucerna render` against
// one process with the same seed and pass count (path, regpath), resume 2 -> 1 and 1 -> 2 ranks,
// SIGTERM to rank 0 (the passes kept are a prefix), a rank killed (the last checkpoint stays valid).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "lucerna/image/image.h"
#include "lucerna/render/film.h"
#include "support/test_support.h"

namespace lu::test {

namespace {

const std::string kScene = SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt");

std::vector<std::string> MpiRun(int ranks, const std::vector<std::string> &args) {
    std::vector<std::string> argv = {LUCERNA_MPIEXEC};
    std::istringstream flags(LUCERNA_MPIEXEC_FLAGS);   // space-separated
    for (std::string f; flags >> f;) argv.push_back(f);
    argv.insert(argv.end(), {"-np", std::to_string(ranks), LucernaBinary()});
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
}

std::vector<std::string> Local(const std::vector<std::string> &args) {
    std::vector<std::string> argv = {LucernaBinary()};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
}

std::vector<std::string> RenderArgs(const std::string &integrator, int spp, const std::string &out,
                                    std::vector<std::string> extra = {}, int seed = 7, const char *res = "32x32") {
    std::vector<std::string> a = {"render", kScene, "--res", res, "--spp", std::to_string(spp), "--seed", std::to_string(seed),
                                  "--integrator", integrator, "-o", out};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

// Equal up to the order of floating-point sums. Film sums (double): each is a sum of the same
// float samples in another order (per rank, then across ranks), so they agree to a few ulps of
// double: |a - b| <= 1e-12 max(|a|, |b|) + 1e-14 max|sum|. The resolved image (float) then agrees
// to about one float ulp: |a - b| <= 1e-5 max(|a|, |b|) + 1e-7 max|value| (1e-5 relative: ~80 ulps).
::testing::AssertionResult SameUpToSumOrder(const std::vector<double> &a, const std::vector<double> &b, double rel,
                                            double absOfMax) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
    double maxAbs = 0;
    for (double v : b) maxAbs = std::max(maxAbs, std::abs(v));
    size_t bad = 0, worst = 0;
    double worstExcess = 0, maxRel = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        double bound = rel * std::max(std::abs(a[i]), std::abs(b[i])) + absOfMax * maxAbs;
        double d = std::abs(a[i] - b[i]);
        if (d > 0) maxRel = std::max(maxRel, d / std::max(std::abs(a[i]), std::abs(b[i])));
        if (!(d <= bound)) {
            if (bad == 0 || d - bound > worstExcess) { worst = i; worstExcess = d - bound; }
            ++bad;
        }
    }
    std::printf("  %zu values, largest relative difference %.3g (bound %.0e relative + %.0e of the largest)\n", a.size(),
                maxRel, rel, absOfMax);
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << bad << " of " << a.size() << " values differ beyond the bound; worst at " << worst
                                         << ": " << a[worst] << " vs " << b[worst];
}

::testing::AssertionResult SameImages(const std::string &pa, const std::string &pb) {
    ImageMetadata ma, mb;
    Image a = ReadImage(pa, false, &ma), b = ReadImage(pb, false, &mb);
    if (ma["lucerna.spp"] != mb["lucerna.spp"])
        return ::testing::AssertionFailure() << "spp " << ma["lucerna.spp"] << " vs " << mb["lucerna.spp"];
    std::vector<double> va(a.pixels.begin(), a.pixels.end()), vb(b.pixels.begin(), b.pixels.end());
    return SameUpToSumOrder(va, vb, 1e-5, 1e-7);
}

::testing::AssertionResult SameCheckpoints(const std::string &pa, const std::string &pb) {
    FilmAccumulator a, b;
    CheckpointInfo ia, ib;
    LoadCheckpoint(pa, &a, &ia);
    LoadCheckpoint(pb, &b, &ib);
    if (a.passes != b.passes) return ::testing::AssertionFailure() << "passes " << a.passes << " vs " << b.passes;
    return SameUpToSumOrder(a.xyzw, b.xyzw, 1e-12, 1e-14);
}

// "mpi: 2 ranks, passes per rank A B, R reductions" (rank 0's log line).
bool ParseLoadLine(const std::string &log, std::vector<int> *perRank, int *reductions) {
    std::smatch m;
    if (!std::regex_search(log, m, std::regex("mpi: (\\d+) ranks, passes per rank((?: \\d+)+), (\\d+) reductions"))) return false;
    std::istringstream is(m[2].str());
    perRank->clear();
    for (int n; is >> n;) perRank->push_back(n);
    *reductions = std::stoi(m[3].str());
    return int(perRank->size()) == std::stoi(m[1].str());
}

std::string Meta(const std::string &exr, const std::string &key) {
    ImageMetadata meta;
    ReadImage(exr, false, &meta);
    return meta[key];
}

// Starts argv with stdout+stderr into `log`; returns the pid.
pid_t Spawn(const std::vector<std::string> &argv, const std::string &log) {
    pid_t pid = fork();
    if (pid == 0) {
        FILE *f = freopen(log.c_str(), "w", stdout);
        (void)f;
        dup2(STDOUT_FILENO, STDERR_FILENO);
        std::vector<char *> args;
        for (const std::string &a : argv) args.push_back(const_cast<char *>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        _exit(127);
    }
    return pid;
}

int Wait(pid_t pid) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The pid of MPI rank `rank` among the launcher's children (Open MPI sets OMPI_COMM_WORLD_RANK).
pid_t RankPid(pid_t launcher, int rank) {
    std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
    for (const auto &task : std::filesystem::directory_iterator("/proc/" + std::to_string(launcher) + "/task")) {
        std::ifstream children(task.path() / "children");
        for (pid_t child; children >> child;) {
            std::ifstream env("/proc/" + std::to_string(child) + "/environ");
            std::string var;
            while (std::getline(env, var, '\0'))
                if (var == want) return child;
        }
    }
    return -1;
}

// Ends a launched job if a test leaves early: its ranks first (they would outlive the launcher).
struct JobGuard {
    pid_t launcher;
    ~JobGuard() {
        int status = 0;
        if (launcher <= 0 || waitpid(launcher, &status, WNOHANG) != 0) return;
        for (int rank = 0; rank < 2; ++rank)
            if (pid_t p = RankPid(launcher, rank); p > 0) kill(p, SIGKILL);
        kill(launcher, SIGKILL);
        waitpid(launcher, &status, 0);
    }
};

bool WaitForFile(const std::string &path, double seconds) {
    auto t0 = std::chrono::steady_clock::now();
    while (!std::filesystem::exists(path)) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
}

}  // namespace

// Two ranks (with reductions every 20 ms: several syncs) give one process's image and sums.
class MpiMatches : public ::testing::TestWithParam<const char *> {};

TEST_P(MpiMatches, OneProcessWithTheSameSeedAndPassCount) {
    std::string integrator = GetParam();
    std::string dir = TempDir("mpi_match_" + integrator);
    // 64x64: enough work that rank 0 cannot finish every pass before rank 1 asks for its first.
    auto one = RunProcess(Local(RenderArgs(integrator, 24, dir + "/one.exr", {"-q", "--checkpoint", dir + "/one.ckpt"}, 7, "64x64")));
    ASSERT_EQ(one.exitCode, 0) << one.output;
    auto two = RunProcess(MpiRun(2, RenderArgs(integrator, 24, dir + "/two.exr",
                                               {"--checkpoint", dir + "/two.ckpt", "--checkpoint-every", "0.02"}, 7, "64x64")));
    ASSERT_EQ(two.exitCode, 0) << two.output;
    std::vector<int> perRank;
    int reductions = 0;
    ASSERT_TRUE(ParseLoadLine(two.output, &perRank, &reductions)) << two.output;
    ASSERT_EQ(perRank.size(), 2u);
    EXPECT_EQ(perRank[0] + perRank[1], 24);
    EXPECT_GT(perRank[1], 0) << "rank 1 rendered nothing: the test would not show a distributed render";
    EXPECT_GE(reductions, 1);
    EXPECT_EQ(Meta(dir + "/two.exr", "lucerna.spp"), "24");
    EXPECT_TRUE(SameCheckpoints(dir + "/two.ckpt", dir + "/one.ckpt"));
    EXPECT_TRUE(SameImages(dir + "/two.exr", dir + "/one.exr"));
    // The bound is not loose: another seed breaks it.
    auto other = RunProcess(Local(RenderArgs(integrator, 24, dir + "/other.exr", {"-q"}, 8, "64x64")));
    ASSERT_EQ(other.exitCode, 0) << other.output;
    EXPECT_FALSE(SameImages(dir + "/other.exr", dir + "/one.exr"));
}

INSTANTIATE_TEST_SUITE_P(Integrators, MpiMatches, ::testing::Values("path", "regpath"));

// A checkpoint of 2 ranks continues in 1 process, and one of 1 process in 2 ranks: both give the
// uninterrupted render.
TEST(Mpi, ResumeAcrossRankCounts) {
    std::string dir = TempDir("mpi_resume");
    auto ref = RunProcess(Local(RenderArgs("regpath", 20, dir + "/ref.exr", {"-q"})));
    ASSERT_EQ(ref.exitCode, 0) << ref.output;

    auto a = RunProcess(MpiRun(2, RenderArgs("regpath", 9, dir + "/a.exr", {"-q", "--checkpoint", dir + "/two.ckpt"})));
    ASSERT_EQ(a.exitCode, 0) << a.output;
    auto a2 = RunProcess(Local(RenderArgs("regpath", 20, dir + "/two_then_one.exr", {"-q", "--resume", dir + "/two.ckpt"})));
    ASSERT_EQ(a2.exitCode, 0) << a2.output;
    EXPECT_TRUE(SameImages(dir + "/two_then_one.exr", dir + "/ref.exr"));

    auto b = RunProcess(Local(RenderArgs("regpath", 9, dir + "/b.exr", {"-q", "--checkpoint", dir + "/one.ckpt"})));
    ASSERT_EQ(b.exitCode, 0) << b.output;
    auto b2 = RunProcess(MpiRun(2, RenderArgs("regpath", 20, dir + "/one_then_two.exr", {"-q", "--resume", dir + "/one.ckpt"})));
    ASSERT_EQ(b2.exitCode, 0) << b2.output;
    EXPECT_TRUE(SameImages(dir + "/one_then_two.exr", dir + "/ref.exr"));
}

// SIGTERM to rank 0: every rank finishes the passes it holds, rank 0 writes the image and a
// checkpoint of passes [0, P) (exit 3); resuming it in one process to P + 3 passes gives the
// uninterrupted render of P + 3 passes, which holds only if exactly the passes 0..P-1 were summed.
TEST(Mpi, SignalToRankZeroKeepsAPrefixOfPasses) {
    std::string dir = TempDir("mpi_signal");
    pid_t launcher = Spawn(MpiRun(2, RenderArgs("path", 1000000, dir + "/sig.exr",
                                                {"-q", "--checkpoint", dir + "/sig.ckpt", "--checkpoint-every", "0.2"})),
                           dir + "/sig.log");
    JobGuard guard{launcher};
    ASSERT_TRUE(WaitForFile(dir + "/sig.ckpt", 30)) << "no periodic checkpoint";
    pid_t rank0 = RankPid(launcher, 0);
    ASSERT_GT(rank0, 0);
    kill(rank0, SIGTERM);
    std::stringstream log;
    int rc = Wait(launcher);
    log << std::ifstream(dir + "/sig.log").rdbuf();
    ASSERT_EQ(rc, 3) << log.str();
    EXPECT_EQ(Meta(dir + "/sig.exr", "lucerna.interrupted"), "1");
    FilmAccumulator film;
    CheckpointInfo info;
    LoadCheckpoint(dir + "/sig.ckpt", &film, &info);
    ASSERT_GT(film.passes, 0u);
    EXPECT_EQ(Meta(dir + "/sig.exr", "lucerna.spp"), std::to_string(film.passes));
    int more = int(film.passes) + 3;
    auto resumed = RunProcess(Local(RenderArgs("path", more, dir + "/resumed.exr", {"-q", "--resume", dir + "/sig.ckpt"})));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    auto ref = RunProcess(Local(RenderArgs("path", more, dir + "/ref.exr", {"-q"})));
    ASSERT_EQ(ref.exitCode, 0) << ref.output;
    EXPECT_TRUE(SameImages(dir + "/resumed.exr", dir + "/ref.exr"));
}

// A rank that dies ends the job with an error (the launcher's exit status is not 0); the last
// periodic checkpoint is whole (written to a temporary file and renamed) and resumable.
TEST(Mpi, DeadRankLeavesTheLastCheckpoint) {
    std::string dir = TempDir("mpi_dead_rank");
    pid_t launcher = Spawn(MpiRun(2, RenderArgs("path", 1000000, dir + "/dead.exr",
                                                {"-q", "--checkpoint", dir + "/dead.ckpt", "--checkpoint-every", "0.2"})),
                           dir + "/dead.log");
    JobGuard guard{launcher};
    ASSERT_TRUE(WaitForFile(dir + "/dead.ckpt", 30)) << "no periodic checkpoint";
    pid_t rank1 = RankPid(launcher, 1);
    ASSERT_GT(rank1, 0);
    kill(rank1, SIGKILL);
    int rc = Wait(launcher);
    std::stringstream log;
    log << std::ifstream(dir + "/dead.log").rdbuf();
    EXPECT_NE(rc, 0) << log.str();
    EXPECT_NE(log.str().find("rank 1"), std::string::npos) << log.str();
    EXPECT_FALSE(std::filesystem::exists(dir + "/dead.exr"));
    FilmAccumulator film;
    CheckpointInfo info;
    ASSERT_NO_THROW(LoadCheckpoint(dir + "/dead.ckpt", &film, &info));
    ASSERT_GT(film.passes, 0u);
    int more = int(film.passes) + 2;
    auto resumed = RunProcess(Local(RenderArgs("path", more, dir + "/resumed.exr", {"-q", "--resume", dir + "/dead.ckpt"})));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    auto ref = RunProcess(Local(RenderArgs("path", more, dir + "/ref.exr", {"-q"})));
    ASSERT_EQ(ref.exitCode, 0) << ref.output;
    EXPECT_TRUE(SameImages(dir + "/resumed.exr", dir + "/ref.exr"));
}

// --time is one wall-clock budget for the job: rank 0 stops handing out blocks at it, and blocks are
// sized to end by it (the job's seconds land just past the budget, not a block or a rank later).
TEST(Mpi, TimeIsOneBudgetForTheJob) {
    std::string dir = TempDir("mpi_time");
    auto r = RunProcess(MpiRun(2, {"render", kScene, "--res", "32x32", "--time", "1", "-q", "-o", dir + "/t.exr",
                                   "--stats-json", dir + "/t.json"}));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::stringstream js;
    js << std::ifstream(dir + "/t.json").rdbuf();
    std::smatch m;
    std::string text = js.str();
    ASSERT_TRUE(std::regex_search(text, m, std::regex("\"seconds\": ([0-9.eE+-]+)"))) << text;
    double seconds = std::stod(m[1].str());
    EXPECT_GE(seconds, 1.0);
    EXPECT_LT(seconds, 1.6) << "blocks ran far past the budget";
    EXPECT_NE(text.find("\"interrupted\": false"), std::string::npos) << text;
    EXPECT_GT(std::stoi(Meta(dir + "/t.exr", "lucerna.spp")), 0);
}

// Bad input on every rank: the job exits with 2 and the rank's message.
TEST(Mpi, MissingSceneIsBadInput) {
    std::string dir = TempDir("mpi_bad_input");
    auto r = RunProcess(MpiRun(2, {"render", dir + "/missing.pbrt", "-o", dir + "/x.exr"}));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("missing.pbrt"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.exr"));
}

}  // namespace lu::test

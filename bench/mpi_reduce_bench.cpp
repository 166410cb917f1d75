// Lucerna benchmark: the time of one film reduction of the distributed mode (render/distributed.h),
// MPI_Reduce (sum into rank 0) of a WxH film's 4 doubles per pixel. Run under mpirun:
//   mpirun -np K build/bench/lucerna_mpi_reduce_bench [W H REPEATS]   (default 1920 1080 20)
#include <cstdio>
#include <cstdlib>

#include "lucerna/render/distributed.h"

int main(int argc, char **argv) {
    lu::MpiSession mpi;
    if (!lu::MpiSession::Active()) {
        std::fprintf(stderr, "run under mpirun (this build %s MPI)\n", lu::HaveMpi() ? "has" : "has no");
        return 2;
    }
    int w = argc > 2 ? std::atoi(argv[1]) : 1920, h = argc > 2 ? std::atoi(argv[2]) : 1080;
    int repeats = argc > 3 ? std::atoi(argv[3]) : 20;
    size_t doubles = size_t(w) * size_t(h) * 4;
    lu::TimeFilmReduction(doubles, 2);   // warm-up: buffers, shared-memory segments
    double s = lu::TimeFilmReduction(doubles, repeats);
    if (lu::MpiSession::Rank() == 0)
        std::printf("ranks %d  film %dx%d (%.1f MB of sums)  reduction %.2f ms  (%.2f GB/s into rank 0)\n",
                    lu::MpiSession::Size(), w, h, double(doubles) * 8e-6, s * 1e3,
                    double(doubles) * 8 * (lu::MpiSession::Size() - 1) / s * 1e-9);
    return mpi.Finish(0);
}

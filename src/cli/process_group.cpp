#include "process_group.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#ifdef ERPT_WITH_MPI
#include <mpi.h>
#endif

namespace erpt::cli {

namespace {
const ProcessGroup* currentGroup = nullptr;

// mpirun (Open MPI, MPICH, or a PMIx launcher) tells its processes the job's size.
int launchedSize() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}
}  // namespace

ProcessGroup::ProcessGroup(int& argc, char**& argv) {
  currentGroup = this;
  const int launched = launchedSize();
#ifdef ERPT_WITH_MPI
  if (launched > 1) {
    MPI_Init(&argc, &argv);
    joined_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
#else
  (void)argc, (void)argv;
  if (launched > 1) {
    // K copies rendering the same image into the same file would only waste the machines.
    std::fprintf(stderr, "erpt: error: launched as one of %d processes, but this erpt was built without MPI\n", launched);
    std::exit(2);
  }
#endif
}

ProcessGroup::~ProcessGroup() {
#ifdef ERPT_WITH_MPI
  if (joined_) MPI_Finalize();
#endif
  currentGroup = nullptr;
}

const ProcessGroup& ProcessGroup::current() {
  if (!currentGroup) throw std::logic_error("no process group");
  return *currentGroup;
}

RenderShare ProcessGroup::share() const {
  RenderShare share;
  share.rank = rank_;
  share.ranks = size_;
#ifdef ERPT_WITH_MPI
  if (size_ > 1)
    share.sumAcrossRanks = [size = size_, rank = rank_](std::vector<double>& values) {
      const int n = int(values.size());
      if (rank == 0) {
        std::vector<double> other(values.size());
        for (int r = 1; r < size; ++r) {  // rank order: the same sum on every run
          MPI_Recv(other.data(), n, MPI_DOUBLE, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          for (int i = 0; i < n; ++i) values[size_t(i)] += other[size_t(i)];
        }
      } else {
        MPI_Send(values.data(), n, MPI_DOUBLE, 0, 0, MPI_COMM_WORLD);
      }
      MPI_Bcast(values.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    };
#endif
  return share;
}

void ProcessGroup::abortAll(int status) const {
#ifdef ERPT_WITH_MPI
  if (joined_) MPI_Abort(MPI_COMM_WORLD, status);
#endif
  std::exit(status);
}

}  // namespace erpt::cli

// The processes of an MPI job (`mpirun -n K erpt render ...`; docs/long-renders.md, "Many
// machines"). With MPI (found at build time: ERPT_WITH_MPI) and launched by mpirun, the group
// is the job's ranks; otherwise it is this process alone.
#pragma once

#include "erpt/render.h"

namespace erpt::cli {

class ProcessGroup {
 public:
  ProcessGroup(int& argc, char**& argv);  // joins the job (MPI_Init) when launched by mpirun
  ~ProcessGroup();
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;
  static const ProcessGroup& current();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool leader() const { return rank_ == 0; }
  // This rank's share of a render: sumAcrossRanks adds in rank order on rank 0 and sends the
  // total back to every rank, so the result does not depend on message timing.
  RenderShare share() const;
  // Ends every rank of the job (after an error on one of them: the others would wait for it).
  [[noreturn]] void abortAll(int status) const;

 private:
  int rank_ = 0, size_ = 1;
  [[maybe_unused]] bool joined_ = false;  // MPI_Init was called (MPI builds only)
};

}  // namespace erpt::cli

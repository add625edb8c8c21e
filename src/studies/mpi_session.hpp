#pragma once
// MPI for distributed campaigns, only when the program was started by an MPI launcher (mpirun,
// srun): the same binary runs alone without it. The messages are text (JSON) between rank 0, the
// coordinator, and the workers of every rank; a worker's tag names its thread, so several threads
// of a rank can wait for their own replies.
#include <string>
#include <vector>

namespace biped {

class MpiSession {
 public:
  // True when the environment shows an MPI launcher (OpenMPI's OMPI_COMM_WORLD_SIZE, PMI's
  // PMI_SIZE, PMIx's PMIX_RANK, Slurm's srun with its PMI) with more than one process or a rank set.
  static bool launched_under_mpi();

  // Initializes MPI (asking for concurrent calls from several threads) when launched under MPI;
  // otherwise a session of one rank that calls nothing.
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Whether threads other than the main one may call MPI (else one worker thread per rank).
  bool threads_may_communicate() const { return thread_multiple_; }

  void send(int destination, int tag, const std::string& text) const;
  std::string receive(int source, int tag) const;
  // A waiting message from any rank and tag, when there is one.
  bool poll(int& source, int& tag) const;
  // Rank 0 gets every rank's value, in rank order (others get an empty list).
  std::vector<int> gather(int value) const;
  // Ends every rank of the job (a failure on one rank would leave the others waiting).
  [[noreturn]] void abort(int code) const;

 private:
  bool active_ = false;
  bool thread_multiple_ = false;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace biped

#pragma once
// The campaign engine: runs the items of a study (scenario runs, push-map cells, ...) on every core
// and, under MPI, on every rank, and keeps each finished item in the campaign database at once.
//
// Rank 0 is the coordinator: it alone opens the database, hands out the items not yet finished one
// at a time (a slow item holds no other), and writes each result in its own transaction as it
// arrives. Its own worker threads and the other ranks' worker threads ask it for items. An item's
// result depends only on its index, so the database is the same whatever the number of threads or
// ranks, and a campaign run again after a kill continues with the unfinished items.
#include <functional>
#include <iosfwd>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "io/campaign_database.hpp"
#include "studies/mpi_session.hpp"

namespace biped {

// What a study runs. Both functions must be safe to call from several threads at once (each call
// builds its own simulation and controller) and depend on nothing but the index.
class CampaignWork {
 public:
  virtual ~CampaignWork() = default;
  virtual long size() const = 0;
  // Names the study's inputs; a database holding another identity is refused.
  virtual std::string identity() const = 0;
  // The item's parameters and reproduce command (cheap; no simulation).
  virtual CampaignRow describe(long index) const = 0;
  // Runs the item; fills `row.result`. May throw: the engine records the error and goes on.
  virtual void run(long index, CampaignRow& row) const = 0;
};

struct CampaignEngineOptions {
  int jobs = 0;                       // worker threads on this rank; 0: every core (1 per rank under MPI)
  std::ostream* progress = nullptr;   // progress lines (coordinator only)
  std::string label = "campaign";     // the progress lines' prefix
};

struct CampaignEngineOutcome {
  bool coordinator = true;   // rank 0: the database is complete and this rank writes the outputs
  long total = 0;
  long finished_before = 0;  // found in the database at the start
  long ran = 0;              // finished in this session
  int ranks = 1;
  int workers = 1;           // worker threads on all ranks
  double wall_time_s = 0.0;
  double storing_s = 0.0;    // the coordinator's time spent receiving and storing results (database, JSON)
};

// The number of cores this process may run on.
int available_cores();

// Runs every unfinished item of `work` into the database at `database_path` (rank 0 only opens it).
CampaignEngineOutcome run_campaign_engine(const CampaignWork& work, const std::string& database_path,
                                          const MpiSession& mpi, const CampaignEngineOptions& options);

// For studies whose results live in memory (speed sweep, step-table search): fn(0..count-1) on
// `jobs` threads (0: every core), results in index order. An exception from any call is rethrown.
template <class T>
std::vector<T> parallel_map(long count, int jobs, const std::function<T(long)>& fn) {
  std::vector<T> results(static_cast<std::size_t>(count));
  std::mutex mutex;
  long next = 0;
  std::exception_ptr failure;
  auto worker = [&] {
    for (;;) {
      long i = 0;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= count || failure) return;
        i = next++;
      }
      try {
        results[static_cast<std::size_t>(i)] = fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  const long threads = std::min<long>(count, jobs > 0 ? jobs : available_cores());
  std::vector<std::thread> pool;
  for (long t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

}  // namespace biped

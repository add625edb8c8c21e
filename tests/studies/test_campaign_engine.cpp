// The campaign engine (studies/campaign_engine.cpp) on a study without simulations: the same
// database whatever the number of threads, errors and non-finite results recorded while the rest
// goes on, finished items never run again, parallel_map in index order.
#include "studies/campaign_engine.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "test_support.hpp"

namespace biped {
namespace {

// Item i: a result computed from i alone, after a pause that differs between items (so that
// threads finish out of order); item 3 throws, item 5 gives NaN.
class ToyWork final : public CampaignWork {
 public:
  explicit ToyWork(long n) : n_(n) {}
  long size() const override { return n_; }
  std::string identity() const override { return "toy " + std::to_string(n_); }
  CampaignRow describe(long i) const override {
    CampaignRow r;
    r.parameters = {{"x", 0.5 * i}};
    r.command = "toy " + std::to_string(i);
    return r;
  }
  void run(long i, CampaignRow& row) const override {
    ++calls;
    std::this_thread::sleep_for(std::chrono::milliseconds((i * 7) % 5));
    if (i == 3) throw std::runtime_error("item 3 failed");
    row.result = {{"fell", i % 4 == 0}, {"distance_m", i == 5 ? std::nan("") : std::sqrt(static_cast<double>(i))}};
  }
  mutable std::atomic<int> calls{0};

 private:
  long n_;
};

std::vector<CampaignRow> run_toy(const std::string& name, long n, int jobs, ToyWork* work = nullptr) {
  const auto path = (test::fresh_dir(name.c_str()) / "c.sqlite").string();
  ToyWork local(n);
  const MpiSession mpi;
  CampaignEngineOptions options;
  options.jobs = jobs;
  const CampaignEngineOutcome outcome = run_campaign_engine(work ? *work : local, path, mpi, options);
  EXPECT_TRUE(outcome.coordinator);
  EXPECT_EQ(outcome.ran, n);
  return CampaignDatabase(path).rows();
}

TEST(CampaignEngine, SameRowsWhateverTheNumberOfThreads) {
  const auto one = run_toy("engine-1", 12, 1), three = run_toy("engine-3", 12, 3);
  ASSERT_EQ(one.size(), 12u);
  ASSERT_EQ(three.size(), 12u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].run, static_cast<long>(i));
    EXPECT_EQ(one[i].status, three[i].status);
    EXPECT_EQ(one[i].error, three[i].error);
    EXPECT_EQ(one[i].result, three[i].result);
    EXPECT_EQ(one[i].parameters, three[i].parameters);
    EXPECT_EQ(one[i].command, three[i].command);
  }
}

TEST(CampaignEngine, ErrorsAndNonFiniteResultsAreRecordedAndTheRestGoesOn) {
  const auto rows = run_toy("engine-errors", 8, 2);
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[3].status, "error");
  EXPECT_EQ(rows[3].error, "item 3 failed");
  EXPECT_EQ(rows[3].command, "toy 3");
  EXPECT_EQ(rows[5].status, "error");
  EXPECT_NE(rows[5].error.find("distance_m"), std::string::npos);
  for (long i : {0, 1, 2, 4, 6, 7}) EXPECT_EQ(rows[static_cast<std::size_t>(i)].status, "ok") << i;
  EXPECT_GE(rows[7].wall_time_s, 0.0);
  EXPECT_FALSE(rows[7].host.empty());
}

TEST(CampaignEngine, FinishedItemsAreNotRunAgain) {
  const auto dir = test::fresh_dir("engine-resume");
  const auto path = (dir / "c.sqlite").string();
  ToyWork work(6);
  {
    CampaignDatabase db(path);
    db.claim(work.identity(), work.size());
    for (long i : {1, 4}) {
      CampaignRow r = work.describe(i);
      r.run = i;
      r.status = "ok";
      r.result = {{"fell", false}, {"marker", "from before"}};
      db.insert(r);
    }
  }
  const MpiSession mpi;
  const CampaignEngineOutcome outcome = run_campaign_engine(work, path, mpi, CampaignEngineOptions{2, nullptr, "t"});
  EXPECT_EQ(outcome.finished_before, 2);
  EXPECT_EQ(outcome.ran, 4);
  EXPECT_EQ(work.calls.load(), 4);
  const auto rows = CampaignDatabase(path).rows();
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[4].result["marker"], "from before");
  // Run once more: nothing left.
  EXPECT_EQ(run_campaign_engine(work, path, mpi, CampaignEngineOptions{2, nullptr, "t"}).ran, 0);
  EXPECT_EQ(work.calls.load(), 4);
}

TEST(CampaignEngine, RefusesADatabaseOfAnotherStudy) {
  const auto path = (test::fresh_dir("engine-other") / "c.sqlite").string();
  const MpiSession mpi;
  run_campaign_engine(ToyWork(2), path, mpi, CampaignEngineOptions{1, nullptr, "t"});
  EXPECT_ANY_THROW(run_campaign_engine(ToyWork(3), path, mpi, CampaignEngineOptions{1, nullptr, "t"}));
}

TEST(ParallelMap, ResultsInIndexOrderAndExceptionsRethrown) {
  const std::vector<long> squares = parallel_map<long>(50, 3, [](long i) { return i * i; });
  for (long i = 0; i < 50; ++i) EXPECT_EQ(squares[static_cast<std::size_t>(i)], i * i);
  EXPECT_THROW(parallel_map<int>(10, 2, [](long i) -> int { if (i == 7) throw std::runtime_error("x"); return 0; }),
               std::runtime_error);
}

}  // namespace
}  // namespace biped

// `biped campaign` (studies/campaign.cpp) end to end on tiny campaigns: the same database with 1 or
// 2 threads and under `mpirun -n 2`, each row reproduced by its command, a campaign killed mid-way
// and run again equal to an uninterrupted one, bad campaign files refused with exit status 2.
#include "studies/campaign.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <fcntl.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "io/campaign_database.hpp"
#include "io/yaml_reader.hpp"
#include "test_support.hpp"

extern char** environ;

namespace biped {
namespace {

namespace fs = std::filesystem;

// `runs` runs of `duration` simulated seconds of LOLA starting to walk, with random pushes.
std::string tiny_campaign(const fs::path& dir, int runs, double duration) {
  const std::string path = (dir / "tiny.yaml").string();
  std::ofstream(path) << "name: tiny\nscenario: " << test::source_path("config/scenarios/lola-walk.yaml")
                      << "\nruns: " << runs << "\nseed: 9\nset: {duration: " << duration << "}\n"
                      << "vary:\n  commands.1.vx: {uniform: [0.1, 0.4]}\n  sensors.noise: {choice: [true, false]}\n"
                      << "generators:\n  pushes:\n    count: [0, 1]\n    items:\n"
                      << "      - {type: push, t: {uniform: [0.3, 0.8]}, direction_deg: {uniform: [-180, 180]}, "
                         "impulse_Ns: {uniform: [0, 40]}}\n";
  return path;
}

int shell(const std::string& command) {
  const int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Everything but the wall time, host and rank.
void expect_same_rows(const std::vector<CampaignRow>& a, const std::vector<CampaignRow>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].run, b[i].run);
    EXPECT_EQ(a[i].status, b[i].status);
    EXPECT_EQ(a[i].error, b[i].error);
    EXPECT_EQ(a[i].parameters, b[i].parameters);
    EXPECT_EQ(a[i].command, b[i].command);
    EXPECT_EQ(a[i].result, b[i].result) << "run " << i;
  }
}

std::vector<CampaignRow> rows_of(const fs::path& out) { return CampaignDatabase((out / "campaign.sqlite").string()).rows(); }

TEST(Campaign, SameResultsWithOneOrTwoThreadsAndEachRowReproducedByItsCommand) {
  const fs::path dir = test::fresh_dir("campaign-jobs");
  const CampaignSpec spec = load_campaign_spec(tiny_campaign(dir, 4, 1.0));
  const MpiSession mpi;
  CampaignEngineOptions options;
  options.jobs = 1;
  const nlohmann::json one = run_campaign(spec, (dir / "one").string(), mpi, options);
  options.jobs = 2;
  const nlohmann::json two = run_campaign(spec, (dir / "two").string(), mpi, options);
  EXPECT_EQ(one["completed"], 4);
  EXPECT_EQ(two["workers"], 2);
  const auto rows = rows_of(dir / "one");
  expect_same_rows(rows, rows_of(dir / "two"));
  for (const char* file : {"results.csv", "summary.json", "report.html"}) EXPECT_TRUE(fs::exists(dir / "two" / file)) << file;

  // The command of a pushed run, through the binary, gives the stored result.
  const CampaignRow* pushed = nullptr;
  for (const CampaignRow& r : rows) {
    if (r.parameters["pushes.count"] == 1) pushed = &r;
  }
  ASSERT_NE(pushed, nullptr);
  std::string command = pushed->command;
  command.replace(0, std::string("build/biped").size(), BIPED_BINARY);
  ASSERT_EQ(shell("cd " + test::source_path("") + " && " + command + " --out " + (dir / "again").string() + " >/dev/null"), 0);
  nlohmann::json summary = nlohmann::json::parse(slurp(dir / "again" / "summary.json"));
  EXPECT_EQ(summary["distance_m"], pushed->result["distance_m"]);
  EXPECT_EQ(summary["fell"], pushed->result["fell"]);
  EXPECT_EQ(summary["upper_body_tilt_deg"]["max"], pushed->result["upper_body_tilt_deg"]["max"]);
}

TEST(Campaign, KilledMidwayAndRunAgainEqualsAnUninterruptedCampaign) {
  const fs::path dir = test::fresh_dir("campaign-kill");
  const std::string spec = tiny_campaign(dir, 16, 1.5);
  const std::string out = (dir / "killed").string();
  const std::string binary = BIPED_BINARY;
  std::vector<std::string> args = {binary, "campaign", spec, "--out", out, "--jobs", "2"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Kill it once a few runs are in the database.
  std::size_t stored = 0;
  for (int i = 0; i < 6000 && stored < 3; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (fs::exists(fs::path(out) / "campaign.sqlite")) {
      try {
        stored = rows_of(out).size();
      } catch (const std::exception&) {
        stored = 0;  // tables not yet created
      }
    }
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the campaign ended before it was killed";
  const std::size_t before = rows_of(out).size();
  EXPECT_GE(before, 3u);
  EXPECT_LT(before, 16u);
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));

  ASSERT_EQ(shell(binary + " campaign " + spec + " --out " + out + " --jobs 2 >/dev/null 2>" + (dir / "err.txt").string()), 0);
  EXPECT_NE(slurp(dir / "err.txt").find("from before"), std::string::npos);
  const std::string whole = (dir / "whole").string();
  ASSERT_EQ(shell(binary + " campaign " + spec + " --out " + whole + " --jobs 1 >/dev/null 2>&1"), 0);
  expect_same_rows(rows_of(out), rows_of(whole));
  const nlohmann::json summary = nlohmann::json::parse(slurp(fs::path(out) / "summary.json"));
  EXPECT_EQ(summary["finished"], 16);
  EXPECT_EQ(summary["finished_before_this_session"], before);
}

TEST(Campaign, UnderMpirunWithTwoRanksGivesTheSameResults) {
  if (shell("command -v mpirun >/dev/null") != 0) GTEST_SKIP() << "OpenMPI's mpirun is not installed";
  const fs::path dir = test::fresh_dir("campaign-mpi");
  const std::string spec = tiny_campaign(dir, 6, 1.0);
  const std::string binary = BIPED_BINARY;
  ASSERT_EQ(shell("mpirun --allow-run-as-root --oversubscribe -n 2 " + binary + " campaign " + spec + " --out " +
                  (dir / "mpi").string() + " >/dev/null 2>" + (dir / "err.txt").string()), 0)
      << slurp(dir / "err.txt");
  ASSERT_EQ(shell(binary + " campaign " + spec + " --out " + (dir / "local").string() + " --jobs 2 >/dev/null 2>&1"), 0);
  const auto rows = rows_of(dir / "mpi");
  expect_same_rows(rows, rows_of(dir / "local"));
  const nlohmann::json summary = nlohmann::json::parse(slurp(dir / "mpi" / "summary.json"));
  EXPECT_EQ(summary["ranks"], 2);
  EXPECT_EQ(summary["workers"], 2);
  std::set<int> ranks;
  for (const CampaignRow& r : rows) ranks.insert(r.rank);
  EXPECT_EQ(ranks, (std::set<int>{0, 1}));
}

TEST(Campaign, BadCampaignFilesExitWithStatusTwoAndOneLine) {
  const fs::path dir = test::fresh_dir("campaign-bad");
  const std::string base = "scenario: " + test::source_path("config/scenarios/lola-walk.yaml") + "\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "runs: 2\nvariations: {}\n", "variations"},
      {base + "runs: 2\nvary:\n  commands.1.vx: {uniform: [0.4, 0.1]}\n", "vary.commands.1.vx"},
      {base + "runs: 2\nvary:\n  commands.1.vx: {normal: {mean: 0.2, std: 0.01, min: 1, max: 2}}\n", "vary.commands.1.vx"},
  };
  for (const auto& [text, key] : cases) {
    const std::string path = (dir / "bad.yaml").string();
    std::ofstream(path) << text;
    const std::string err = (dir / "err.txt").string();
    EXPECT_EQ(shell(std::string(BIPED_BINARY) + " campaign " + path + " --out " + (dir / "out").string() + " 2>" + err), 2);
    const std::string message = slurp(err);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  // --set overrides campaign keys too, and is checked the same way.
  const std::string path = (dir / "good.yaml").string();
  std::ofstream(path) << base << "runs: 2\nvary:\n  commands.1.vx: {uniform: [0.1, 0.4]}\n";
  EXPECT_EQ(shell(std::string(BIPED_BINARY) + " campaign " + path + " --out " + (dir / "out").string() +
                  " --set runs=-1 2>/dev/null"), 2);
}

}  // namespace
}  // namespace biped

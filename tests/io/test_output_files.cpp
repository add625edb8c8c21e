#include "io/output_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

using test::fresh_dir;

TEST(AtomicOutputFile, NothingAppearsUnlessCommitted) {
  const fs::path dir = fresh_dir("atomic");
  {
    AtomicOutputFile file((dir / "log.csv").string());
    file.stream() << "partial";
  }
  EXPECT_TRUE(fs::is_empty(dir));
  {
    AtomicOutputFile file((dir / "log.csv").string());
    file.stream() << "whole";
    file.commit();
  }
  EXPECT_TRUE(fs::exists(dir / "log.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(PrepareOutputDirectory, AFileInThePathIsBadInput) {
  const fs::path dir = fresh_dir("prepare");
  std::ofstream(dir / "plain-file") << "x";
  EXPECT_THROW(prepare_output_directory((dir / "plain-file" / "out").string()), InputError);
  EXPECT_NO_THROW(prepare_output_directory((dir / "a" / "b").string()));
  EXPECT_TRUE(fs::is_empty(dir / "a" / "b"));
  fs::remove_all(dir);
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Run n leaves its files in DIR; each earlier run's are kept under DIR/previous/<k> (1: the one
// before), at most `keep` of them; other files in DIR stay where they are.
TEST(KeepPreviousRun, ShiftsEarlierRunsAndKeepsAtMostKeep) {
  const fs::path dir = fresh_dir("keep-previous");
  const std::vector<std::string> files = {"summary.json", "log.csv"};
  EXPECT_EQ(keep_previous_run(dir.string(), files, 2), "") << "nothing to keep yet";
  std::ofstream(dir / "notes.txt") << "mine";
  for (int run = 1; run <= 4; ++run) {
    if (run > 1) {
      EXPECT_EQ(keep_previous_run(dir.string(), files, 2), (dir / "previous" / "1").string());
    }
    std::ofstream(dir / "summary.json") << "run " << run;
    std::ofstream(dir / "log.csv") << "log " << run;
  }
  EXPECT_EQ(read(dir / "summary.json"), "run 4");
  EXPECT_EQ(read(dir / "previous" / "1" / "summary.json"), "run 3");
  EXPECT_EQ(read(dir / "previous" / "1" / "log.csv"), "log 3");
  EXPECT_EQ(read(dir / "previous" / "2" / "summary.json"), "run 2");
  EXPECT_FALSE(fs::exists(dir / "previous" / "3"));
  EXPECT_EQ(read(dir / "notes.txt"), "mine");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace biped

#include "io/output_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>

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

}  // namespace
}  // namespace biped

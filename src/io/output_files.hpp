#pragma once
// Output files are written whole or not at all: into a temporary name, renamed on commit().
#include <fstream>
#include <string>
#include <vector>

namespace biped {

class AtomicOutputFile {
 public:
  // Opens DIR/.NAME.tmp; throws InputError naming the path if it cannot be created.
  explicit AtomicOutputFile(const std::string& final_path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  std::ofstream& stream() { return out_; }
  // Flushes and renames to the final name; throws std::runtime_error on an I/O failure.
  void commit();

 private:
  std::string final_path_;
  std::string temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

// Creates the output directory (and parents) and checks it is writable; throws InputError.
void prepare_output_directory(const std::string& dir);

// Keeps an earlier run's files before a new run replaces them: moves those of `files` that exist in
// DIR into DIR/previous/1/, after shifting previous/1 to previous/2 and so on; at most `keep`
// earlier runs stay (the oldest is deleted). Returns DIR/previous/1, or "" when DIR held none of the files.
std::string keep_previous_run(const std::string& dir, const std::vector<std::string>& files, int keep);

}  // namespace biped

#pragma once
// Output files are written whole or not at all: into a temporary name, renamed on commit().
#include <fstream>
#include <string>

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

}  // namespace biped

#include "io/output_files.hpp"

#include <filesystem>
#include <stdexcept>

#include "io/yaml_reader.hpp"

namespace fs = std::filesystem;

namespace biped {

AtomicOutputFile::AtomicOutputFile(const std::string& final_path) : final_path_(final_path) {
  const fs::path p(final_path);
  temp_path_ = (p.parent_path() / ("." + p.filename().string() + ".tmp")).string();
  out_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(p.parent_path().string() + ": output folder is not writable (cannot create " + temp_path_ + ")");
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    fs::remove(temp_path_, ec);
  }
}

void AtomicOutputFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok) throw std::runtime_error("write failed: " + temp_path_);
  fs::rename(temp_path_, final_path_);
  committed_ = true;
}

void prepare_output_directory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError(dir + ": cannot create the output folder" + (ec ? " (" + ec.message() + ")" : ""));
  }
  const fs::path probe = fs::path(dir) / ".write-test.tmp";
  {
    std::ofstream test(probe);
    if (!test) throw InputError(dir + ": output folder is not writable");
  }
  fs::remove(probe, ec);
}

std::string keep_previous_run(const std::string& dir, const std::vector<std::string>& files, int keep) {
  const fs::path base(dir);
  bool any = false;
  for (const std::string& f : files) any = any || fs::exists(base / f);
  if (!any) return "";
  const fs::path previous = base / "previous";
  const auto slot = [&](int n) { return previous / std::to_string(n); };
  fs::remove_all(slot(keep));
  for (int n = keep - 1; n >= 1; --n) {
    if (fs::exists(slot(n))) fs::rename(slot(n), slot(n + 1));
  }
  fs::create_directories(slot(1));
  for (const std::string& f : files) {
    if (fs::exists(base / f)) fs::rename(base / f, slot(1) / f);
  }
  return slot(1).string();
}

}  // namespace biped

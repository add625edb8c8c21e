#pragma once
// Strict reading of YAML files: every value is checked, unknown keys are errors, and every error
// is one line naming the file, the key and (where known) the line.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace biped {

// Bad input (files, parameters, command-line values): the CLI exits with status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Loads a YAML file; throws InputError for a missing file or a syntax error (with its line).
YAML::Node load_yaml_file(const std::string& path);

// Applies one `--set KEY=VALUE` (KEY dotted, e.g. controller.stabilizer; list items by index,
// e.g. commands.1.vx) to a document. The value is parsed as YAML.
void apply_override(YAML::Node& root, const std::string& assignment);

// The parts of a dotted key ("commands.1.vx" -> commands, 1, vx).
std::vector<std::string> split_dotted_key(const std::string& key);

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& problem) const;

  // `map` must be a mapping (or absent) whose keys are all in `allowed`.
  void expect_keys(const YAML::Node& map, const std::string& where, const std::vector<std::string>& allowed) const;

  double number(const YAML::Node& map, const std::string& where, const char* key) const;
  double number_or(const YAML::Node& map, const std::string& where, const char* key, double fallback) const;
  double positive_or(const YAML::Node& map, const std::string& where, const char* key, double fallback) const;
  double non_negative_or(const YAML::Node& map, const std::string& where, const char* key, double fallback) const;
  long integer_or(const YAML::Node& map, const std::string& where, const char* key, long fallback) const;
  bool boolean_or(const YAML::Node& map, const std::string& where, const char* key, bool fallback) const;
  std::string text(const YAML::Node& map, const std::string& where, const char* key) const;
  std::string text_or(const YAML::Node& map, const std::string& where, const char* key, const std::string& fallback) const;
  Eigen::Vector3d vector3(const YAML::Node& map, const std::string& where, const char* key) const;
  Eigen::Vector3d vector3_or(const YAML::Node& map, const std::string& where, const char* key,
                             const Eigen::Vector3d& fallback) const;
  // A list of exactly n finite numbers.
  Eigen::VectorXd numbers(const YAML::Node& map, const std::string& where, const char* key, int n) const;
  // A sequence (empty when the key is absent).
  YAML::Node sequence(const YAML::Node& map, const std::string& where, const char* key) const;
  // A mapping (null when the key is absent).
  YAML::Node mapping(const YAML::Node& map, const std::string& where, const char* key) const;

  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

 private:
  double finite(const YAML::Node& node, const std::string& key) const;
  std::string file_;
};

}  // namespace biped

#include "io/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace biped {
namespace {

const char* kOverrideTag = "!override";

bool is_index(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  try {
    return YAML::Load(in);
  } catch (const YAML::ParserException& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
}

std::vector<std::string> split_dotted_key(const std::string& key) {
  std::vector<std::string> parts;
  for (std::size_t start = 0; start <= key.size();) {
    const auto dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

void apply_override(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--set " + assignment + ": expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::ParserException& e) {
    throw InputError("--set " + assignment + ": the value is not valid YAML: " + e.msg);
  }
  value.SetTag(kOverrideTag);

  const std::vector<std::string> parts = split_dotted_key(key);
  // Walk down with copies of handles (YAML::Node assignment would rebind, not descend).
  std::vector<YAML::Node> path{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node here = path.back();
    const std::string& part = parts[i];
    if (part.empty()) throw InputError("--set " + assignment + ": empty key component");
    if (here.IsSequence()) {
      if (!is_index(part) || std::stoul(part) >= here.size()) {
        throw InputError("--set " + assignment + ": '" + part + "' is not an item of the list");
      }
      path.push_back(here[std::stoul(part)]);
    } else {
      if (here.IsDefined() && !here.IsNull() && !here.IsMap()) {
        throw InputError("--set " + assignment + ": '" + part + "' is inside a value that is not a mapping");
      }
      if (!here[part]) here[part] = YAML::Node(YAML::NodeType::Map);
      path.push_back(here[part]);
    }
  }
  YAML::Node parent = path.back();
  const std::string& last = parts.back();
  if (last.empty()) throw InputError("--set " + assignment + ": empty key component");
  if (parent.IsSequence()) {
    if (!is_index(last) || std::stoul(last) >= parent.size()) {
      throw InputError("--set " + assignment + ": '" + last + "' is not an item of the list");
    }
    parent[std::stoul(last)] = value;
  } else {
    if (parent.IsDefined() && !parent.IsNull() && !parent.IsMap()) {
      throw InputError("--set " + assignment + ": the parent of '" + last + "' is not a mapping");
    }
    parent[last] = value;
  }
}

void YamlReader::fail(const YAML::Node& node, const std::string& key, const std::string& problem) const {
  std::string where = file_;
  if (node.IsDefined() && node.Tag() == kOverrideTag) {
    where += " (--set)";
  } else if (node.IsDefined() && node.Mark().line >= 0) {
    where += ":" + std::to_string(node.Mark().line + 1);
  }
  throw InputError(where + ": key '" + key + "': " + problem);
}

void YamlReader::expect_keys(const YAML::Node& map, const std::string& where,
                             const std::vector<std::string>& allowed) const {
  if (!map.IsDefined() || map.IsNull()) return;
  if (!map.IsMap()) fail(map, where.empty() ? "(top level)" : where, "expected a mapping of keys to values");
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(entry.first, join(where, key), "unknown key (allowed here: " + list + ")");
    }
  }
}

double YamlReader::finite(const YAML::Node& node, const std::string& key) const {
  double v = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v)) fail(node, key, "expected a number");
  if (!std::isfinite(v)) fail(node, key, "must be a finite number (got '" + node.Scalar() + "')");
  return v;
}

double YamlReader::number(const YAML::Node& map, const std::string& where, const char* key) const {
  const YAML::Node node = map[key];
  if (!node) fail(map, join(where, key), "missing (required)");
  return finite(node, join(where, key));
}

double YamlReader::number_or(const YAML::Node& map, const std::string& where, const char* key, double fallback) const {
  const YAML::Node node = map[key];
  return node ? finite(node, join(where, key)) : fallback;
}

double YamlReader::positive_or(const YAML::Node& map, const std::string& where, const char* key,
                               double fallback) const {
  const double v = number_or(map, where, key, fallback);
  if (!(v > 0.0)) fail(map[key], join(where, key), "must be positive (got " + map[key].Scalar() + ")");
  return v;
}

double YamlReader::non_negative_or(const YAML::Node& map, const std::string& where, const char* key,
                                   double fallback) const {
  const double v = number_or(map, where, key, fallback);
  if (v < 0.0) fail(map[key], join(where, key), "must not be negative (got " + map[key].Scalar() + ")");
  return v;
}

long YamlReader::integer_or(const YAML::Node& map, const std::string& where, const char* key, long fallback) const {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  long v = 0;
  if (!node.IsScalar() || !YAML::convert<long>::decode(node, v)) fail(node, join(where, key), "expected an integer");
  return v;
}

bool YamlReader::boolean_or(const YAML::Node& map, const std::string& where, const char* key, bool fallback) const {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  bool v = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) {
    fail(node, join(where, key), "expected true or false");
  }
  return v;
}

std::string YamlReader::text(const YAML::Node& map, const std::string& where, const char* key) const {
  const YAML::Node node = map[key];
  if (!node) fail(map, join(where, key), "missing (required)");
  if (!node.IsScalar() || node.Scalar().empty()) fail(node, join(where, key), "expected a non-empty text");
  return node.Scalar();
}

std::string YamlReader::text_or(const YAML::Node& map, const std::string& where, const char* key,
                                const std::string& fallback) const {
  return map[key] ? text(map, where, key) : fallback;
}

Eigen::Vector3d YamlReader::vector3(const YAML::Node& map, const std::string& where, const char* key) const {
  const YAML::Node node = map[key];
  if (!node) fail(map, join(where, key), "missing (required)");
  if (!node.IsSequence() || node.size() != 3) fail(node, join(where, key), "expected a list of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = finite(node[i], join(where, key));
  return v;
}

Eigen::Vector3d YamlReader::vector3_or(const YAML::Node& map, const std::string& where, const char* key,
                                       const Eigen::Vector3d& fallback) const {
  return map[key] ? vector3(map, where, key) : fallback;
}

Eigen::VectorXd YamlReader::numbers(const YAML::Node& map, const std::string& where, const char* key, int n) const {
  const YAML::Node node = map[key];
  if (!node) fail(map, join(where, key), "missing (required)");
  if (!node.IsSequence() || static_cast<int>(node.size()) != n) {
    fail(node, join(where, key), "expected a list of " + std::to_string(n) + " numbers");
  }
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = finite(node[i], join(where, key));
  return v;
}

YAML::Node YamlReader::sequence(const YAML::Node& map, const std::string& where, const char* key) const {
  const YAML::Node node = map[key];
  if (!node || node.IsNull()) return YAML::Node(YAML::NodeType::Sequence);
  if (!node.IsSequence()) fail(node, join(where, key), "expected a list");
  return node;
}

YAML::Node YamlReader::mapping(const YAML::Node& map, const std::string& where, const char* key) const {
  const YAML::Node node = map[key];
  if (!node || node.IsNull()) return YAML::Node();
  if (!node.IsMap()) fail(node, join(where, key), "expected a mapping of keys to values");
  return node;
}

}  // namespace biped

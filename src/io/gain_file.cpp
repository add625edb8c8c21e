#include "io/gain_file.hpp"

#include "io/output_files.hpp"
#include "io/yaml_reader.hpp"

namespace biped {
namespace {

void flatten(const YamlReader& r, const YAML::Node& node, const std::string& key, std::vector<std::string>& out) {
  if (node.IsMap()) {
    for (const auto& entry : node) flatten(r, entry.second, key + "." + entry.first.Scalar(), out);
    return;
  }
  double number = 0.0;
  bool flag = false;
  if (!node.IsScalar() ||
      !(YAML::convert<double>::decode(node, number) || YAML::convert<bool>::decode(node, flag))) {
    r.fail(node, key, "a gain file holds numbers and booleans only");
  }
  out.push_back(key + "=" + node.Scalar());
}

}  // namespace

void write_gain_file(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::string>& assignments) {
  YAML::Node root(YAML::NodeType::Map);
  for (const std::string& assignment : assignments) {
    const std::size_t equals = assignment.find('=');
    const std::vector<std::string> parts = split_dotted_key(assignment.substr(0, equals));
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (!node[parts[i]]) node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      node.reset(node[parts[i]]);
    }
    node[parts.back()] = assignment.substr(equals + 1);
  }
  YAML::Emitter yaml;
  yaml << root;
  AtomicOutputFile file(path);
  for (const std::string& line : header) file.stream() << "# " << line << '\n';
  file.stream() << yaml.c_str() << '\n';
  file.commit();
}

std::vector<std::string> read_gain_file(const std::string& path, const RunConfig& config) {
  RunConfig check = config;
  apply_include_file(path, check);
  const YAML::Node root = load_yaml_file(path);
  const YamlReader r(path);
  for (const char* robot_only : {"simulation", "drives"}) {
    if (root[robot_only]) r.fail(root[robot_only], robot_only, "a starting gain set holds controller keys only");
  }
  std::vector<std::string> assignments;
  if (root["controller"]) flatten(r, root["controller"], "controller", assignments);
  return assignments;
}

}  // namespace biped

#include "io/parameter_table.hpp"

#include <algorithm>
#include <cstdio>

#include "io/yaml_reader.hpp"

namespace biped {
namespace {

// The messages are YamlReader's (positive_or, non_negative_or), so they read as everywhere else.
void check_bounds(const YamlReader& r, const YAML::Node& node, const std::string& key, double value,
                  const Check& check) {
  if (check.lower == Check::Lower::Positive && !(value > 0.0)) {
    r.fail(node, key, "must be positive (got " + node.Scalar() + ")");
  }
  if (check.lower == Check::Lower::NonNegative && value < 0.0) {
    r.fail(node, key, "must not be negative (got " + node.Scalar() + ")");
  }
  if (check.upper_included ? value > check.upper : value >= check.upper) {
    r.fail(node, key,
           std::string("must be ") + (check.upper_included ? "at most " : "below ") + number_text(check.upper) +
               (check.reason ? std::string(" (") + check.reason + ")" : ""));
  }
}

// Markdown cells: a '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// Characters on screen: UTF-8 continuation bytes take no column.
std::size_t columns(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

}  // namespace

std::optional<double> read_number(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                  const char* key, const Check& check) {
  const YAML::Node node = map[key];
  if (!node) return std::nullopt;
  const double value = r.number(map, where, key);
  check_bounds(r, node, YamlReader::join(where, key), value, check);
  return value;
}

std::optional<int> read_integer(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                const char* key, const Check& check) {
  const YAML::Node node = map[key];
  if (!node) return std::nullopt;
  const long value = r.integer_or(map, where, key, 0);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
    r.fail(node, YamlReader::join(where, key), "out of range (got " + node.Scalar() + ")");
  }
  check_bounds(r, node, YamlReader::join(where, key), static_cast<double>(value), check);
  return static_cast<int>(value);
}

std::optional<bool> read_boolean(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                 const char* key) {
  if (!map[key]) return std::nullopt;
  return r.boolean_or(map, where, key, false);
}

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string check_text(const Check& check, bool integer) {
  std::string text;
  if (check.lower == Check::Lower::Positive) text = "> 0";
  if (check.lower == Check::Lower::NonNegative) text = "≥ 0";
  if (std::isfinite(check.upper)) {
    text += (text.empty() ? "" : ", ") + std::string(check.upper_included ? "≤ " : "< ") + number_text(check.upper);
  }
  if (integer) return text.empty() ? "integer" : "integer " + text;
  return text.empty() ? "finite" : text;
}

void read_section(const YamlReader& r, const YAML::Node& map, const ParameterSection& section) {
  std::vector<std::string> allowed;
  for (const BoundTable& table : section.tables) allowed.insert(allowed.end(), table.keys().begin(), table.keys().end());
  allowed.insert(allowed.end(), section.other_keys.begin(), section.other_keys.end());
  r.expect_keys(map, section.where, allowed);
  if (!map.IsDefined() || map.IsNull()) return;
  for (const BoundTable& table : section.tables) table.read(r, map, section.where);
}

std::vector<ParameterDoc> document_sections(const std::vector<ParameterSection>& sections) {
  std::vector<ParameterDoc> rows;
  for (const ParameterSection& section : sections) {
    for (const BoundTable& table : section.tables) table.document(section.where, rows);
  }
  return rows;
}

std::string markdown_table(const std::vector<ParameterDoc>& rows) {
  std::string out = "| key | unit | default | check | description |\n|---|---|---|---|---|\n";
  for (const ParameterDoc& row : rows) {
    out += "| `" + row.key + "` | " + cell(row.unit) + " | " + cell(row.default_value) + " | " + cell(row.check) +
           " | " + cell(row.description) + " |\n";
  }
  return out;
}

std::string text_table(const std::vector<ParameterDoc>& rows) {
  std::size_t key_width = 0, value_width = 0, check_width = 0;
  auto value_of = [](const ParameterDoc& row) { return row.default_value + (row.unit.empty() ? "" : " " + row.unit); };
  for (const ParameterDoc& row : rows) {
    key_width = std::max(key_width, columns(row.key));
    value_width = std::max(value_width, columns(value_of(row)));
    check_width = std::max(check_width, columns(row.check));
  }
  auto padded = [](const std::string& text, std::size_t width) { return text + std::string(width - columns(text) + 2, ' '); };
  std::string out;
  for (const ParameterDoc& row : rows) {
    out += padded(row.key, key_width) + padded(value_of(row), value_width) + padded(row.check, check_width) +
           row.description + "\n";
  }
  return out;
}

}  // namespace biped

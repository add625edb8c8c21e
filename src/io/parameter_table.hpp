#pragma once
// Parameter tables: one per parameter struct, one row per YAML key (member, unit, check,
// description). From the tables follow reading a mapping into the structs with every value checked,
// the keys allowed in that mapping, and the parameter reference of the documentation. Defaults are
// the structs' own member initializers, so each is written once.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace YAML {
class Node;
}

namespace biped {

class YamlReader;

// What a number must be besides finite: a lower bound of zero (excluded or included) or none, and
// an optional upper bound with the reason for it (part of the error message).
struct Check {
  enum class Lower { None, Positive, NonNegative };
  Lower lower = Lower::None;
  double upper = std::numeric_limits<double>::infinity();
  bool upper_included = true;
  const char* reason = nullptr;
};
inline constexpr Check kFinite{};
inline constexpr Check kPositive{Check::Lower::Positive};
inline constexpr Check kNonNegative{Check::Lower::NonNegative};
constexpr Check positive_below(double upper, const char* reason = nullptr) {
  return {Check::Lower::Positive, upper, false, reason};
}
constexpr Check positive_at_most(double upper, const char* reason = nullptr) {
  return {Check::Lower::Positive, upper, true, reason};
}

inline constexpr double kRadiansPerDegree = M_PI / 180.0;

// A member in radians that the file gives in degrees.
template <class T>
struct Degrees {
  double T::*radians;
};

template <class T>
struct Parameter {
  const char* key;
  std::variant<double T::*, Degrees<T>, int T::*, bool T::*> member;
  const char* unit;  // "" for none
  Check check;       // not used for booleans
  const char* description;
};

template <class T>
using ParameterTable = std::vector<Parameter<T>>;

// The checked value of `key` in `map` (an InputError naming file, dotted key and line otherwise),
// or nothing when the key is absent.
std::optional<double> read_number(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                  const char* key, const Check& check);
std::optional<int> read_integer(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                const char* key, const Check& check);
std::optional<bool> read_boolean(const YamlReader& r, const YAML::Node& map, const std::string& where,
                                 const char* key);

// Sets the members whose keys `map` holds; the others keep their values.
template <class T>
void read_parameters(const YamlReader& r, const YAML::Node& map, const std::string& where,
                     const ParameterTable<T>& table, T& into) {
  for (const Parameter<T>& p : table) {
    if (const auto* m = std::get_if<double T::*>(&p.member)) {
      if (const auto v = read_number(r, map, where, p.key, p.check)) into.*(*m) = *v;
    } else if (const auto* d = std::get_if<Degrees<T>>(&p.member)) {
      if (const auto v = read_number(r, map, where, p.key, p.check)) into.*(d->radians) = *v * kRadiansPerDegree;
    } else if (const auto* i = std::get_if<int T::*>(&p.member)) {
      if (const auto v = read_integer(r, map, where, p.key, p.check)) into.*(*i) = *v;
    } else if (const auto v = read_boolean(r, map, where, p.key)) {
      into.*std::get<bool T::*>(p.member) = *v;
    }
  }
}

// One line of the parameter reference, as text.
struct ParameterDoc {
  std::string key;  // dotted
  std::string unit, default_value, check, description;
};

std::string number_text(double value);
std::string check_text(const Check& check, bool integer);

// The reference rows of a table, with the values of `defaults` as the defaults.
template <class T>
void document_parameters(const std::string& where, const ParameterTable<T>& table, const T& defaults,
                         std::vector<ParameterDoc>& out) {
  for (const Parameter<T>& p : table) {
    ParameterDoc doc{where.empty() ? p.key : where + "." + p.key, p.unit, "", check_text(p.check, false),
                     p.description};
    if (const auto* m = std::get_if<double T::*>(&p.member)) {
      doc.default_value = number_text(defaults.*(*m));
    } else if (const auto* d = std::get_if<Degrees<T>>(&p.member)) {
      doc.default_value = number_text(defaults.*(d->radians) / kRadiansPerDegree);
    } else if (const auto* i = std::get_if<int T::*>(&p.member)) {
      doc.default_value = std::to_string(defaults.*(*i));
      doc.check = check_text(p.check, true);
    } else {
      doc.default_value = defaults.*std::get<bool T::*>(p.member) ? "true" : "false";
      doc.check = "true or false";
    }
    out.push_back(std::move(doc));
  }
}

// A table together with the struct it reads into (and documents the values of as defaults).
class BoundTable {
 public:
  template <class T>
  BoundTable(const ParameterTable<T>& table, T& object)
      : table_(&table), object_(&object), read_(&read_erased<T>), document_(&document_erased<T>) {
    for (const Parameter<T>& p : table) keys_.push_back(p.key);
  }

  const std::vector<std::string>& keys() const { return keys_; }

  void read(const YamlReader& r, const YAML::Node& map, const std::string& where) const {
    read_(table_, object_, r, map, where);
  }
  void document(const std::string& where, std::vector<ParameterDoc>& out) const {
    document_(table_, object_, where, out);
  }

 private:
  template <class T>
  static void read_erased(const void* table, void* object, const YamlReader& r, const YAML::Node& map,
                          const std::string& where) {
    read_parameters(r, map, where, *static_cast<const ParameterTable<T>*>(table), *static_cast<T*>(object));
  }
  template <class T>
  static void document_erased(const void* table, const void* object, const std::string& where,
                              std::vector<ParameterDoc>& out) {
    document_parameters(where, *static_cast<const ParameterTable<T>*>(table), *static_cast<const T*>(object), out);
  }

  const void* table_;
  void* object_;
  std::vector<std::string> keys_;
  void (*read_)(const void*, void*, const YamlReader&, const YAML::Node&, const std::string&);
  void (*document_)(const void*, const void*, const std::string&, std::vector<ParameterDoc>&);
};

// One YAML mapping (dotted path `where`, "" for the top level): the tables read from it and the
// keys read by hand (texts, sub-mappings).
struct ParameterSection {
  std::string where;
  std::vector<BoundTable> tables;
  std::vector<std::string> other_keys;
};

// Fails on a key that is neither a table's nor one of the other keys, then reads the tables.
void read_section(const YamlReader& r, const YAML::Node& map, const ParameterSection& section);

// The reference rows of the sections' tables (the other keys are documented by hand).
std::vector<ParameterDoc> document_sections(const std::vector<ParameterSection>& sections);

std::string markdown_table(const std::vector<ParameterDoc>& rows);
// Aligned plain text, one parameter a line.
std::string text_table(const std::vector<ParameterDoc>& rows);

}  // namespace biped

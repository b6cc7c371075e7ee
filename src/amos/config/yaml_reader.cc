#include "amos/config/yaml_reader.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "amos/core/error.h"
#include "amos/core/whole_file.h"

namespace amos::config {

namespace {
// OpenCV writes `%YAML:1.0`, which is not a valid YAML directive; blank it (keeping line numbers intact).
std::string withoutOpenCvHeader(std::string text) {
  if (text.rfind("%YAML:", 0) == 0) {
    const auto eol = text.find('\n');
    text.replace(0, eol == std::string::npos ? text.size() : eol, "");
  }
  return text;
}
}  // namespace

YamlReader YamlReader::fromFile(const std::string& path) {
  return fromText(core::readWholeFileOrThrow(path, fmt::format("cannot open settings file '{}'", path)), path);
}

YamlReader YamlReader::fromText(const std::string& text, const std::string& virtual_path) {
  YAML::Node root;
  try {
    root = YAML::Load(withoutOpenCvHeader(text));
  } catch (const YAML::Exception& e) {
    throw core::Error(fmt::format("{}:{}: malformed YAML: {}", virtual_path, e.mark.line + 1, e.msg));
  }
  if (!root.IsMap()) {
    throw core::Error(fmt::format("{}: settings must be a map of `Key: value` lines", virtual_path));
  }
  return YamlReader(root, virtual_path);
}

YamlReader::YamlReader(YAML::Node root, std::string path) : root_(std::move(root)), path_(std::move(path)) {
  // yaml-cpp keeps every pair of a map, duplicates included, in file order: a key set twice would silently take
  // one of its values.
  std::map<std::string, int> first_line;
  for (const auto& kv : root_) {
    const int line = kv.first.Mark().line + 1;
    if (!kv.first.IsScalar()) throw core::Error(fmt::format("{}:{}: a key must be a plain name", path_, line));
    const std::string key = kv.first.Scalar();
    const auto [first, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      throw core::Error(fmt::format("{}:{}: key '{}' is set again (first on line {}); keep one of the two lines", path_,
                                    line, key, first->second));
    }
    entries_[key] = kv.second;
  }
}

bool YamlReader::has(const std::string& key) const { return entries_.count(key) > 0; }

std::string YamlReader::where(const std::string& key) const {
  auto it = entries_.find(key);
  if (it == entries_.end()) return path_;
  return fmt::format("{}:{}", path_, it->second.Mark().line + 1);
}

const YAML::Node& YamlReader::node(const std::string& key) {
  read_.insert(key);
  return entries_.at(key);
}

template <typename T>
void YamlReader::readScalar(const std::string& key, T& value, const char* type_name) {
  if (!has(key)) return;
  const YAML::Node& n = node(key);
  const std::string text = n.IsScalar() ? n.Scalar() : std::string("<not a scalar>");
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "not a scalar");
    value = n.as<T>();
  } catch (const YAML::Exception&) {
    throw core::Error(fmt::format("{}: key '{}' must be {}, got '{}'", where(key), key, type_name, text));
  }
}

void YamlReader::read(const std::string& key, double& value) {
  readScalar(key, value, "a number");
  if (has(key) && !std::isfinite(value)) throw core::Error(fmt::format("{}: key '{}' must be finite", where(key), key));
}
void YamlReader::read(const std::string& key, float& value) {
  double v = value;
  read(key, v);
  value = static_cast<float>(v);
}
void YamlReader::read(const std::string& key, int& value) { readScalar(key, value, "a whole number"); }
void YamlReader::read(const std::string& key, unsigned& value) {
  long long v = value;
  readScalar(key, v, "a whole number >= 0");
  if (v < 0 || v > static_cast<long long>(std::numeric_limits<unsigned>::max())) {
    throw core::Error(fmt::format("{}: key '{}' must be a whole number >= 0, got {}", where(key), key, v));
  }
  value = static_cast<unsigned>(v);
}
void YamlReader::read(const std::string& key, bool& value) {
  if (!has(key)) return;
  // ORB-SLAM2 files write flags as 0/1; accept those as well as true/false.
  const YAML::Node& n = node(key);
  const std::string text = n.IsScalar() ? n.Scalar() : "";
  if (text == "1") value = true;
  else if (text == "0") value = false;
  else readScalar(key, value, "true/false (or 1/0)");
}
void YamlReader::read(const std::string& key, std::string& value) { readScalar(key, value, "a string"); }
void YamlReader::read(const std::string& key, std::vector<std::string>& value) {
  if (!has(key)) return;
  const YAML::Node& n = node(key);
  if (n.IsScalar()) {
    value = {n.Scalar()};
    return;
  }
  if (!n.IsSequence()) throw core::Error(fmt::format("{}: key '{}' must be a list of names", where(key), key));
  value.clear();
  for (const auto& item : n) {
    if (!item.IsScalar()) throw core::Error(fmt::format("{}: key '{}' must be a list of names", where(key), key));
    value.push_back(item.Scalar());
  }
}

std::vector<std::string> YamlReader::unreadKeys() const {
  std::vector<std::string> out;
  for (const auto& [key, n] : entries_) {
    if (!read_.count(key)) out.push_back(key);
  }
  return out;
}

std::vector<std::string> YamlReader::keys() const {
  std::vector<std::string> out;
  for (const auto& kv : entries_) out.push_back(kv.first);
  return out;
}

}  // namespace amos::config

#pragma once
// Reads one flat YAML settings file (ORB-SLAM2 style: top-level keys such as `Camera.fx`), remembering the line
// of every key so that every error can name file and line. Also accepts OpenCV's `%YAML:1.0` header. A key set twice
// is an error naming both lines.
#include <yaml-cpp/yaml.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace amos::config {

class YamlReader {
 public:
  // Throws core::Error naming the file (and line, for syntax errors).
  static YamlReader fromFile(const std::string& path);
  // For tests: parse text as if it came from `virtual_path`.
  static YamlReader fromText(const std::string& text, const std::string& virtual_path);

  bool has(const std::string& key) const;
  // Reads `key` into `value` when present (value keeps its default otherwise). A value of the wrong type throws
  // core::Error "file:line: key 'K' must be <type>, got 'V'".
  void read(const std::string& key, double& value);
  void read(const std::string& key, float& value);
  void read(const std::string& key, int& value);
  void read(const std::string& key, unsigned& value);
  void read(const std::string& key, bool& value);
  void read(const std::string& key, std::string& value);
  void read(const std::string& key, std::vector<std::string>& value);

  // "file:line" of a key, or just the file when the key is absent.
  std::string where(const std::string& key) const;
  const std::string& path() const { return path_; }
  // Keys present in the file that nothing read.
  std::vector<std::string> unreadKeys() const;
  std::vector<std::string> keys() const;

 private:
  YamlReader(YAML::Node root, std::string path);
  const YAML::Node& node(const std::string& key);
  template <typename T>
  void readScalar(const std::string& key, T& value, const char* type_name);

  YAML::Node root_;
  std::string path_;
  std::map<std::string, YAML::Node> entries_;
  std::set<std::string> read_;
};

}  // namespace amos::config

#pragma once
// Reading YAML configuration with messages that name the file, line and key.
//
//   auto root = ConfigNode::load_file("motion.yaml");
//   root.read("max_features", options.max_features, 10, 100000);
//   root.expect_only({"max_features", ...});   // a typo is an error, not a silent default

#include <initializer_list>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "uavmot/core/error.hpp"

namespace uavmot {

class ConfigNode {
 public:
  ConfigNode(YAML::Node node, std::string file, std::string path);

  // Throws InputError for a missing, unreadable or malformed file (with the line of the syntax error).
  static ConfigNode load_file(const std::string& file);
  static ConfigNode load_string(const std::string& text, const std::string& name = "<string>");

  bool has(const std::string& key) const;
  ConfigNode child(const std::string& key) const;  // throws if absent or not a map
  std::vector<ConfigNode> children(const std::string& key) const;  // a sequence of maps
  std::vector<std::string> keys() const;

  // Keeps `value` (the default) when the key is absent; throws InputError on a wrong type or range.
  void read(const std::string& key, bool& value) const;
  void read(const std::string& key, std::string& value) const;
  void read(const std::string& key, std::vector<std::string>& value) const;
  void read(const std::string& key, int& value, int min, int max) const;
  void read(const std::string& key, double& value, double min, double max) const;
  // Accepts only one of `choices`.
  void read_choice(const std::string& key, std::string& value, const std::vector<std::string>& choices) const;

  // Rejects keys not listed, suggesting the closest known key.
  void expect_only(std::initializer_list<const char*> known) const;
  void expect_only(const std::vector<std::string>& known) const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  std::string location(const std::string& key = "") const;  // "file:line: path.key"
  const YAML::Node& yaml() const { return node_; }

 private:
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace uavmot

#include "uavmot/core/yaml_config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace uavmot {
namespace {
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string join_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
}  // namespace

ConfigNode::ConfigNode(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

ConfigNode ConfigNode::load_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot open configuration file '" + file + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return load_string(buffer.str(), file);
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& name) {
  YAML::Node node;
  try {
    node = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  if (node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
  if (!node.IsMap()) throw InputError(name + ": expected a mapping of keys to values at the top level");
  return ConfigNode(node, name, "");
}

std::string ConfigNode::location(const std::string& key) const {
  const YAML::Node target = (!key.empty() && node_.IsMap() && node_[key]) ? node_[key] : node_;
  std::string where = file_;
  if (target.Mark().line >= 0) where += ":" + std::to_string(target.Mark().line + 1);
  const std::string path = key.empty() ? path_ : join_path(path_, key);
  return path.empty() ? where : where + ": " + path;
}

void ConfigNode::fail(const std::string& key, const std::string& message) const {
  throw InputError(location(key) + ": " + message);
}

bool ConfigNode::has(const std::string& key) const { return node_.IsMap() && node_[key] && !node_[key].IsNull(); }

ConfigNode ConfigNode::child(const std::string& key) const {
  if (!has(key)) fail(key, "missing section");
  if (!node_[key].IsMap()) fail(key, "expected a mapping");
  return ConfigNode(node_[key], file_, join_path(path_, key));
}

std::vector<ConfigNode> ConfigNode::children(const std::string& key) const {
  std::vector<ConfigNode> out;
  if (!has(key)) return out;
  const YAML::Node seq = node_[key];
  if (!seq.IsSequence()) fail(key, "expected a list");
  for (size_t i = 0; i < seq.size(); ++i) {
    const std::string path = join_path(path_, key) + "[" + std::to_string(i) + "]";
    if (!seq[i].IsMap()) throw InputError(file_ + ":" + std::to_string(seq[i].Mark().line + 1) + ": " + path + ": expected a mapping");
    out.emplace_back(seq[i], file_, path);
  }
  return out;
}

std::vector<std::string> ConfigNode::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) {
    // A complex key ("? [a, b]" or "? {a: 1}") has no name: a conversion to string would throw YAML's own exception.
    if (!kv.first.IsScalar()) {
      const std::string where = path_.empty() ? "" : ": " + path_;
      throw InputError(file_ + ":" + std::to_string(kv.first.Mark().line + 1) + where + ": keys must be plain names");
    }
    out.push_back(kv.first.Scalar());
  }
  return out;
}

void ConfigNode::read(const std::string& key, bool& value) const {
  if (!has(key)) return;
  try {
    value = node_[key].as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got '" + node_[key].as<std::string>("?") + "'");
  }
}

void ConfigNode::read(const std::string& key, std::string& value) const {
  if (!has(key)) return;
  if (!node_[key].IsScalar()) fail(key, "expected a string");
  value = node_[key].as<std::string>();
}

void ConfigNode::read(const std::string& key, std::vector<std::string>& value) const {
  if (!has(key)) return;
  const YAML::Node seq = node_[key];
  if (!seq.IsSequence()) fail(key, "expected a list of strings");
  value.clear();
  for (const auto& item : seq) {
    if (!item.IsScalar()) fail(key, "expected a list of strings");
    value.push_back(item.as<std::string>());
  }
}

void ConfigNode::read(const std::string& key, int& value, int min, int max) const {
  if (!has(key)) return;
  long long parsed = 0;
  try {
    parsed = node_[key].as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer, got '" + node_[key].as<std::string>("?") + "'");
  }
  if (parsed < min || parsed > max) {
    fail(key, "value " + std::to_string(parsed) + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  value = static_cast<int>(parsed);
}

void ConfigNode::read(const std::string& key, double& value, double min, double max) const {
  if (!has(key)) return;
  double parsed = 0.0;
  try {
    parsed = node_[key].as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number, got '" + node_[key].as<std::string>("?") + "'");
  }
  if (!std::isfinite(parsed)) fail(key, "expected a finite number");
  if (parsed < min || parsed > max) {
    std::ostringstream msg;
    msg << "value " << parsed << " is outside [" << min << ", " << max << "]";
    fail(key, msg.str());
  }
  value = parsed;
}

void ConfigNode::read_choice(const std::string& key, std::string& value, const std::vector<std::string>& choices) const {
  if (!has(key)) return;
  std::string parsed;
  read(key, parsed);
  if (std::find(choices.begin(), choices.end(), parsed) == choices.end()) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail(key, "'" + parsed + "' is not one of: " + list);
  }
  value = parsed;
}

void ConfigNode::expect_only(std::initializer_list<const char*> known) const {
  expect_only(std::vector<std::string>(known.begin(), known.end()));
}

void ConfigNode::expect_only(const std::vector<std::string>& known) const {
  for (const auto& key : keys()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string best;
    size_t best_distance = 4;  // suggest only close matches
    for (const auto& candidate : known) {
      const size_t d = edit_distance(key, candidate);
      if (d < best_distance) {
        best_distance = d;
        best = candidate;
      }
    }
    fail(key, "unknown key '" + key + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)"));
  }
}

}  // namespace uavmot

#include "uavmot/launch/profile.hpp"

#include "uavmot/core/error.hpp"
#include "uavmot/core/yaml_config.hpp"

namespace uavmot::launch {
namespace {

std::string substitute(const std::string& text, const std::map<std::string, std::string>& variables,
                       const std::string& where) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t start = text.find("${", pos);
    if (start == std::string::npos) {
      out += text.substr(pos);
      return out;
    }
    const size_t end = text.find('}', start);
    if (end == std::string::npos) throw InputError(where + ": unterminated '${' in '" + text + "'");
    const std::string name = text.substr(start + 2, end - start - 2);
    const auto it = variables.find(name);
    if (it == variables.end() && name.rfind("readers:", 0) == 0) {
      throw InputError(where + ": '${" + name + "}': no process of the profile reads '" + name.substr(8) +
                       "' (list it under that process's reads)");
    }
    if (it == variables.end()) {
      throw InputError(where + ": variable '${" + name + "}' is not defined (set it with --set " + name + "=VALUE)");
    }
    out += text.substr(pos, start - pos) + it->second;
    pos = end + 1;
  }
}

bool parse_enabled(const std::string& value, const std::string& where) {
  if (value == "true" || value == "yes" || value == "on" || value == "1") return true;
  if (value == "false" || value == "no" || value == "off" || value == "0" || value.empty()) return false;
  throw InputError(where + ": enabled is '" + value + "' (expected true or false)");
}

double parse_seconds(const std::string& value, const std::string& where) {
  size_t used = 0;
  double seconds = -1.0;
  try {
    seconds = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (value.empty() || used != value.size() || !(seconds >= 0.0 && seconds <= 3600.0)) {
    throw InputError(where + " is '" + value + "' (expected seconds, 0 to 3600)");
  }
  return seconds;
}

}  // namespace

Profile load_profile(const std::string& file) {
  const ConfigNode root = ConfigNode::load_file(file);
  root.expect_only({"description", "variables", "common_args", "processes"});
  Profile profile;
  profile.file = file;
  root.read("description", profile.description);
  root.read("common_args", profile.common_args);
  if (root.has("variables")) {
    const ConfigNode vars = root.child("variables");
    for (const auto& key : vars.keys()) {
      std::string value;
      vars.read(key, value);
      profile.variables[key] = value;
    }
  }
  const auto processes = root.children("processes");
  if (processes.empty()) root.fail("processes", "a profile needs a list of processes");
  for (const auto& node : processes) {
    node.expect_only({"name", "command", "args", "env", "common_args", "required", "stop_on_failure", "respawn", "respawn_delay",
                      "max_respawns", "start_delay", "enabled", "reads", "hang_timeout", "respawn_args"});
    ProcessSpec spec;
    node.read("name", spec.name);
    node.read("command", spec.command);
    if (spec.name.empty()) node.fail("name", "every process needs a name");
    if (spec.command.empty()) node.fail("command", "every process needs a command");
    for (const auto& other : profile.processes) {
      if (other.name == spec.name) node.fail("name", "duplicate process name '" + spec.name + "'");
    }
    node.read("args", spec.args);
    node.read("enabled", spec.enabled);
    node.read("reads", spec.reads);
    node.read("common_args", spec.common_args);
    node.read("required", spec.required);
    node.read("stop_on_failure", spec.stop_on_failure);
    node.read("respawn", spec.respawn);
    node.read("respawn_delay", spec.respawn_delay);
    node.read("max_respawns", spec.max_respawns, 0, 1000000);
    node.read("start_delay", spec.start_delay_s, 0.0, 3600.0);
    node.read("hang_timeout", spec.hang_timeout);
    node.read("respawn_args", spec.respawn_args);
    if (node.has("env")) {
      const ConfigNode env = node.child("env");
      for (const auto& key : env.keys()) env.read(key, spec.env[key]);
    }
    profile.processes.push_back(std::move(spec));
  }
  return profile;
}

Profile resolve(const Profile& profile, const std::map<std::string, std::string>& variables) {
  std::map<std::string, std::string> all = profile.variables;
  for (const auto& [k, v] : variables) all[k] = v;
  // A profile's default may name other variables (e.g. "${profile_dir}/qos"): one level deep.
  const auto given = all;
  for (auto& [k, v] : all) {
    if (profile.variables.count(k) && !variables.count(k)) v = substitute(v, given, profile.file + ": variable '" + k + "'");
  }
  Profile out = profile;
  out.processes.clear();
  for (const auto& p : profile.processes) {
    const std::string where = profile.file + ": process '" + p.name + "'";
    if (parse_enabled(substitute(p.enabled, all, where), where)) out.processes.push_back(p);
  }
  // Readers per topic among the processes that run; every topic some process names has a count.
  std::map<std::string, int> readers;
  for (const auto& p : profile.processes) {
    for (const auto& topic : p.reads) readers[substitute(topic, all, profile.file + ": process '" + p.name + "'")] += 0;
  }
  for (auto& p : out.processes) {
    for (auto& topic : p.reads) {
      topic = substitute(topic, all, profile.file + ": process '" + p.name + "'");
      ++readers[topic];
    }
  }
  for (const auto& [topic, count] : readers) all["readers:" + topic] = std::to_string(count);
  for (auto& arg : out.common_args) arg = substitute(arg, all, profile.file + ": common_args");
  for (auto& p : out.processes) {
    const std::string where = profile.file + ": process '" + p.name + "'";
    p.command = substitute(p.command, all, where);
    for (auto& arg : p.args) arg = substitute(arg, all, where);
    for (auto& arg : p.respawn_args) arg = substitute(arg, all, where);
    for (auto& [k, v] : p.env) v = substitute(v, all, where);
    p.enabled = "true";
    p.hang_timeout = substitute(p.hang_timeout, all, where);
    p.hang_timeout_s = parse_seconds(p.hang_timeout, where + ": hang_timeout");
    p.respawn_delay = substitute(p.respawn_delay, all, where);
    p.respawn_delay_s = parse_seconds(p.respawn_delay, where + ": respawn_delay");
  }
  out.variables = all;
  return out;
}

}  // namespace uavmot::launch

#pragma once
// One list of every scenario field with its YAML key and valid range, walked by the YAML
// reader, the YAML writer and the JSON metadata writer, so the three never disagree.

#include <string>

#include "uavmot/sim/scenario.hpp"

namespace uavmot::sim::detail {

class FieldVisitor {
 public:
  virtual ~FieldVisitor() = default;
  virtual void begin_section(const char* name) = 0;
  virtual void end_section() = 0;
  virtual void field(const char* key, int& value, int min, int max) = 0;
  virtual void field(const char* key, double& value, double min, double max) = 0;
  virtual void field(const char* key, bool& value) = 0;
  virtual void field(const char* key, std::string& value) = 0;
};

void visit_scenario(Scenario& scenario, FieldVisitor& visitor);

}  // namespace uavmot::sim::detail

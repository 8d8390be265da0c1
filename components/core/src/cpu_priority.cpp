#include "uavmot/core/cpu_priority.hpp"

#include <sched.h>

#include <cerrno>
#include <cstring>

#include "uavmot/core/error.hpp"

namespace uavmot {

CpuPriority parse_cpu_priority(const std::string& name) {
  if (name == "normal") return CpuPriority::Normal;
  if (name == "idle") return CpuPriority::Idle;
  throw InvalidArgument("CPU priority '" + name + "' is not normal or idle");
}

const char* to_string(CpuPriority priority) { return priority == CpuPriority::Idle ? "idle" : "normal"; }

void set_cpu_priority(CpuPriority priority) {
  // pid 0: the calling thread (Linux schedules threads, not processes).
  const sched_param param{0};
  if (sched_setscheduler(0, priority == CpuPriority::Idle ? SCHED_IDLE : SCHED_OTHER, &param) != 0) {
    throw InputError(std::string("cannot set CPU priority ") + to_string(priority) + ": " + std::strerror(errno));
  }
}

CpuPriority current_cpu_priority() { return sched_getscheduler(0) == SCHED_IDLE ? CpuPriority::Idle : CpuPriority::Normal; }

}  // namespace uavmot

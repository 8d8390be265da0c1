#pragma once
// How a process competes for the CPU with the chain beside it.

#include <string>

namespace uavmot {

enum class CpuPriority {
  Normal,  // the scheduler's default: shares the cores evenly with the chain
  Idle,    // SCHED_IDLE: runs only on CPU time no normal-priority thread wants
};

// "normal" or "idle"; anything else: InvalidArgument naming the choices.
CpuPriority parse_cpu_priority(const std::string& name);
const char* to_string(CpuPriority priority);

// Applies `priority` to the calling thread; threads it creates afterwards inherit it, so call it
// before any library starts its own threads (DDS participants, servers). Throws InputError with the
// kernel's reason if the policy cannot be set.
void set_cpu_priority(CpuPriority priority);

// The calling thread's priority as the kernel reports it.
CpuPriority current_cpu_priority();

}  // namespace uavmot

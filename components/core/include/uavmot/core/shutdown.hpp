#pragma once
// SIGINT/SIGTERM set a flag that every process loop polls, so components finish the
// frame in hand, flush what they accepted and exit cleanly.

namespace uavmot {

void install_shutdown_handler();
bool shutdown_requested();
void request_shutdown();  // for tests and for components that decide to stop

}  // namespace uavmot

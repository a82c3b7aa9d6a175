// `goris devices`: which compute backends this build has and which one --device auto would pick.
#include <cstdio>

#include "app/cli_common/command.h"
#include "core/compute/device.h"

namespace {
void setup_devices(CLI::App& root) {
  auto* c = root.add_subcommand("devices", "List the compute backends and the device --device auto picks");
  c->callback([] {
    std::printf("cpu : oneTBB, always available\n");
    std::printf("cuda: %s\n", goris::cuda_compiled() ? goris::cuda_device_description().c_str()
                                                     : "not compiled into this build (no nvcc at configure time)");
    std::printf("--device auto -> %s\n", goris::device_name(goris::resolve_device("auto")));
  });
}
}  // namespace
GORIS_COMMAND(90, setup_devices);

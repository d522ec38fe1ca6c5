// lccp devices: every OpenNI2 device with its URI, vendor, name and depth modes.
#include <cstdio>

#include "commands.hpp"
#include "lccp/capture/openni_sources.hpp"

namespace lccp::app {
namespace {

std::string modes_text(const std::vector<DepthMode>& modes) {
  if (modes.empty()) return "no millimetre depth mode (or the device is busy)";
  std::string text;
  for (const DepthMode& m : modes) {
    text += (text.empty() ? "" : ", ") + std::to_string(m.width) + "x" + std::to_string(m.height) + " @ " +
            std::to_string(m.fps) + " Hz";
  }
  return text;
}

int run_devices() {
  const std::vector<DeviceDescription> devices = list_devices();
  if (devices.empty()) std::printf("no OpenNI2 device found\n");
  for (const DeviceDescription& d : devices) {
    std::printf("%s\n  %s, %s\n  depth: %s\n", d.uri.c_str(), d.vendor.c_str(), d.name.c_str(),
                modes_text(d.depth_modes).c_str());
  }
  return kExitDone;
}

}  // namespace

Subcommand add_devices_command(CLI::App& cli) {
  CLI::App* command = cli.add_subcommand("devices", "list the OpenNI2 devices: URI, vendor and name, depth modes");
  return {command, [](std::stop_token) { return run_devices(); }};
}

}  // namespace lccp::app

// `shellmarch devices`: every Vulkan device, the tracers it offers (ray queries, a ray tracing
// pipeline) and what it lacks for the renderer, so that a user sees before rendering which device
// and tracer `render` would take.
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "vk/context.h"

namespace sm::app {
namespace {

struct DevicesOptions {
  bool json = false;
};

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

void runDevices(const DevicesOptions& o) {
  const auto devices = vk::Context::listDevices(vk::ContextOptions{});
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const vk::DeviceReport& d : devices)
      j.push_back({{"index", d.index},
                   {"name", d.name},
                   {"usable", d.missing.empty()},
                   {"tracers", d.tracers},
                   {"default_tracer", d.tracers.empty() ? "" : d.tracers.front()},
                   {"lacks", d.missing}});
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  if (devices.empty()) std::printf("no Vulkan device found\n");
  for (const vk::DeviceReport& d : devices) {
    std::printf("[%u] %s: tracers %s", d.index, d.name.c_str(),
                d.tracers.empty() ? "none" : joined(d.tracers, ", ").c_str());
    if (!d.tracers.empty()) std::printf(" (auto takes %s)", d.tracers.front().c_str());
    if (!d.missing.empty()) std::printf("; lacks %s", joined(d.missing, "; ").c_str());
    std::printf("\n");
  }
}

}  // namespace

void registerDevices(CLI::App& app) {
  auto o = std::make_shared<DevicesOptions>();
  CLI::App* sub = app.add_subcommand(
      "devices", "List the Vulkan devices, the tracers each offers and what each lacks");
  sub->add_flag("--json", o->json, "Print one JSON array instead of text");
  sub->callback([o] { runDevices(*o); });
}

}  // namespace sm::app

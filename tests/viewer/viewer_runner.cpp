#include "viewer_runner.h"

#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <span>
#include <sstream>

#include <glm/common.hpp>

#include "common/error.h"
#include "common/file_util.h"

namespace sm::test {
namespace {

uint32_t bigEndian(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t(b[at]) << 24 | uint32_t(b[at + 1]) << 16 | uint32_t(b[at + 2]) << 8 | b[at + 3];
}

int shiftOf(uint32_t mask) {
  int s = 0;
  while (mask && !(mask & 1)) {
    mask >>= 1;
    ++s;
  }
  return s;
}

}  // namespace

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = joinPath(dir, name);
  writeBytesAtomically(path, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  return path;
}

std::string quote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) {
    if (c == '\'')
      q.append("'\\''");
    else
      q.push_back(c);
  }
  q.push_back('\'');
  return q;
}

CommandResult runCommand(const std::string& command, const std::string& dir,
                         const std::string& tag) {
  const std::string out = joinPath(dir, tag + ".out"), err = joinPath(dir, tag + ".err");
  const int raw = std::system((command + " > " + quote(out) + " 2> " + quote(err)).c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = fileExists(out) ? readTextFile(out) : "";
  r.err = fileExists(err) ? readTextFile(err) : "";
  return r;
}

std::string shellmarch() {
  return quote(SHELLMARCH_EXE);
}
std::string xvfbRun(const std::string& serverArgs) {
  return quote(SHELLMARCH_XVFB_RUN) + " -a -s " + quote(serverArgs);
}
std::string mpiexec() {
  return quote(SHELLMARCH_MPIEXEC);
}

std::string generateTestMesh(const std::string& dir) {
  const std::string mesh = joinPath(dir, "cube.pvtu");
  CommandResult r = runCommand(shellmarch() +
                                   " generate --analytic cube-tets5 --cube-n 10 --clusters 4 "
                                   "--steps 3 --out " +
                                   quote(mesh),
                               dir, "generate");
  if (r.status != 0) throw Error("generate failed: ", r.err);
  return mesh;
}

nlohmann::json lastJson(const std::string& out) {
  std::istringstream in(out);
  nlohmann::json found;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] != '{') continue;
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.is_object()) found = j;
  }
  if (found.is_null()) throw Error("no JSON line in the output:\n", out);
  return found;
}

std::string renderArgs(const nlohmann::json& j) {
  std::string args;
  for (const auto& a : j.at("render_args")) {
    args.push_back(' ');
    args += quote(a.get<std::string>());
  }
  return args;
}

scene::Image readXwd(const std::string& path) {
  const std::vector<uint8_t> b = readFile(path);
  if (b.size() < 100) throw Error(path, ": too short for an XWD header");
  auto field = [&](int i) { return bigEndian(b, size_t(i) * 4); };
  const uint32_t headerSize = field(0), width = field(4), height = field(5), byteOrder = field(7);
  const uint32_t bitsPerPixel = field(11), bytesPerLine = field(12);
  const uint32_t red = field(14), green = field(15), blue = field(16), colors = field(19);
  if (bitsPerPixel != 32) throw Error(path, ": ", bitsPerPixel, " bits per pixel (expected 32)");
  const size_t pixels = size_t(headerSize) + size_t(colors) * 12;
  if (b.size() < pixels + size_t(bytesPerLine) * height) throw Error(path, ": truncated");
  scene::Image img(static_cast<int>(width), static_cast<int>(height));
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const uint8_t* p = &b[pixels + size_t(y) * bytesPerLine + size_t(x) * 4];
      const uint32_t v = byteOrder == 0 ? uint32_t(p[0]) | uint32_t(p[1]) << 8 |
                                              uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24
                                        : bigEndian(b, size_t(p - b.data()));
      img.at(int(x), int(y)) =
          glm::vec4(float((v & red) >> shiftOf(red)), float((v & green) >> shiftOf(green)),
                    float((v & blue) >> shiftOf(blue)), 255.0f) /
          255.0f;
    }
  return img;
}

size_t pixelsUnlike(const scene::Image& img, const glm::vec3& background) {
  size_t n = 0;
  for (const glm::vec4& p : img.pixels) {
    const glm::vec3 d = glm::abs(glm::vec3(p) - background);
    n += std::max(d.r, std::max(d.g, d.b)) > 2.0f / 255.0f;
  }
  return n;
}

}  // namespace sm::test

// spv_embed IN.spv OUT.cpp NAME NAMESPACE: writes a C++ source defining
//   std::span<const uint32_t> NAMESPACE::NAME()
// over a static array holding the SPIR-V words of IN.spv, for cmake/EmbedShaders.cmake. A
// build-time host tool, never installed. The words are read little-endian, the byte order
// glslangValidator writes; IN.spv must be a whole number of words and start with the SPIR-V magic
// number. OUT.cpp is written to OUT.cpp.tmp and renamed, so that a failed run leaves no
// half-written source behind.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

namespace {

constexpr uint32_t kSpirvMagic = 0x07230203u;
constexpr size_t kWordsPerLine = 16;

int fail(const std::string& message) {
  std::fprintf(stderr, "spv_embed: %s\n", message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    return fail("usage: spv_embed IN.spv OUT.cpp NAME NAMESPACE");
  }
  const std::string in = argv[1];
  const std::filesystem::path out = argv[2];
  const std::string name = argv[3];
  const std::string ns = argv[4];

  std::ifstream file(in, std::ios::binary);
  if (!file) {
    return fail(in + ": cannot be read");
  }
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(file),
                                         std::istreambuf_iterator<char>()};
  if (file.bad()) {
    return fail(in + ": read error");
  }
  if (bytes.size() % 4 != 0) {
    return fail(in + ": " + std::to_string(bytes.size()) +
                " bytes, not a whole number of 32-bit words");
  }
  const size_t words = bytes.size() / 4;
  auto word = [&](size_t i) {
    return uint32_t(bytes[4 * i]) | uint32_t(bytes[4 * i + 1]) << 8 |
           uint32_t(bytes[4 * i + 2]) << 16 | uint32_t(bytes[4 * i + 3]) << 24;
  };
  if (words == 0 || word(0) != kSpirvMagic) {
    return fail(in + ": not SPIR-V (no magic number 0x07230203 in its first word)");
  }

  std::string text;
  text.reserve(words * 12 + 512);
  text += "#include <cstdint>\n#include <span>\nnamespace " + ns + " {\n";
  text += "static const uint32_t k_" + name + "[" + std::to_string(words) + "] = {\n";
  static const char kHex[] = "0123456789abcdef";
  for (size_t i = 0; i < words; ++i) {
    const uint32_t w = word(i);
    char literal[12] = {'0', 'x'};
    for (int d = 0; d < 8; ++d) {
      literal[2 + d] = kHex[(w >> (28 - 4 * d)) & 0xfu];
    }
    literal[10] = 'u';
    literal[11] = ',';
    text.append(literal, sizeof literal);
    if ((i + 1) % kWordsPerLine == 0 || i + 1 == words) {
      text += '\n';
    }
  }
  text += "};\nstd::span<const uint32_t> " + name + "() { return {k_" + name + ", " +
          std::to_string(words) + "}; }\n}\n";

  std::filesystem::path tmp = out;
  tmp += ".tmp";
  {
    std::ofstream dst(tmp, std::ios::binary | std::ios::trunc);
    dst.write(text.data(), std::streamsize(text.size()));
    dst.close();
    if (!dst) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      return fail(tmp.string() + ": cannot be written");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, out, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return fail(out.string() + ": cannot be replaced (" + ec.message() + ")");
  }
  return 0;
}

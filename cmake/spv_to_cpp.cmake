# Converts a SPIR-V binary (IN) to a C++ source defining NS::NAME() (OUT).
file(READ "${IN}" hex HEX)
string(LENGTH "${hex}" len)
math(EXPR words "${len} / 8")
set(body "")
set(i 0)
while(i LESS len)
  # SPIR-V words are little-endian on disk: reverse the byte order of each word.
  string(SUBSTRING "${hex}" ${i} 8 w)
  string(SUBSTRING "${w}" 6 2 b3)
  string(SUBSTRING "${w}" 4 2 b2)
  string(SUBSTRING "${w}" 2 2 b1)
  string(SUBSTRING "${w}" 0 2 b0)
  string(APPEND body "0x${b3}${b2}${b1}${b0}u,")
  math(EXPR i "${i} + 8")
  math(EXPR col "(${i} / 8) % 8")
  if(col EQUAL 0)
    string(APPEND body "\n")
  endif()
endwhile()
file(WRITE "${OUT}"
  "#include <cstdint>\n#include <span>\nnamespace ${NS} {\n"
  "static const uint32_t k_${NAME}[${words}] = {\n${body}};\n"
  "std::span<const uint32_t> ${NAME}() { return {k_${NAME}, ${words}}; }\n}\n")

# Writes a SPIR-V binary (SPV) as a C++ header (OUT) holding `inline constexpr uint32_t NAME[]`:
# kernels travel inside the binary, so nothing is looked up at run time.
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR rem "${n} % 8")
if(NOT rem EQUAL 0)
  message(FATAL_ERROR "${SPV}: not a whole number of 32-bit words")
endif()
# Little-endian words: bytes aa bb cc dd -> 0xddccbbaa.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "(([^,]*,){8})" "\\1\n    " words "${words}")
file(WRITE ${OUT}.tmp "// Generated from ${SRC} by cmake/embed_spirv.cmake: do not edit.\n#pragma once\n#include <cstdint>\ninline constexpr uint32_t ${NAME}[] = {\n    ${words}};\n")
file(RENAME ${OUT}.tmp ${OUT})

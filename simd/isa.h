// Instruction-set paths: which kernels exist, what this CPU runs, and the one
// rule for choosing: min(requested, detected), never more than the CPU has.
#pragma once

#include <optional>
#include <string>

namespace quadra {

// Ordered: a later path needs every feature of the earlier ones.
enum class Isa { Scalar = 0, Sse2 = 1, Avx2 = 2, Avx512 = 3 };

const char* isaName(Isa isa);
// "scalar" | "sse2" | "avx2" | "avx512"; nullopt when unknown.
std::optional<Isa> parseIsa(const std::string& name);
// The best path this CPU (and OS) supports.
Isa detectBestIsa();
bool isaSupported(Isa isa);

}  // namespace quadra

// Option-value parsing shared by the quadra commands: strict numbers, with a
// one-line Error naming the option on anything else.
#pragma once

#include <string>

namespace quadra {

double parseNumber(const std::string& option, const std::string& text);
int parseInteger(const std::string& option, const std::string& text, int lo, int hi);
bool endsWithIgnoringCase(const std::string& text, const std::string& suffix);

}  // namespace quadra

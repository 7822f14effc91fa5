#pragma once
// Small string helpers shared by the option and input code.
#include <cstring>
#include <string>

namespace nltopo {

// Whether s begins with the characters of p.
inline bool StartsWith(const std::string &s, const char *p) { return s.compare(0, std::strlen(p), p) == 0; }

} // namespace nltopo

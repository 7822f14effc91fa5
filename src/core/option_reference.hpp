#pragma once
// The options reference, generated from the option tables (core/option_table.hpp):
// `nltopo -option_tables md` writes docs/options.md, `nltopo -option_tables json`
// the rows as JSON for tools (tests/fuzz/fuzz.py draws its values from them).
#include <string>

namespace nltopo {

std::string OptionReferenceMarkdown();
std::string OptionReferenceJson();

} // namespace nltopo

#pragma once
// The outputs reference, generated from the schemas (io/schema.hpp):
// `nltopo -output_schema md` writes docs/outputs.md, and the help scene test
// checks that the committed page is what the binary writes.
#include <string>

namespace nltopo {

std::string OutputReferenceMarkdown();

} // namespace nltopo

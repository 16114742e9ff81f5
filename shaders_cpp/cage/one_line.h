// Error and warning text as Tessera prints it: one line, and floats in the fewest digits that say them. Readers quote
// what a library said (tinygltf, OpenImageIO, OpenSubdiv, CLI11), and that text may hold line breaks or be any length
// (a 10 MB bad token in a cage must not become a 10 MB "line").
#pragma once

#include <string>
#include <string_view>

namespace tessera {

// Line breaks become "; " (trailing separators dropped); a message of more than 600 bytes keeps its
// first and last 280 with the count of bytes left out between them.
std::string one_line_message(std::string_view message);

// A float in a message or a setting's text: the shortest decimal that parses back to the identical
// float (std::to_chars: 100, 0.1, 3e-05), or "nan", "inf", "-inf" as the settings' parser reads them.
std::string float_text(float x);

}  // namespace tessera

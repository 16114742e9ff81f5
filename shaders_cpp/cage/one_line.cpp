#include "shaders_cpp/cage/one_line.h"

#include <charconv>
#include <cmath>

namespace tessera {

std::string one_line_message(std::string_view message) {
  std::string s;
  for (const char c : message) {
    if (c == '\n' || c == '\r') {
      if (!s.empty() && s.back() != ' ') s += "; ";
    } else {
      s += c;
    }
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == ';')) s.pop_back();
  constexpr std::size_t kMax = 600, kKeep = 280;
  if (s.size() > kMax)
    s = s.substr(0, kKeep) + " [... " + std::to_string(s.size() - 2 * kKeep) + " bytes ...] " +
        s.substr(s.size() - kKeep);
  return s;
}

std::string float_text(float x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);  // shortest that reads back exactly
  return std::string(buffer, r.ptr);
}

}  // namespace tessera

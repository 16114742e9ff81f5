#include "pipeline/pipeline_state.h"

#include <array>
#include <utility>

namespace tessera {
namespace {

constexpr std::array<std::pair<CullMode, std::string_view>, 3> kCull{
    {{CullMode::none, "none"}, {CullMode::front, "front"}, {CullMode::back, "back"}}};
constexpr std::array<std::pair<CompareFunc, std::string_view>, 8> kCompare{
    {{CompareFunc::never, "never"},
     {CompareFunc::less, "less"},
     {CompareFunc::equal, "equal"},
     {CompareFunc::less_equal, "less_equal"},
     {CompareFunc::greater, "greater"},
     {CompareFunc::not_equal, "not_equal"},
     {CompareFunc::greater_equal, "greater_equal"},
     {CompareFunc::always, "always"}}};

template <class E, std::size_t K>
std::string_view name_of(const std::array<std::pair<E, std::string_view>, K>& table, E e) {
  for (const auto& [v, n] : table)
    if (v == e) return n;
  return "?";
}
template <class E, std::size_t K>
std::optional<E> parse(const std::array<std::pair<E, std::string_view>, K>& table, std::string_view s) {
  for (const auto& [v, n] : table)
    if (n == s) return v;
  return std::nullopt;
}

}  // namespace

std::string_view to_string(CullMode m) { return name_of(kCull, m); }
std::string_view to_string(CompareFunc f) { return name_of(kCompare, f); }
std::optional<CullMode> parse_cull_mode(std::string_view s) { return parse(kCull, s); }
std::optional<CompareFunc> parse_compare_func(std::string_view s) { return parse(kCompare, s); }

}  // namespace tessera

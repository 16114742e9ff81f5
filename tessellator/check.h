// Preconditions: what a caller must guarantee, checked where breaking it would corrupt state or
// memory. A failed check is a programmer's error, never bad data: data that can be wrong (a file, an
// option, a request) gets a returned error or the reader's exception naming the file and element.
//
//   TESSERA_CHECK(cond, context...)     always on; the context values are printed after the condition
//   TESSERA_CHECK_EQ/NE/LT/LE(a, b, ...)  always on; prints both expressions and their values
//   TESSERA_DCHECK*(...)                 the same, compiled in debug and sanitizer builds only (where a
//                                        check costs time on a hot path); elsewhere not evaluated
//
// A failed check throws CheckFailure (a std::logic_error) whose message reads
//   ".../limit_surface.cpp:389: check failed: positions.size() == m.vertex_limit.size()
//    (positions.size() = 3, m.vertex_limit.size() = 8) LimitSurface::repose: one position per cage vertex"
// so a library user's frame, a test or the CLI's top level reports it; nothing is logged here.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace tessera {

struct CheckFailure : std::logic_error {
  using std::logic_error::logic_error;
};

// Whether the TESSERA_DCHECK forms are compiled: debug (no NDEBUG) and sanitizer builds.
#if !defined(NDEBUG) || defined(TESSERA_SANITIZED)
inline constexpr bool kDchecks = true;
#else
inline constexpr bool kDchecks = false;
#endif

namespace detail {

template <class... Context>
std::string check_context(const Context&... context) {
  if constexpr (sizeof...(Context) == 0) {
    return {};
  } else {
    std::ostringstream s;
    ((s << ' ' << context), ...);
    return s.str();
  }
}

[[noreturn]] inline void check_failed(const char* file, int line, const char* condition, const std::string& values,
                                      const std::string& context) {
  std::string m = std::string(file) + ":" + std::to_string(line) + ": check failed: " + condition;
  if (!values.empty()) m += " (" + values + ")";
  throw CheckFailure(m + context);
}

template <class A, class B>
std::string check_values(const char* a_text, const A& a, const char* b_text, const B& b) {
  std::ostringstream s;
  s << a_text << " = " << a << ", " << b_text << " = " << b;
  return s.str();
}

}  // namespace detail
}  // namespace tessera

#define TESSERA_CHECK(cond, ...)                                                                             \
  do {                                                                                                       \
    if (!(cond)) [[unlikely]]                                                                                \
      ::tessera::detail::check_failed(__FILE__, __LINE__, #cond, {},                                         \
                                      ::tessera::detail::check_context(__VA_ARGS__));                        \
  } while (0)

#define TESSERA_CHECK_OP_(op, a, b, ...)                                                                     \
  do {                                                                                                       \
    const auto& tessera_check_a_ = (a);                                                                      \
    const auto& tessera_check_b_ = (b);                                                                      \
    if (!(tessera_check_a_ op tessera_check_b_)) [[unlikely]]                                                \
      ::tessera::detail::check_failed(                                                                       \
          __FILE__, __LINE__, #a " " #op " " #b,                                                             \
          ::tessera::detail::check_values(#a, tessera_check_a_, #b, tessera_check_b_),                       \
          ::tessera::detail::check_context(__VA_ARGS__));                                                    \
  } while (0)

#define TESSERA_CHECK_EQ(a, b, ...) TESSERA_CHECK_OP_(==, a, b, __VA_ARGS__)
#define TESSERA_CHECK_NE(a, b, ...) TESSERA_CHECK_OP_(!=, a, b, __VA_ARGS__)
#define TESSERA_CHECK_LT(a, b, ...) TESSERA_CHECK_OP_(<, a, b, __VA_ARGS__)
#define TESSERA_CHECK_LE(a, b, ...) TESSERA_CHECK_OP_(<=, a, b, __VA_ARGS__)

// Off: `if constexpr` keeps the expressions compiled (so they cannot rot) but never evaluated.
#define TESSERA_DCHECK(cond, ...)                                 \
  do {                                                            \
    if constexpr (::tessera::kDchecks) TESSERA_CHECK(cond, __VA_ARGS__); \
  } while (0)
#define TESSERA_DCHECK_EQ(a, b, ...)                                            \
  do {                                                                          \
    if constexpr (::tessera::kDchecks) TESSERA_CHECK_EQ(a, b, __VA_ARGS__);     \
  } while (0)
#define TESSERA_DCHECK_LT(a, b, ...)                                            \
  do {                                                                          \
    if constexpr (::tessera::kDchecks) TESSERA_CHECK_LT(a, b, __VA_ARGS__);     \
  } while (0)
#define TESSERA_DCHECK_LE(a, b, ...)                                            \
  do {                                                                          \
    if constexpr (::tessera::kDchecks) TESSERA_CHECK_LE(a, b, __VA_ARGS__);     \
  } while (0)

// tessellator/check.h: a failed precondition names its file, line and condition and prints the values,
// a passing one evaluates its operands once, and the TESSERA_DCHECK forms run exactly where kDchecks
// says (debug and sanitizer builds).
#include <string>

#include <catch2/catch.hpp>

#include "shaders_cpp/cage/cage_obj.h"
#include "shaders_cpp/subdiv/limit_surface.h"
#include "tessellator/check.h"
#include "test_data.h"

using namespace tessera;

namespace {

std::string failure_of(auto&& f) {
  try {
    f();
  } catch (const CheckFailure& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("TESSERA_CHECK_EQ prints both expressions and their values, then the context", "[check]") {
  const int vertices = 8;
  const std::size_t given = 3;
  const std::string m = failure_of([&] { TESSERA_CHECK_EQ(given, std::size_t(vertices), "repose:", "one per vertex"); });
  CHECK_THAT(m, Catch::Contains("test_preconditions.cpp:"));
  CHECK_THAT(m, Catch::Contains("check failed: given == std::size_t(vertices) (given = 3, std::size_t(vertices) = 8)"));
  CHECK_THAT(m, Catch::Contains("repose: one per vertex"));
  CHECK(failure_of([&] { TESSERA_CHECK_LT(given, std::size_t(vertices)); }).empty());
  CHECK_THAT(failure_of([&] { TESSERA_CHECK_LE(vertices, 2); }), Catch::Contains("(vertices = 8, 2 = 2)"));
  CHECK_THAT(failure_of([&] { TESSERA_CHECK(given > 5, "given", given); }),
             Catch::Contains("check failed: given > 5 given 3"));
}

TEST_CASE("a check evaluates its operands once, a DCHECK runs only where kDchecks is on", "[check]") {
  int evaluated = 0;
  auto next = [&] { return ++evaluated; };
  TESSERA_CHECK_EQ(next(), 1);
  CHECK(evaluated == 1);
  int dchecked = 0;
  TESSERA_DCHECK(++dchecked > 0);
  CHECK(dchecked == (kDchecks ? 1 : 0));
  const bool thrown = !failure_of([] { TESSERA_DCHECK(1 + 1 == 3, "arithmetic"); }).empty();
  CHECK(thrown == kDchecks);
#if defined(TESSERA_SANITIZED)
  CHECK(kDchecks);  // sanitizer builds run the DCHECKs
#endif
}

TEST_CASE("a programmer's error in the library is a CheckFailure naming the call", "[check]") {
  const Cage cage = load_obj_cage(test::data("osd-shapes/catmark_cube.obj"));
  LimitSurface s = LimitSurface::create(cage);
  const std::vector<glm::vec3> three(3, glm::vec3(0.0f));
  const std::string m = failure_of([&] { s.repose(three); });
  CHECK_THAT(m, Catch::Contains("limit_surface.cpp"));
  CHECK_THAT(m, Catch::Contains("(positions.size() = 3, m.vertex_limit.size() = 8)"));
  CHECK_THAT(failure_of([&] { (void)s.patch_counts(); }), Catch::Contains("the adaptive method only"));
}

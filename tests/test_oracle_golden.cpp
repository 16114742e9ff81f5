// Differential test against the D3D11 reference, without Mesa: the digests in
// golden/tessellator/oracle_digests.txt were captured from llvmpipe (tools/regen_golden.sh), and
// golden/tessellator/oracle_small.dump holds full captures of small cases.
#include <catch2/catch.hpp>

#include <fstream>

#include "tools/verify/oracle.h"

using namespace tessera;

TEST_CASE("tessellator output equals the D3D11 reference's captured digests, in order", "[tessellator][oracle]") {
  std::ifstream in(TESSERA_GOLDEN_DIR "/tessellator/oracle_digests.txt");
  REQUIRE(in);
  std::string line;
  int cases = 0, line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    oracle::Case c;
    oracle::Digest want;
    std::string error;
    INFO("golden line " << line_no << ": " << line);
    REQUIRE(oracle::parse_golden_line(line, c, want, error));
    const auto got = oracle::digest(oracle::tessera_primitives(c));
    CHECK(got.primitives == want.primitives);
    CHECK(got.set == want.set);
    CHECK(got.ordered == want.ordered);  // same primitives in the same order
    ++cases;
  }
  CHECK(cases >= 300);
}

TEST_CASE("tessellator output equals full reference captures of small cases", "[tessellator][oracle]") {
  std::ifstream in(TESSERA_GOLDEN_DIR "/tessellator/oracle_small.dump");
  REQUIRE(in);
  std::vector<oracle::Capture> captures;
  std::string error;
  REQUIRE(oracle::read_dump(in, captures, error));
  REQUIRE(captures.size() >= 20);
  for (const auto& cap : captures) {
    INFO(cap.c.line);
    const auto cmp = oracle::compare(cap.primitives, oracle::tessera_primitives(cap.c));
    CHECK(cmp.set_equal);
    CHECK(cmp.order_equal);
  }
}

TEST_CASE("the oracle comparison detects a difference", "[tessellator][oracle]") {
  oracle::Case c;
  std::string error;
  REQUIRE(oracle::parse_case_line("quads equal_spacing ccw prims 3 3 3 3 3 3", c, error));
  auto ours = oracle::tessera_primitives(c);
  auto changed = ours;
  changed[5][1][0] ^= 1;  // one bit of one coordinate
  CHECK_FALSE(oracle::compare(ours, changed).set_equal);
  CHECK(oracle::digest(ours) != oracle::digest(changed));
  std::swap(changed[0], changed[1]);
  CHECK_FALSE(oracle::compare(ours, changed).order_equal);
  CHECK_FALSE(oracle::parse_case_line("quads equal_spacing ccw prims 3 3 3", c, error));
  CHECK_FALSE(oracle::parse_case_line("cubes equal_spacing ccw prims 3 3 3 3 3 3", c, error));
}

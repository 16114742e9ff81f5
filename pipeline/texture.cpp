#include "pipeline/texture.h"

#include "pipeline/simd4.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace tessera {
namespace {

// Beyond this a texel-space coordinate is reduced before it becomes an int (i0 + 1 must not
// overflow either). Any float this large is already an integer, so the reduction is exact.
constexpr float kFarCoordinate = 1073741824.0f;  // 2^30

// floor for |x| < 2^30 without a libm call: truncate, then step down for negative non-integers.
inline int floor_to_int(float x) {
  const int t = static_cast<int>(x);
  return x < static_cast<float>(t) ? t - 1 : t;
}

int wrap_index(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// GL's MIRRORED_REPEAT on integer coordinates: 0 1 .. n-1 | n-1 .. 1 0 | 0 1 ..
int mirror_index(int i, int n) {
  const int m = wrap_index(i, 2 * n);
  return m < n ? m : 2 * n - 1 - m;
}

// The addressing of an index outside [0, n). Kept out of line so that the in-range test below
// stays small enough to inline into every tap.
[[gnu::noinline]] int address_outside(int i, int n, AddressMode mode) {
  switch (mode) {
    case AddressMode::wrap: return wrap_index(i, n);
    case AddressMode::clamp: return i < 0 ? 0 : n - 1;
    case AddressMode::mirror: return mirror_index(i, n);
  }
  return 0;
}

// Every mode is the identity inside the level, which is where almost all taps land.
inline int address(int i, int n, AddressMode mode) {
  return static_cast<unsigned>(i) < static_cast<unsigned>(n) ? i : address_outside(i, n, mode);
}

// A texel-space coordinate that is NaN, infinite or too large for an int, brought into range
// without changing the texels it addresses (see the header). fmod is exact, and its result
// (|r| < 2n <= 65536, an integer) converts to float exactly.
float reduce_far(float x, int n, AddressMode mode) {
  if (!std::isfinite(x)) return 0.0f;
  switch (mode) {
    case AddressMode::wrap: return static_cast<float>(std::fmod(static_cast<double>(x), static_cast<double>(n)));
    case AddressMode::mirror:
      return static_cast<float>(std::fmod(static_cast<double>(x), 2.0 * static_cast<double>(n)));
    case AddressMode::clamp: break;
  }
  return x < 0.0f ? -1.0f : static_cast<float>(n);
}

inline int point_tap(float x, int n, AddressMode mode) {
  // NaN fails the comparison, so it takes the reduction path too.
  if (!(std::fabs(x) < kFarCoordinate)) x = reduce_far(x, n, mode);
  return address(floor_to_int(x), n, mode);
}

struct LinearTaps {
  int i0;
  int i1;
  float frac;  // weight of i1
};

inline LinearTaps linear_taps(float x, int n, AddressMode mode) {
  if (!(std::fabs(x) < kFarCoordinate)) x = reduce_far(x, n, mode);
  const int i = floor_to_int(x);
  // x - floor(x) is exact: it is x's fractional bits, which a float holds (0 once |x| >= 2^23).
  return {address(i, n, mode), address(i + 1, n, mode), x - static_cast<float>(i)};
}

// Missing channels read as (0, 0, 0, 1); the channel count is a template argument so the
// one-channel path loads one float per texel. Results go through a plain array: glm's
// operator[] is a switch with an assert, which stops the channel loop from unrolling.
template <int C>
glm::vec4 fetch(const float* p) {
  float out[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  for (int c = 0; c < C; ++c) out[c] = p[c];
  return {out[0], out[1], out[2], out[3]};
}

glm::vec4 fetch(const float* p, int channels) {
  switch (channels) {
    case 1: return fetch<1>(p);
    case 2: return fetch<2>(p);
    case 3: return fetch<3>(p);
    default: return fetch<4>(p);
  }
}

template <int C>
glm::vec4 bilerp(const float* level, int width, const LinearTaps& tu, const LinearTaps& tv) {
  const std::size_t stride = static_cast<std::size_t>(width) * C;
  const float* row0 = level + static_cast<std::size_t>(tv.i0) * stride;
  const float* row1 = level + static_cast<std::size_t>(tv.i1) * stride;
  const std::size_t x0 = static_cast<std::size_t>(tu.i0) * C;
  const std::size_t x1 = static_cast<std::size_t>(tu.i1) * C;
  const float wu0 = 1.0f - tu.frac;
  const float wv0 = 1.0f - tv.frac;
  float out[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  for (int c = 0; c < C; ++c) {
    const float top = row0[x0 + c] * wu0 + row0[x1 + c] * tu.frac;
    const float bottom = row1[x0 + c] * wu0 + row1[x1 + c] * tu.frac;
    out[c] = top * wv0 + bottom * tv.frac;
  }
  return {out[0], out[1], out[2], out[3]};
}

// One destination texel of a mip reduction along one axis: up to three source texels, their
// integer overlaps with the footprint, and the footprint's length in the same units. Integer
// weights with one division at the end keep results exact wherever the weighted sum is.
struct BoxTaps {
  int first = 0;
  int count = 0;
  std::array<float, 3> weight{};
  float denominator = 1.0f;
};

// Taps reducing a size s to max(1, s / 2); see "Mip chain" in the header.
std::vector<BoxTaps> box_taps(int s) {
  const int d = s / 2 > 1 ? s / 2 : 1;
  std::vector<BoxTaps> taps(static_cast<std::size_t>(d));
  if (s == 1) {
    taps[0] = {0, 1, {1.0f, 0.0f, 0.0f}, 1.0f};
    return taps;
  }
  if (s % 2 == 0) {
    for (int i = 0; i < d; ++i) taps[static_cast<std::size_t>(i)] = {2 * i, 2, {1.0f, 1.0f, 0.0f}, 2.0f};
    return taps;
  }
  // Odd s = 2d + 1: in units of 1/d source texels, destination i covers [i*s, (i+1)*s) and source
  // texel j covers [j*d, (j+1)*d). The footprint is 2 + 1/d texels long, so it overlaps at most 3.
  for (int i = 0; i < d; ++i) {
    const std::int64_t lo = std::int64_t{i} * s;
    const std::int64_t hi = lo + s;
    BoxTaps& t = taps[static_cast<std::size_t>(i)];
    t.first = static_cast<int>(lo / d);
    t.denominator = static_cast<float>(s);
    for (std::int64_t j = t.first; j * d < hi; ++j) {
      const std::int64_t a = j * d > lo ? j * d : lo;
      const std::int64_t b = (j + 1) * d < hi ? (j + 1) * d : hi;
      t.weight[static_cast<std::size_t>(t.count++)] = static_cast<float>(b - a);
    }
  }
  return taps;
}

// One reduced value: `src` is the first source texel's channel on the reduced axis, `step` the
// floats between neighbours along it. Summed in tap order, then divided once.
float reduce_one(const float* src, std::size_t step, const BoxTaps& t) {
  const std::size_t first = static_cast<std::size_t>(t.first);
  float sum = t.weight[0] * src[first * step];
  for (std::size_t k = 1; k < static_cast<std::size_t>(t.count); ++k) sum = sum + t.weight[k] * src[(first + k) * step];
  return sum / t.denominator;
}

// Builds one mip level from the previous: u first (rows), then v (columns).
void build_level(const float* src, int sw, int sh, int channels, float* dst, int dw, int dh) {
  const std::size_t c = static_cast<std::size_t>(channels);
  // Horizontal pass: sw x sh -> dw x sh.
  std::vector<float> tmp(static_cast<std::size_t>(dw) * static_cast<std::size_t>(sh) * c);
  const std::vector<BoxTaps> tu = box_taps(sw);
  for (std::size_t y = 0; y < static_cast<std::size_t>(sh); ++y) {
    const float* srow = src + y * static_cast<std::size_t>(sw) * c;
    float* trow = tmp.data() + y * static_cast<std::size_t>(dw) * c;
    for (std::size_t x = 0; x < static_cast<std::size_t>(dw); ++x)
      for (std::size_t k = 0; k < c; ++k) trow[x * c + k] = reduce_one(srow + k, c, tu[x]);
  }
  // Vertical pass: dw x sh -> dw x dh.
  const std::vector<BoxTaps> tv = box_taps(sh);
  const std::size_t row = static_cast<std::size_t>(dw) * c;
  for (std::size_t y = 0; y < static_cast<std::size_t>(dh); ++y)
    for (std::size_t i = 0; i < row; ++i) dst[y * row + i] = reduce_one(tmp.data() + i, row, tv[y]);
}

std::string size_error(const char* what, int value, int lo, int hi) {
  return "texture " + std::string(what) + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
         std::to_string(value);
}

}  // namespace

std::string_view to_string(Filter f) {
  switch (f) {
    case Filter::point: return "point";
    case Filter::bilinear: return "bilinear";
    case Filter::trilinear: return "trilinear";
  }
  return "?";
}

std::optional<Filter> parse_filter(std::string_view s) {
  for (Filter f : {Filter::point, Filter::bilinear, Filter::trilinear})
    if (s == to_string(f)) return f;
  return std::nullopt;
}

std::string_view to_string(AddressMode m) {
  switch (m) {
    case AddressMode::wrap: return "wrap";
    case AddressMode::clamp: return "clamp";
    case AddressMode::mirror: return "mirror";
  }
  return "?";
}

std::optional<AddressMode> parse_address_mode(std::string_view s) {
  for (AddressMode m : {AddressMode::wrap, AddressMode::clamp, AddressMode::mirror})
    if (s == to_string(m)) return m;
  return std::nullopt;
}

std::optional<Texture2D> Texture2D::create(int width, int height, int channels, std::vector<float> texels,
                                           bool build_mips, std::string* error) {
  std::string reason;
  if (width < 1 || width > kMaxTextureSize) {
    reason = size_error("width", width, 1, kMaxTextureSize);
  } else if (height < 1 || height > kMaxTextureSize) {
    reason = size_error("height", height, 1, kMaxTextureSize);
  } else if (channels < 1 || channels > 4) {
    reason = size_error("channels", channels, 1, 4);
  } else {
    const std::size_t expected =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels);
    if (texels.size() != expected)
      reason = "texture of " + std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels) +
               " needs " + std::to_string(expected) + " floats, got " + std::to_string(texels.size());
  }
  if (!reason.empty()) {
    if (error) *error = std::move(reason);
    return std::nullopt;
  }

  Texture2D t;
  t.channels_ = channels;
  std::size_t total = 0;
  int w = width;
  int h = height;
  for (;;) {
    Level& level = t.levels_info_[static_cast<std::size_t>(t.levels_++)];
    level = {w, h, static_cast<float>(w), static_cast<float>(h), total};
    total += static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(channels);
    if (!build_mips || (w == 1 && h == 1)) break;
    w = w / 2 > 1 ? w / 2 : 1;
    h = h / 2 > 1 ? h / 2 : 1;
  }

  // Level 0 stays where the caller's vector put it; the smaller levels follow it.
  t.texels_ = std::move(texels);
  t.texels_.resize(total);
  for (int i = 1; i < t.levels_; ++i) {
    const Level& src = t.levels_info_[static_cast<std::size_t>(i - 1)];
    const Level& dst = t.levels_info_[static_cast<std::size_t>(i)];
    build_level(t.texels_.data() + src.offset, src.width, src.height, channels, t.texels_.data() + dst.offset,
                dst.width, dst.height);
  }
  return t;
}

int Texture2D::width(int level) const {
  return level >= 0 && level < levels_ ? levels_info_[static_cast<std::size_t>(level)].width : 0;
}

int Texture2D::height(int level) const {
  return level >= 0 && level < levels_ ? levels_info_[static_cast<std::size_t>(level)].height : 0;
}

glm::vec4 Texture2D::load(int level, int x, int y) const {
  if (level < 0 || level >= levels_) return glm::vec4(0.0f);
  const Level& l = levels_info_[static_cast<std::size_t>(level)];
  if (x < 0 || x >= l.width || y < 0 || y >= l.height) return glm::vec4(0.0f);
  const std::size_t c = static_cast<std::size_t>(channels_);
  return fetch(texels_.data() + l.offset +
                   (static_cast<std::size_t>(y) * static_cast<std::size_t>(l.width) + static_cast<std::size_t>(x)) * c,
               channels_);
}

float Texture2D::clamp_lod(const Sampler& s, float lod) const {
  // Written as compares so that a NaN (lod, bias or sampler field) lands on a bound: a comparison
  // with NaN is false and selects the right-hand side.
  float x = lod > s.min_lod ? lod : s.min_lod;
  x = x < s.max_lod ? x : s.max_lod;
  x = x > 0.0f ? x : 0.0f;
  const float top = static_cast<float>(levels_ - 1);
  return x < top ? x : top;
}

glm::vec4 Texture2D::sample_point(const Sampler& s, const Level& level, glm::vec2 uv) const {
  const int x = point_tap(uv.x * level.fwidth, level.width, s.address_u);
  const int y = point_tap(uv.y * level.fheight, level.height, s.address_v);
  const std::size_t c = static_cast<std::size_t>(channels_);
  return fetch(
      texels_.data() + level.offset +
          (static_cast<std::size_t>(y) * static_cast<std::size_t>(level.width) + static_cast<std::size_t>(x)) * c,
      channels_);
}

glm::vec4 Texture2D::sample_bilinear(const Sampler& s, const Level& level, glm::vec2 uv) const {
  const LinearTaps tu = linear_taps(uv.x * level.fwidth - 0.5f, level.width, s.address_u);
  const LinearTaps tv = linear_taps(uv.y * level.fheight - 0.5f, level.height, s.address_v);
  const float* base = texels_.data() + level.offset;
  switch (channels_) {
    case 1: return bilerp<1>(base, level.width, tu, tv);
    case 2: return bilerp<2>(base, level.width, tu, tv);
    case 3: return bilerp<3>(base, level.width, tu, tv);
    default: return bilerp<4>(base, level.width, tu, tv);
  }
}

// lod is already clamped to [0, levels_ - 1], so every level index below is in range.
glm::vec4 Texture2D::sample_at_lod(const Sampler& s, glm::vec2 uv, float lod) const {
  switch (s.filter) {
    case Filter::point: return sample_point(s, levels_info_[static_cast<std::size_t>(lod + 0.5f)], uv);
    case Filter::bilinear: return sample_bilinear(s, levels_info_[static_cast<std::size_t>(lod + 0.5f)], uv);
    case Filter::trilinear: break;
  }
  const int l0 = static_cast<int>(lod);
  const float f = lod - static_cast<float>(l0);
  const glm::vec4 a = sample_bilinear(s, levels_info_[static_cast<std::size_t>(l0)], uv);
  if (f == 0.0f) return a;  // also the top level, where l0 + 1 does not exist
  const glm::vec4 b = sample_bilinear(s, levels_info_[static_cast<std::size_t>(l0 + 1)], uv);
  // Component-wise, as a * (1 - f) + b * f. The defaults of missing channels stay exact:
  // (1 - f) + f == 1 for every float f in [0, 1] (checked exhaustively).
  return a * (1.0f - f) + b * f;
}

glm::vec4 Texture2D::sample_level(const Sampler& s, glm::vec2 uv, float lod) const {
  return sample_at_lod(s, uv, clamp_lod(s, lod + s.mip_lod_bias));
}

namespace {

// sample_level4's taps when, in every lane, both taps of each axis lie inside the level (no address
// mode applies): the coordinate, its floor and its fraction in lanes, each the scalar expression of
// linear_taps (truncate, then one less where the coordinate is below it; the fraction by subtraction).
// False, with nothing written, when any lane needs linear_taps' far-coordinate or addressing paths.
//
// The taps come back in registers (simd::F4), each vector built from its four loads: written to an
// array lane by lane and read back as one vector, every such read waited for its four stores to reach
// the cache (a load that spans several stores is not forwarded from the store buffer).
template <class Level>
bool bilinear_taps_inside4(const std::array<glm::vec2, 4>& uv, const Level& level, const float* base,
                           std::size_t stride, simd::F4& t00, simd::F4& t01, simd::F4& t10, simd::F4& t11, simd::F4& fu,
                           simd::F4& fv) {
#if defined(__SSE2__)
  const __m128 x = _mm_sub_ps(_mm_mul_ps(_mm_setr_ps(uv[0].x, uv[1].x, uv[2].x, uv[3].x), _mm_set1_ps(level.fwidth)),
                              _mm_set1_ps(0.5f));
  const __m128 y = _mm_sub_ps(_mm_mul_ps(_mm_setr_ps(uv[0].y, uv[1].y, uv[2].y, uv[3].y), _mm_set1_ps(level.fheight)),
                              _mm_set1_ps(0.5f));
  const __m128 magnitude = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)), far = _mm_set1_ps(kFarCoordinate);
  // NaN compares false, so it fails here as in linear_taps.
  const __m128 near =
      _mm_and_ps(_mm_cmplt_ps(_mm_and_ps(x, magnitude), far), _mm_cmplt_ps(_mm_and_ps(y, magnitude), far));
  if (_mm_movemask_ps(near) != 0xF) return false;
  const auto floor_lanes = [](__m128 a) {
    const __m128i t = _mm_cvttps_epi32(a);
    return _mm_add_epi32(t, _mm_castps_si128(_mm_cmplt_ps(a, _mm_cvtepi32_ps(t))));  // the mask is -1 where a < t
  };
  const __m128i iu = floor_lanes(x), iv = floor_lanes(y);
  // Both taps inside: 0 <= i and i + 1 <= n - 1.
  const auto inside = [](__m128i i, int n) {
    return _mm_and_si128(_mm_cmpgt_epi32(i, _mm_set1_epi32(-1)), _mm_cmplt_epi32(i, _mm_set1_epi32(n - 1)));
  };
  if (_mm_movemask_ps(_mm_castsi128_ps(_mm_and_si128(inside(iu, level.width), inside(iv, level.height)))) != 0xF)
    return false;
  fu = simd::F4{_mm_sub_ps(x, _mm_cvtepi32_ps(iu))};
  fv = simd::F4{_mm_sub_ps(y, _mm_cvtepi32_ps(iv))};
  alignas(16) std::int32_t column[4], row[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(column), iu);
  _mm_store_si128(reinterpret_cast<__m128i*>(row), iv);
  const float* r[4];
  for (std::size_t k = 0; k < 4; ++k)
    r[k] = base + static_cast<std::size_t>(row[k]) * stride + static_cast<std::size_t>(column[k]);
  t00 = simd::F4{_mm_setr_ps(r[0][0], r[1][0], r[2][0], r[3][0])};
  t01 = simd::F4{_mm_setr_ps(r[0][1], r[1][1], r[2][1], r[3][1])};
  t10 = simd::F4{_mm_setr_ps(r[0][stride], r[1][stride], r[2][stride], r[3][stride])};
  t11 = simd::F4{_mm_setr_ps(r[0][stride + 1], r[1][stride + 1], r[2][stride + 1], r[3][stride + 1])};
  return true;
#else
  (void)uv, (void)level, (void)base, (void)stride, (void)t00, (void)t01, (void)t10, (void)t11, (void)fu, (void)fv;
  return false;
#endif
}

}  // namespace

// bilerp<1> of one level in lanes: the taps per lane as sample_bilinear finds them, then the same
// weights and the same operations in the same order.
void Texture2D::bilinear4(const Sampler& s, const Level& level, const std::array<glm::vec2, 4>& uv,
                          std::array<float, 4>& out) const {
  using simd::F4;
  const float* base = texels_.data() + level.offset;
  const std::size_t stride = static_cast<std::size_t>(level.width);
  F4 t00, t01, t10, t11, u1, v1;
  if (!bilinear_taps_inside4(uv, level, base, stride, t00, t01, t10, t11, u1, v1)) {
    std::array<float, 4> a00, a01, a10, a11, fu, fv;
    for (std::size_t k = 0; k < 4; ++k) {
      const LinearTaps tu = linear_taps(uv[k].x * level.fwidth - 0.5f, level.width, s.address_u);
      const LinearTaps tv = linear_taps(uv[k].y * level.fheight - 0.5f, level.height, s.address_v);
      const float* row0 = base + static_cast<std::size_t>(tv.i0) * stride;
      const float* row1 = base + static_cast<std::size_t>(tv.i1) * stride;
      a00[k] = row0[tu.i0];
      a01[k] = row0[tu.i1];
      a10[k] = row1[tu.i0];
      a11[k] = row1[tu.i1];
      fu[k] = tu.frac;
      fv[k] = tv.frac;
    }
    t00 = F4::load(a00), t01 = F4::load(a01), t10 = F4::load(a10), t11 = F4::load(a11);
    u1 = F4::load(fu), v1 = F4::load(fv);
  }
  const F4 one = F4::splat(1.0f);
  const F4 u0 = one - u1, v0 = one - v1;
  const F4 top = t00 * u0 + t01 * u1;
  const F4 bottom = t10 * u0 + t11 * u1;
  (top * v0 + bottom * v1).store(out);
}

void Texture2D::sample_level4(const Sampler& s, const std::array<glm::vec2, 4>& uv, float lod,
                              std::array<glm::vec4, 4>& out) const {
  const float l = clamp_lod(s, lod + s.mip_lod_bias);
  if (s.filter == Filter::point || channels_ != 1) {
    for (std::size_t k = 0; k < 4; ++k) out[k] = sample_at_lod(s, uv[k], l);
    return;
  }
  // sample_at_lod's levels and blend in lanes. A one-channel texel is (r, 0, 0, 1), and the blend keeps
  // the constant channels exact ((1 - f) + f == 1), so only r is computed.
  using simd::F4;
  std::array<float, 4> lanes;
  if (s.filter == Filter::bilinear) {
    bilinear4(s, levels_info_[static_cast<std::size_t>(l + 0.5f)], uv, lanes);
  } else {
    const int l0 = static_cast<int>(l);
    const float f = l - static_cast<float>(l0);
    bilinear4(s, levels_info_[static_cast<std::size_t>(l0)], uv, lanes);
    if (f != 0.0f) {
      std::array<float, 4> next;
      bilinear4(s, levels_info_[static_cast<std::size_t>(l0 + 1)], uv, next);
      (F4::load(lanes) * F4::splat(1.0f - f) + F4::load(next) * F4::splat(f)).store(lanes);
    }
  }
  for (std::size_t k = 0; k < 4; ++k) out[k] = glm::vec4(lanes[k], 0.0f, 0.0f, 1.0f);
}

float Texture2D::grad_lod(glm::vec2 ddx, glm::vec2 ddy) const {
  const Level& base = levels_info_[0];
  const float xu = ddx.x * base.fwidth;
  const float xv = ddx.y * base.fheight;
  const float yu = ddy.x * base.fwidth;
  const float yv = ddy.y * base.fheight;
  const float lx = xu * xu + xv * xv;
  const float ly = yu * yu + yv * yv;
  // log2(max(|a|, |b|)) = log2(max(|a|^2, |b|^2)) / 2: one log, no square roots.
  return 0.5f * std::log2(lx > ly ? lx : ly);
}

glm::vec4 Texture2D::sample_grad(const Sampler& s, glm::vec2 uv, glm::vec2 ddx, glm::vec2 ddy) const {
  return sample_level(s, uv, grad_lod(ddx, ddy));
}

void Texture2D::sample_grad4(const Sampler& s, const std::array<glm::vec2, 4>& uv, glm::vec2 ddx, glm::vec2 ddy,
                             std::array<glm::vec4, 4>& out) const {
  sample_level4(s, uv, grad_lod(ddx, ddy), out);
}

}  // namespace tessera

#include "shaders_cpp/animation/animation_sampler.h"

#include <algorithm>
#include <charconv>

namespace tessera {
namespace {

// The key interval holding `time`: k with times[k] <= time < times[k + 1], and the fraction across it.
struct KeySpan {
  std::size_t k = 0;
  double s = 0.0;       // 0..1 across the interval
  double length = 0.0;  // the interval in seconds
  bool clamped = true;  // before the first or after the last key: value k only
};

KeySpan find_span(const std::vector<float>& times, double time) {
  KeySpan span;
  if (times.size() < 2 || time <= double(times.front())) return span;
  if (time >= double(times.back())) {
    span.k = times.size() - 1;
    return span;
  }
  const auto it =
      std::upper_bound(times.begin(), times.end(), time, [](double t, float key) { return t < double(key); });
  span.k = std::size_t(it - times.begin()) - 1;
  span.length = double(times[span.k + 1]) - double(times[span.k]);
  span.s = (time - double(times[span.k])) / span.length;
  span.clamped = false;
  return span;
}

// The value of component c (0..width-1) of key k: for cubic_spline the middle of the three groups.
double value(const AnimationChannel& ch, std::size_t k, int c, int group = 1) {
  const std::size_t w = std::size_t(ch.width);
  const std::size_t per_key = ch.interpolation == Interpolation::cubic_spline ? 3 * w : w;
  const std::size_t g = ch.interpolation == Interpolation::cubic_spline ? std::size_t(group) : 0;
  return double(ch.values[k * per_key + g * w + std::size_t(c)]);
}

// The channel's `width` components at `time`. Rotations are slerped (LINEAR) or normalised after.
std::vector<double> sample(const AnimationChannel& ch, double time) {
  const KeySpan span = find_span(ch.times, time);
  std::vector<double> out(std::size_t(ch.width));
  const bool rotation = ch.path == AnimationPath::rotation;
  if (span.clamped || ch.interpolation == Interpolation::step) {
    for (int c = 0; c < ch.width; ++c) out[std::size_t(c)] = value(ch, span.k, c);
  } else if (ch.interpolation == Interpolation::linear && rotation) {
    const glm::dquat a(value(ch, span.k, 3), value(ch, span.k, 0), value(ch, span.k, 1), value(ch, span.k, 2));
    const glm::dquat b(value(ch, span.k + 1, 3), value(ch, span.k + 1, 0), value(ch, span.k + 1, 1),
                       value(ch, span.k + 1, 2));
    const glm::dquat q = glm::slerp(a, b, span.s);  // GLM takes the shorter arc
    out = {q.x, q.y, q.z, q.w};
  } else if (ch.interpolation == Interpolation::linear) {
    for (int c = 0; c < ch.width; ++c)
      out[std::size_t(c)] = value(ch, span.k, c) + span.s * (value(ch, span.k + 1, c) - value(ch, span.k, c));
  } else {  // cubic_spline: glTF §3.11.4 (out-tangent of k, in-tangent of k + 1)
    const double s = span.s, s2 = s * s, s3 = s2 * s, d = span.length;
    for (int c = 0; c < ch.width; ++c)
      out[std::size_t(c)] = (2 * s3 - 3 * s2 + 1) * value(ch, span.k, c) +
                            d * (s3 - 2 * s2 + s) * value(ch, span.k, c, 2) +
                            (-2 * s3 + 3 * s2) * value(ch, span.k + 1, c) + d * (s3 - s2) * value(ch, span.k + 1, c, 0);
  }
  if (rotation) {
    const glm::dquat q = glm::normalize(glm::dquat(out[3], out[0], out[1], out[2]));
    out = {q.x, q.y, q.z, q.w};
  }
  return out;
}

}  // namespace

std::vector<NodeState> animate_nodes(const CageRig& rig, int animation, double time) {
  std::vector<NodeState> nodes = rest_nodes(rig);
  if (animation < 0 || animation >= int(rig.animations.size())) return nodes;
  for (const AnimationChannel& ch : rig.animations[std::size_t(animation)].channels) {
    const std::vector<double> v = sample(ch, time);
    NodeState& n = nodes[std::size_t(ch.node)];
    switch (ch.path) {
      case AnimationPath::translation: n.translation = {v[0], v[1], v[2]}; break;
      case AnimationPath::scale: n.scale = {v[0], v[1], v[2]}; break;
      case AnimationPath::rotation: n.rotation = glm::dquat(v[3], v[0], v[1], v[2]); break;
      case AnimationPath::weights: n.weights = v; break;
    }
  }
  return nodes;
}

int find_animation(const CageRig& rig, const std::string& name) {
  for (std::size_t a = 0; a < rig.animations.size(); ++a)
    if (rig.animations[a].name == name) return int(a);
  int index = -1;
  const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), index);
  if (ec == std::errc() && end == name.data() + name.size() && index >= 0 && index < int(rig.animations.size()))
    return index;
  return -1;
}

}  // namespace tessera

// Position functions, progress and the CPU reference renderer. The GLSL renderer (shaders/folding/fold.glsl)
// evaluates the same equations in the same order, in float, so the two agree within rounding.
#include <sylva/folding/Renderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::folding {

double PositionFunction::evaluate(double phi) const {
  switch (type) {
  case Type::Linear:
    return std::clamp(slope * (phi - delay), 0.0, 1.0);
  case Type::Piecewise: {
    if (knots.empty()) {
      return phi;
    }
    if (phi <= knots.front().x) {
      return knots.front().y;
    }
    for (std::size_t i = 1; i < knots.size(); ++i) {
      if (phi <= knots[i].x) {
        const double f = (phi - knots[i - 1].x) / (knots[i].x - knots[i - 1].x);
        return knots[i - 1].y + f * (knots[i].y - knots[i - 1].y);
      }
    }
    return knots.back().y;
  }
  case Type::Exponential:
    if (std::abs(k) < 1e-6) {
      return phi;
    }
    return std::expm1(k * phi) / std::expm1(k);
  case Type::Sigmoid: {
    auto sigma = [](double z) { return 1.0 / (1.0 + std::exp(-z)); };
    const double lo = sigma(-k * centre);
    const double hi = sigma(k * (1.0 - centre));
    return (sigma(k * (phi - centre)) - lo) / (hi - lo);
  }
  case Type::Sine:
    return amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * frequency * phi + phase)) * 0.5 + offset;
  }
  return phi;
}

namespace {

/** fract(t/T + σ) in double: the per-profile part of φ, so large t loses no precision. */
double basePhase(const Profile& profile, double t) {
  const double v = t / profile.periodS + profile.shift;
  return v - std::floor(v);
}

float fractf(float v) {
  return v - std::floor(v);
}

/** φ with the loop remap applied, from the profile's base phase and the texel's offset (float, as in GLSL).
 */
float texelPhase(const Profile& profile, float base, float dt) {
  float phi = fractf(base + dt);
  if (profile.loop == LoopMode::PingPong) {
    phi = 1.0f - std::abs(1.0f - 2.0f * phi);
  }
  return phi;
}

} // namespace

double progressAt(const Profile& profile, double t, double dt) {
  return profile.fn.evaluate(
      texelPhase(profile, static_cast<float>(basePhase(profile, t)), static_cast<float>(dt)));
}

CrossfadePhases crossfadePhases(const Profile& profile, double t, double dt) {
  const float phi1 = fractf(static_cast<float>(basePhase(profile, t)) + static_cast<float>(dt));
  const float phi2 = fractf(phi1 + 0.5f);
  CrossfadePhases out;
  out.s1 = profile.fn.evaluate(phi1);
  out.s2 = profile.fn.evaluate(phi2);
  out.w = 1.0 - std::abs(1.0 - 2.0 * static_cast<double>(phi1));
  return out;
}

std::vector<Profile> applyPlayback(std::vector<Profile> profiles, const PlaybackOptions& playback) {
  for (Profile& p : profiles) {
    p.periodS /= std::max(1e-6, playback.speed);
    p.shift += playback.shift;
    if (playback.function && *playback.function != p.fn.type) {
      p.fn.type = *playback.function;
      if (p.fn.type == PositionFunction::Type::Piecewise && p.fn.knots.empty()) {
        p.fn.knots = {{0.0, 0.0}, {0.5, 1.0}, {1.0, 0.0}};
      }
    }
  }
  return profiles;
}

namespace {

struct LayerView {
  const float* jump;
  const float* fold;
};

/** Colour atlas bilinear read at continuous atlas pixel position p (pixel centres at i + ½), 0..255. */
glm::vec4 sampleAtlas(const Image& atlas, glm::vec2 p) {
  const int w = atlas.width();
  const int h = atlas.height();
  const float fx = std::clamp(p.x, 0.5f, static_cast<float>(w) - 0.5f) - 0.5f;
  const float fy = std::clamp(p.y, 0.5f, static_cast<float>(h) - 0.5f) - 0.5f;
  const auto x0 = static_cast<int>(fx); // fx, fy ≥ 0: truncation is floor
  const auto y0 = static_cast<int>(fy);
  const float tx = fx - static_cast<float>(x0);
  const float ty = fy - static_cast<float>(y0);
  const int x1 = std::min(x0 + 1, w - 1);
  const int y1 = std::min(y0 + 1, h - 1);
  const std::uint8_t* d = reinterpret_cast<const std::uint8_t*>(atlas.data());
  const std::uint8_t* r0 = d + static_cast<std::size_t>(y0) * w * 4;
  const std::uint8_t* r1 = d + static_cast<std::size_t>(y1) * w * 4;
  glm::vec4 out;
  for (int c = 0; c < 4; ++c) {
    const float a = r0[x0 * 4 + c];
    const float b = r0[x1 * 4 + c];
    const float e = r1[x0 * 4 + c];
    const float f = r1[x1 * 4 + c];
    const float top = a + (b - a) * tx;
    const float bottom = e + (f - e) * tx;
    out[c] = top + (bottom - top) * ty;
  }
  return out;
}

bool inInterval(float s, float t0, float t1) {
  return t0 < s && s <= t1;
}

/** Read point for progress s: (x0, y0) + ½ + Σ_k a_k s_k J_k (atlas pixels). */
glm::vec2 readPoint(const float* init, const std::vector<LayerView>& layers, const std::vector<float>& breaks,
                    std::size_t index, float s) {
  glm::vec2 p(init[0] + 0.5f, init[1] + 0.5f);
  const std::size_t k = layers.size();
  for (std::size_t l = 0; l < k; ++l) {
    const float* j = layers[l].jump + index * 4;
    const float sl = k == 1 ? s : std::clamp((s - breaks[l]) / (breaks[l + 1] - breaks[l]), 0.0f, 1.0f);
    bool a = inInterval(sl, j[2], j[3]);
    if (layers[l].fold) {
      const float* f = layers[l].fold + index * 4;
      a = a || inInterval(sl, f[0], f[1]) || inInterval(sl, f[2], f[3]);
    }
    if (a) {
      p += sl * glm::vec2(j[0], j[1]);
    }
  }
  return p;
}

} // namespace

Image renderFrame(const Textures& textures, const std::vector<Profile>& profiles,
                  const std::vector<double>& jumpLayers, double t, unsigned threads) {
  const int w = textures.width();
  const int h = textures.height();
  Image out(w, h, 4, PixelType::U8);
  const Image& atlas = textures.atlas.color;
  const float* init = textures.init.values<float>().data();
  std::vector<LayerView> layers;
  for (std::size_t l = 0; l < textures.jump.size(); ++l) {
    layers.push_back(
        {textures.jump[l].values<float>().data(), l < textures.fold.size() && !textures.fold[l].empty()
                                                      ? textures.fold[l].values<float>().data()
                                                      : nullptr});
  }
  std::vector<float> breaks(jumpLayers.begin(), jumpLayers.end());
  std::vector<float> bases(profiles.size());
  for (std::size_t k = 0; k < profiles.size(); ++k) {
    bases[k] = static_cast<float>(basePhase(profiles[k], t));
  }
  std::uint8_t* dst = reinterpret_cast<std::uint8_t*>(out.data());
  const std::uint8_t* src = reinterpret_cast<const std::uint8_t*>(atlas.data());
  const bool simple = layers.size() == 1 && layers[0].fold == nullptr;
  auto rows = [&](std::size_t begin, std::size_t end) {
    // Progress depends only on (profile, dt), which is constant over most zones: evaluate the position
    // function once per run of equal (profile, dt) instead of per texel. Same values, far fewer calls.
    int lastK = -1;
    float lastDt = -1.0f;
    float s = 0.0f;
    float s2 = 0.0f;
    float wgt = 1.0f;
    bool crossfade = false;
    for (std::size_t y = begin; y < end; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = y * static_cast<std::size_t>(w) + x;
        const float* in = init + i * 4;
        std::uint8_t* o = dst + i * 4;
        const int k = static_cast<int>(in[3]);
        if (in[3] < 0.0f || k >= static_cast<int>(profiles.size())) {
          std::copy_n(src + i * 4, 4, o);
          continue;
        }
        if (k != lastK || in[2] != lastDt) {
          const Profile& profile = profiles[static_cast<std::size_t>(k)];
          crossfade = profile.loop == LoopMode::Crossfade;
          if (crossfade) {
            const float phi1 = fractf(bases[k] + in[2]);
            const float phi2 = fractf(phi1 + 0.5f);
            s = static_cast<float>(profile.fn.evaluate(phi1));
            s2 = static_cast<float>(profile.fn.evaluate(phi2));
            wgt = 1.0f - std::abs(1.0f - 2.0f * phi1);
          } else {
            s = static_cast<float>(profile.fn.evaluate(texelPhase(profile, bases[k], in[2])));
          }
          lastK = k;
          lastDt = in[2];
        }
        glm::vec4 c;
        if (crossfade) {
          c = glm::mix(sampleAtlas(atlas, readPoint(in, layers, breaks, i, s2)),
                       sampleAtlas(atlas, readPoint(in, layers, breaks, i, s)), wgt);
        } else if (simple) {
          const float* j = layers[0].jump + i * 4;
          glm::vec2 p(in[0] + 0.5f, in[1] + 0.5f);
          if (inInterval(s, j[2], j[3])) {
            p += s * glm::vec2(j[0], j[1]);
          }
          c = sampleAtlas(atlas, p);
        } else {
          c = sampleAtlas(atlas, readPoint(in, layers, breaks, i, s));
        }
        for (int ch = 0; ch < 4; ++ch) {
          // c ∈ [0, 255] (a convex mix of bytes): truncating c + ½ rounds half up, like floor(c + ½).
          o[ch] = static_cast<std::uint8_t>(std::min(c[ch] + 0.5f, 255.0f));
        }
      }
    }
  };
  if (threads > 1) {
    parallelFor(static_cast<std::size_t>(h), rows, 8);
  } else {
    rows(0, static_cast<std::size_t>(h));
  }
  return out;
}

Image cropToEntry(const Image& frame, const AtlasEntry& entry) {
  const Rect r = entry.atlasRect();
  Image out(r.width(), r.height(), frame.channels(), frame.type());
  const std::size_t pixelBytes = static_cast<std::size_t>(frame.channels()) * bytesPerChannel(frame.type());
  for (int y = 0; y < r.height(); ++y) {
    std::copy_n(frame.data() + (static_cast<std::size_t>(r.min.y + y) * frame.width() + r.min.x) * pixelBytes,
                static_cast<std::size_t>(r.width()) * pixelBytes, out.data() + y * out.rowBytes());
  }
  return out;
}

double longestPeriod(const std::vector<Profile>& profiles) {
  double longest = 0.0;
  for (const Profile& p : profiles) {
    longest = std::max(longest, p.periodS);
  }
  return longest > 0.0 ? longest : 1.0;
}

LoopPeriod loopPeriod(const std::vector<Profile>& profiles) {
  const double longest = longestPeriod(profiles);
  for (int k = 1; k <= kMaxLoopCycles && (k == 1 || k * longest <= kMaxLoopS * (1.0 + 1e-9)); ++k) {
    const double t = k * longest;
    const bool whole = std::all_of(profiles.begin(), profiles.end(), [&](const Profile& p) {
      const double cycles = t / p.periodS;
      return std::abs(cycles - std::round(cycles)) <= 1e-6 * std::max(1.0, cycles);
    });
    if (whole) {
      return {t, true};
    }
  }
  return {longest, false};
}

std::vector<Image> renderFrames(int count, const std::string& label, const std::function<Image(int)>& frame) {
  std::vector<Image> frames;
  frames.reserve(static_cast<std::size_t>(std::max(count, 0)));
  Progress progress("rendering frames", static_cast<std::size_t>(std::max(count, 1)));
  for (int i = 0; i < count; ++i) {
    if (progress.cancelled()) {
      fail("{}: rendering cancelled", label);
    }
    frames.push_back(frame(i));
    progress.advance();
  }
  if (progress.cancelled()) {
    fail("{}: rendering cancelled", label);
  }
  return frames;
}

} // namespace sylva::folding

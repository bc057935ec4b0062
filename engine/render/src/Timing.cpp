#include <sylva/render/Timing.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

Stats Stats::of(std::vector<double> samples) {
  Stats s;
  s.count = samples.size();
  if (samples.empty()) {
    return s;
  }
  std::sort(samples.begin(), samples.end());
  auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(samples.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const auto hi = std::min(lo + 1, samples.size() - 1);
    return samples[lo] + (samples[hi] - samples[lo]) * (pos - static_cast<double>(lo));
  };
  s.median = quantile(0.5);
  s.p10 = quantile(0.1);
  s.p90 = quantile(0.9);
  s.min = samples.front();
  s.max = samples.back();
  return s;
}

nlohmann::json Stats::toJson() const {
  return {{"median", median}, {"min", min}, {"max", max}, {"p10", p10}, {"p90", p90}, {"count", count}};
}

FrameClock::FrameClock(double fixedStep) : mFixedStep(fixedStep) {}

double FrameClock::tick() {
  if (mFixedStep > 0.0) {
    mTime += mFixedStep;
    return mFixedStep;
  }
  const auto now = std::chrono::steady_clock::now();
  double dt = 0.0;
  if (mStarted) {
    dt = std::chrono::duration<double>(now - mLast).count();
  }
  mStarted = true;
  mLast = now;
  mTime += dt;
  return dt;
}

} // namespace sylva::render

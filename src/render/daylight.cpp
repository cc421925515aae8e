#include "render/daylight.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace render {

namespace {

float smooth(float lo, float hi, float x) {
    const float t = glm::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Exactly a at t = 0 and exactly b at t = 1 (noon's colours are the constants below, bit for bit).
glm::vec3 mix3(const glm::vec3& a, const glm::vec3& b, float t) { return a * (1.0f - t) + b * t; }

// Colours of the sky at noon, at sunset and at midnight.
constexpr glm::vec3 kDayFog{0.62f, 0.76f, 0.93f}, kDuskFog{0.86f, 0.52f, 0.36f}, kNightFog{0.025f, 0.03f, 0.06f};
constexpr glm::vec3 kDayZenith{0.30f, 0.50f, 0.85f}, kNightZenith{0.006f, 0.01f, 0.03f};
constexpr glm::vec3 kNightSky{0.11f, 0.13f, 0.22f}; // moonlit: about a sixth of noon's sky light, bluish
constexpr glm::vec3 kDuskSun{1.0f, 0.55f, 0.3f}, kMoonLight{0.10f, 0.12f, 0.18f};

} // namespace

Daylight daylightAt(double hours) {
    Daylight d;
    // The sun's path: a circle through kNoonSun and a horizontal east, turning a full turn a day.
    const glm::dvec3 noon = glm::normalize(glm::dvec3(kNoonSun));
    const glm::dvec3 east = glm::normalize(glm::dvec3(noon.z, 0.0, -noon.x));
    const double angle = (hours - 6.0) / 24.0 * 2.0 * 3.14159265358979323846;
    const glm::dvec3 sun = std::cos(angle) * east + std::sin(angle) * noon;
    d.sunDirection = glm::normalize(glm::vec3(sun));
    d.moonDirection = -d.sunDirection;
    const float height = d.sunDirection.y; // sine of the sun's elevation
    // Day: 1 from a little above the horizon, 0 a little below it; the shading light swaps to the moon in
    // between, while both are dark.
    const float day = smooth(-0.25f, 0.4f, height);
    const float low = 1.0f - smooth(0.0f, 0.4f, std::abs(height)); // 1 at the horizon: the colours of dusk
    const bool sunUp = height > 0.0f;
    d.lightDirection = sunUp ? d.sunDirection : d.moonDirection;
    d.lightColour = sunUp ? mix3(glm::vec3(1.0f), kDuskSun, low) * smooth(0.0f, 0.12f, height)
                          : kMoonLight * smooth(0.0f, 0.12f, -height);
    d.skyColour = mix3(kNightSky, glm::vec3(1.0f), day);
    // Dusk's warm horizon while the sun is near it, fading out as it sinks below.
    d.fogColour = mix3(mix3(kNightFog, kDayFog, day), kDuskFog, 0.75f * low * smooth(-0.15f, 0.05f, height));
    d.zenithColour = mix3(kNightZenith, kDayZenith, day);
    d.stars = 1.0f - smooth(-0.2f, 0.02f, height);
    d.sunDisc = smooth(-0.05f, 0.02f, height);
    d.moonDisc = smooth(-0.05f, 0.02f, -height);
    return d;
}

float skyBrightness(const Daylight& d) { return (d.skyColour.r + d.skyColour.g + d.skyColour.b) / 3.0f; }

float levelBrightness(int level) { return std::pow(0.82f, static_cast<float>(15 - std::clamp(level, 0, 15))); }

glm::vec3 lampLight(glm::ivec3 colour) {
    const auto channel = [](int level) { return level > 0 ? levelBrightness(level) : 0.0f; };
    return glm::vec3(channel(colour.r), channel(colour.g), channel(colour.b)) * kLampColour;
}

glm::vec3 localTint(const Daylight& d, int sun, glm::ivec3 colour) {
    return glm::max(glm::vec3(skyBrightness(d) * levelBrightness(sun)), lampLight(colour));
}

} // namespace render

#include "game/day_clock.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/quote.h"

namespace game {

void advance(DayClock& clock, double dt) {
    if (clock.stopped) return;
    clock.hours += dt * kHoursPerDay / (clock.dayMinutes * 60.0);
    // At most one wrap a tick for any day the settings allow; fmod keeps a hand-made state in range too.
    if (clock.hours >= kHoursPerDay) clock.hours = std::fmod(clock.hours, kHoursPerDay);
}

double parseHours(std::string_view text) {
    double hours = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), hours);
    if (ec != std::errc{} || end != text.data() + text.size() || !(hours >= 0.0 && hours <= kHoursPerDay))
        throw std::invalid_argument(core::quoteForMessage(text) +
                                    " is not an hour from 0 to 24 (12 is noon, 0 and 24 midnight)");
    return hours == kHoursPerDay ? 0.0 : hours;
}

std::string checkDayClock(const DayClock& clock) {
    if (!isClockHour(clock.hours)) return "time_of_day = " + exactHours(clock.hours) + " is outside [0, 24)";
    if (!(clock.dayMinutes >= kShortestDayMinutes && clock.dayMinutes <= kLongestDayMinutes))
        return "day_length = " + exactHours(clock.dayMinutes) + " is outside 1..1440 minutes";
    return {};
}

std::string exactHours(double hours) { return core::shortestText(hours); }

std::string clockText(double hours) {
    const int minutes = static_cast<int>(std::floor(hours * 60.0)) % (24 * 60);
    char text[8];
    std::snprintf(text, sizeof text, "%02d:%02d", minutes / 60, minutes % 60);
    return text;
}

} // namespace game

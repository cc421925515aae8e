// The time of day: simulation state, advanced by the tick, that the sky, the fog and the light follow
// (render/daylight.h). It is hashed, dumped and saved with the world (game/state_fields.h); its length and
// whether it runs are settings (session/setting_table.h) that the session writes into it.
#pragma once
#include <string>
#include <string_view>

namespace game {

inline constexpr double kHoursPerDay = 24.0;
// A new world's time, and the time a world saved before the clock existed (schema 4 and older) opens at.
inline constexpr double kDefaultHours = 12.0;
inline constexpr double kDefaultDayMinutes = 20.0;
inline constexpr double kShortestDayMinutes = 1.0, kLongestDayMinutes = 1440.0;

struct DayClock {
    double hours = kDefaultHours;           // [0, 24): 0 midnight, 6 sunrise, 12 noon, 18 sunset
    double dayMinutes = kDefaultDayMinutes; // real minutes a whole day takes at the tick's own pace
    bool stopped = false;                   // the sun stands still
};

// An hour the clock can read: 0 <= hours < 24 (NaN is not).
inline bool isClockHour(double hours) { return hours >= 0.0 && hours < kHoursPerDay; }
// Moves the clock on by dt seconds of game time (nothing while stopped), wrapping at 24.
void advance(DayClock& clock, double dt);
// The hour as --time-of-day and the script's `time` take it: a number from 0 to 24, where 24 is the
// midnight that 0 also is (the clock reads 0). Throws std::invalid_argument naming the text otherwise.
double parseHours(std::string_view text);
// Empty when the clock is one the game can reach; else what is wrong (checkInvariants, the world loader).
std::string checkDayClock(const DayClock& clock);
// The shortest text that parseHours reads back as exactly this hour (a recording's `time` line).
std::string exactHours(double hours);
// "HH:MM" for people (the world panel, the overlay).
std::string clockText(double hours);

} // namespace game

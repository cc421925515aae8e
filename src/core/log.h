// Minimal leveled logging to stderr. No global state beyond the threshold; never throws.
#pragma once
#include <string_view>

namespace core {

enum class LogLevel { Debug, Info, Warn, Error };

void setLogLevel(LogLevel level);
void log(LogLevel level, std::string_view message);
inline void logInfo(std::string_view m) { log(LogLevel::Info, m); }
inline void logWarn(std::string_view m) { log(LogLevel::Warn, m); }
inline void logError(std::string_view m) { log(LogLevel::Error, m); }

} // namespace core

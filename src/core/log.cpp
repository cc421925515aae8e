#include "core/log.h"

#include <atomic>
#include <cstdio>

namespace core {

namespace {
std::atomic<LogLevel> g_level{LogLevel::Info};
constexpr const char* kPrefix[] = {"debug", "info", "warning", "error"};
} // namespace

void setLogLevel(LogLevel level) { g_level = level; }

void log(LogLevel level, std::string_view message) {
    if (level < g_level.load()) return;
    std::fprintf(stderr, "minecrappy: %s: %.*s\n", kPrefix[static_cast<int>(level)], static_cast<int>(message.size()),
                 message.data());
}

} // namespace core

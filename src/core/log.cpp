#include "core/log.h"

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace core {

namespace {

std::atomic<const char*> g_program{"minecrappy"};

void writeLine(const char* kind, const char* format, va_list args) {
    va_list copy;
    va_copy(copy, args);
    const int n = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    std::string line = g_program.load();
    line += ": ";
    line += kind;
    if (n > 0) {
        const std::size_t head = line.size();
        line.resize(head + static_cast<std::size_t>(n) + 1);
        std::vsnprintf(line.data() + head, static_cast<std::size_t>(n) + 1, format, args);
        line.resize(head + static_cast<std::size_t>(n));
    }
    line += '\n';
    std::fwrite(line.data(), 1, line.size(), stderr); // one write: lines of two threads never interleave
}

} // namespace

void logError(const char* format, ...) {
    va_list args;
    va_start(args, format);
    writeLine("", format, args);
    va_end(args);
}

void logWarn(const char* format, ...) {
    va_list args;
    va_start(args, format);
    writeLine("warning: ", format, args);
    va_end(args);
}

void logNote(const char* format, ...) {
    va_list args;
    va_start(args, format);
    writeLine("", format, args);
    va_end(args);
}

void setLogProgram(const char* name) { g_program = name; }

std::string errorLine(const std::string& message) {
    std::string line = g_program.load();
    line += ": ";
    line += message;
    return line;
}

} // namespace core

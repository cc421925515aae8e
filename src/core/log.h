// The one way the programs report to the person running them: a line on stderr that starts with the
// program's name, so that it can be told apart from its results on stdout (paths written, reports) and
// from the shell's own messages. Thread-safe (one write per line); never throws.
//   logError: something failed ("minecrappy: save failed: ...").
//   logWarn:  it went on, but the user should know ("minecrappy: warning: ...").
//   logNote:  a plain note of what happened ("minecrappy: saved ...").
#pragma once
#include <string>

namespace core {

#if defined(__GNUC__)
#define MC_PRINTF_LIKE __attribute__((format(printf, 1, 2)))
#else
#define MC_PRINTF_LIKE
#endif

void logError(const char* format, ...) MC_PRINTF_LIKE;
void logWarn(const char* format, ...) MC_PRINTF_LIKE;
void logNote(const char* format, ...) MC_PRINTF_LIKE;

// The name every line starts with; "minecrappy" unless a program sets its own at start.
void setLogProgram(const char* name);
// The line logError would print for `message`, without the newline: for messages a caller returns rather
// than prints (the command-line parser's).
std::string errorLine(const std::string& message);

#undef MC_PRINTF_LIKE

} // namespace core

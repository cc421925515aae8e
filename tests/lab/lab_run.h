// Runs minecrappy-lab in-process, the way a shell would: argv[0] plus the given arguments, with its
// exit code and both output streams captured; and the other small helpers the lab's tests share (a text's lines,
// a docs page's block between two markers, and the check that a docs page quotes the lab exactly).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "lab/lab_cli.h"

namespace lab_test {

struct LabRun {
    int code = -1;
    std::string out, err;
};

inline LabRun runLab(std::vector<std::string> args, std::string_view version = {}) {
    args.insert(args.begin(), "minecrappy-lab");
    std::vector<const char*> argv;
    argv.reserve(args.size());
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    LabRun r;
    r.code = lab::runLab(static_cast<int>(argv.size()), argv.data(), out, err, version);
    r.out = out.str();
    r.err = err.str();
    return r;
}

inline std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

// The text of docs/FILE between "<!-- NAME:begin -->\n" and "<!-- NAME:end -->"; empty with `why` set when the
// file or a marker is missing.
inline std::string docsBlock(const std::string& file, const std::string& name, std::string& why) {
    std::ifstream in(std::string(MC_TEST_DATA) + "/../docs/" + file);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string s = text.str(), begin = "<!-- " + name + ":begin -->\n", end = "<!-- " + name + ":end -->";
    const auto a = s.find(begin), b = s.find(end);
    if (s.empty()) {
        why = "docs/" + file + " not found beside tests/";
    } else if (a == std::string::npos || b == std::string::npos || b < a) {
        why = "docs/" + file + " lacks the " + name + " markers, or they are out of order";
    } else {
        return s.substr(a + begin.size(), b - a - begin.size());
    }
    return {};
}

// The docs test: expects docs/FILE's block NAME to be exactly what `make` returns, after asserting that the block is
// there and that the made text holds each of `rows` (the table rows the prose relies on); `mismatch` is the message
// when they differ.
inline void expectDocsQuote(const std::string& file, const std::string& name, const std::function<std::string()>& make,
                            std::initializer_list<const char*> rows, const std::string& mismatch) {
    std::string why;
    const std::string quoted = docsBlock(file, name, why);
    ASSERT_TRUE(why.empty()) << why;
    const std::string made = make();
    for (const char* row : rows) ASSERT_NE(made.find(row), std::string::npos) << row;
    EXPECT_EQ(quoted, made) << mismatch;
}

} // namespace lab_test

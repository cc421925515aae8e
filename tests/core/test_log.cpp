// The one logging path: one line on stderr per message, named after the program.
#include <gtest/gtest.h>

#include <string>

#include "core/log.h"

namespace {

TEST(Log, EachKindIsOneLineStartingWithTheProgramsName) {
    testing::internal::CaptureStderr();
    core::logError("save failed: %s", "disk full");
    core::logWarn("%d event%s will not run", 2, "s");
    core::logNote("saved %s", "/w/a.mcworld");
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "minecrappy: save failed: disk full\n"
                                                      "minecrappy: warning: 2 events will not run\n"
                                                      "minecrappy: saved /w/a.mcworld\n");
}

TEST(Log, AnotherProgramNamesItselfAndReturnedLinesMatchPrintedOnes) {
    core::setLogProgram("minecrappy-atlas");
    testing::internal::CaptureStderr();
    core::logError("failed to write '%s'", "x.png");
    const std::string printed = testing::internal::GetCapturedStderr();
    const std::string returned = core::errorLine("failed to write 'x.png'");
    core::setLogProgram("minecrappy");
    EXPECT_EQ(printed, "minecrappy-atlas: failed to write 'x.png'\n");
    EXPECT_EQ(returned + "\n", printed);
}

TEST(Log, ALongMessageIsNotCut) {
    const std::string longText(5000, 'x');
    testing::internal::CaptureStderr();
    core::logError("%s", longText.c_str());
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "minecrappy: " + longText + "\n");
}

} // namespace

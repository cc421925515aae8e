// core::AtomicFile and core::writeFileAtomically: a user's file is replaced whole or left as it was, and no
// temporary file is ever left behind, whichever way the write ends.
#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("mc_atomic_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

int entries(const fs::path& dir) {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
}

TEST(AtomicFile, CommitReplacesTheFileWholeAndLeavesNothingElse) {
    const fs::path dir = freshDir("commit"), target = dir / "out.txt";
    std::ofstream(target) << "old contents";
    {
        core::AtomicFile f(target);
        f.stream() << "new";
        ASSERT_EQ(read(target), "old contents") << "replaced before the commit";
        f.commit();
    }
    EXPECT_EQ(read(target), "new");
    EXPECT_EQ(entries(dir), 1) << "a temporary file was left behind";
}

TEST(AtomicFile, AWriterDestroyedWithoutCommitLeavesTheFileAsItWas) {
    const fs::path dir = freshDir("abandon"), target = dir / "out.txt";
    std::ofstream(target) << "old contents";
    {
        core::AtomicFile f(target);
        f.stream() << "half of something";
        ASSERT_EQ(entries(dir), 2); // precondition: the temporary file exists while writing
    }
    EXPECT_EQ(read(target), "old contents");
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, AFolderThatDoesNotExistIsNamedInTheError) {
    const fs::path target = freshDir("missing") / "no" / "such" / "out.txt";
    try {
        core::AtomicFile f(target);
        FAIL() << "opened a file in a folder that does not exist";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
}

TEST(WriteFileAtomically, AFailedOrThrowingWriterLeavesTheFileAsItWasAndNoTemporary) {
    const fs::path dir = freshDir("callback"), target = dir / "image.png";
    std::ofstream(target) << "old picture";
    // The writer reports failure after writing half a file.
    try {
        core::writeFileAtomically(target, [](const fs::path& temp) {
            std::ofstream(temp) << "half";
            return false;
        });
        FAIL() << "a failed write did not throw";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(read(target), "old picture");
    EXPECT_EQ(entries(dir), 1);
    // The writer throws: its exception comes through, and the temporary file goes.
    EXPECT_THROW(core::writeFileAtomically(target,
                                           [](const fs::path& temp) -> bool {
                                               std::ofstream(temp) << "half";
                                               throw std::logic_error("encoder broke");
                                           }),
                 std::logic_error);
    EXPECT_EQ(read(target), "old picture");
    EXPECT_EQ(entries(dir), 1);
    // And a good one replaces the file.
    core::writeFileAtomically(target,
                              [](const fs::path& temp) { return static_cast<bool>(std::ofstream(temp) << "new"); });
    EXPECT_EQ(read(target), "new");
    EXPECT_EQ(entries(dir), 1);
}

} // namespace

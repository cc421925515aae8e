// core::writeOutput and core::AtomicFile: the one rule for every output file (core/atomic_file.h). A regular
// file is replaced whole or left as it was, with no temporary left behind, whichever system call fails; a
// symlink is followed and kept; a FIFO or a character device is written in place; anything else is refused.
#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "../temp_dir.h"

namespace {

namespace fs = std::filesystem;
using core::WriteFault;

fs::path freshDir(const std::string& name) {
    return test_util::freshTempDir("mc_atomic_" + name + "_" + std::to_string(::getpid()));
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

// Expects the file at `p` (links followed) to hold exactly `bytes` and to have exactly the permission bits `mode`.
void expectFile(const fs::path& p, const std::string& bytes, mode_t mode) {
    EXPECT_EQ(read(p), bytes);
    struct stat st {};
    ASSERT_EQ(::stat(p.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, mode);
}

// The message of the OutputError writeOutput throws, or "written".
std::string attempt(const fs::path& target, const std::string& bytes) {
    try {
        core::writeOutput(target, bytes);
    } catch (const core::OutputError& e) {
        return e.what();
    }
    return "written";
}

TEST(WriteOutput, ANewFileGetsTheBytesAndTheUmasksModeAndNothingElseIsLeft) {
    const fs::path dir = freshDir("new"), target = dir / "out.txt";
    const mode_t old = ::umask(022);
    EXPECT_EQ(attempt(target, "hello"), "written");
    ::umask(old);
    expectFile(target, "hello", 0644);
    EXPECT_EQ(entries(dir), 1);
}

// The old file's permission bits carry over; a hard link to the old file keeps the old bytes (documented).
TEST(WriteOutput, AReplacedFileKeepsItsModeAndAHardLinkKeepsTheOldBytes) {
    const fs::path dir = freshDir("replace"), target = dir / "out.txt", link = dir / "link.txt";
    std::ofstream(target) << "old";
    ASSERT_EQ(::chmod(target.c_str(), 0600), 0);
    fs::create_hard_link(target, link);
    EXPECT_EQ(attempt(target, "new"), "written");
    expectFile(target, "new", 0600);
    EXPECT_EQ(read(link), "old");
    EXPECT_EQ(entries(dir), 2);
}

TEST(WriteOutput, ASymlinkIsFollowedAndKept) {
    const fs::path dir = freshDir("symlink"), real = dir / "real.json", link = dir / "l.json";
    std::ofstream(real) << "old";
    fs::create_symlink("real.json", link);
    EXPECT_EQ(attempt(link, "new"), "written");
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(read(real), "new");
    EXPECT_EQ(entries(dir), 2);
    // A link to a file that is not there yet is dangling too: refused, never turned into a file.
    const fs::path ahead = dir / "ahead.json";
    fs::create_symlink("sub/target.json", ahead);
    fs::create_directory(dir / "sub");
    EXPECT_NE(attempt(ahead, "x").find("which does not exist"), std::string::npos)
        << "a link to nothing is refused, not turned into a file";
    EXPECT_TRUE(fs::is_symlink(ahead));
}

TEST(WriteOutput, ADanglingLinkOrALoopIsRefusedAndLeftAsItWas) {
    const fs::path dir = freshDir("dangling"), dangling = dir / "d.json", a = dir / "a", b = dir / "b";
    fs::create_symlink("nowhere.json", dangling);
    EXPECT_NE(attempt(dangling, "x").find("a symbolic link to 'nowhere.json', which does not exist"),
              std::string::npos);
    fs::create_symlink("b", a);
    fs::create_symlink("a", b);
    EXPECT_NE(attempt(a, "x").find("a loop of symbolic links"), std::string::npos) << attempt(a, "x");
    EXPECT_TRUE(fs::is_symlink(dangling) && fs::is_symlink(a) && fs::is_symlink(b));
    EXPECT_EQ(entries(dir), 3);
}

// The folders the callers make (--capture-dir, the lab's --out) are checked by brokenLinkOnPath: a link to nothing
// or a loop, at the path or at any folder above it, is named; a good link and plain missing folders are not. Catches
// a check of the path alone (a dangling link two levels up still failed with "File exists").
TEST(BrokenLinkOnPath, NamesADanglingLinkOrALoopAnywhereOnThePath) {
    const fs::path dir = freshDir("linkpath");
    fs::create_symlink("gone", dir / "d");
    fs::create_symlink("l2", dir / "l1");
    fs::create_symlink("l1", dir / "l2");
    fs::create_directory(dir / "real");
    fs::create_symlink("real", dir / "good");
    const auto quoted = [](const fs::path& p) {
        std::string text(1, '\''); // piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + string
        text += p.string();
        return text += '\'';
    };
    EXPECT_EQ(core::brokenLinkOnPath(dir / "d"),
              quoted(dir / "d") + " is a symbolic link to 'gone', which does not exist");
    EXPECT_EQ(core::brokenLinkOnPath(dir / "d" / "x" / "y"), core::brokenLinkOnPath(dir / "d"));
    EXPECT_EQ(core::brokenLinkOnPath(dir / "l1" / "x"), quoted(dir / "l1") + " is a loop of symbolic links");
    EXPECT_EQ(core::brokenLinkOnPath(dir / "good" / "new" / "deeper"), "");
    EXPECT_EQ(core::brokenLinkOnPath("relative/missing"), "");
    EXPECT_EQ(core::brokenLinkOnPath("/"), "");
}

TEST(WriteOutput, AFifoWithAReaderIsWrittenInPlaceAndOneWithoutIsRefusedAtOnce) {
    const fs::path dir = freshDir("fifo"), fifo = dir / "f.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NE(attempt(fifo, "x").find("a FIFO that no process reads"), std::string::npos);
    // Refused at once: a wait for a reader would never end; 20 s leaves a busy machine room.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20)) << "it waited for a reader";
    // A reader: open for reading first (non-blocking, so this thread goes on), then write.
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    const std::string payload(100000, 'z'); // more than a pipe holds: the writer must wait for the reader
    auto written = std::async(std::launch::async, [&] { return attempt(fifo, payload); });
    std::string got;
    char buf[4096];
    while (got.size() < payload.size()) {
        const ssize_t n = ::read(reader, buf, sizeof buf);
        if (n > 0) got.append(buf, static_cast<std::size_t>(n));
        if (n < 0 && errno != EAGAIN) break;
        if (n <= 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(written.get(), "written");
    ::close(reader);
    EXPECT_EQ(got, payload);
    struct stat st {};
    ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
}

TEST(WriteOutput, ACharacterDeviceIsWrittenInPlaceAndItsErrorReported) {
    EXPECT_EQ(attempt("/dev/null", "anything"), "written");
    struct stat st {};
    ASSERT_EQ(::stat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
    ASSERT_EQ(::stat("/dev/full", &st), 0) << "this test expects /dev/full";
    EXPECT_NE(attempt("/dev/full", "x").find(std::strerror(ENOSPC)), std::string::npos) << attempt("/dev/full", "x");
    ASSERT_EQ(::stat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
}

TEST(WriteOutput, AFolderASocketAndAMissingFolderAreRefused) {
    const fs::path dir = freshDir("refused");
    EXPECT_NE(attempt(dir, "x").find("it is a folder"), std::string::npos);
    const fs::path sock = dir / "s.sock";
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(fd, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, sock.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
    EXPECT_NE(attempt(sock, "x").find("it is a socket"), std::string::npos);
    ::close(fd);
    EXPECT_NE(attempt(dir / "no" / "x.json", "x").find("the folder '" + (dir / "no").string() + "' does not exist"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "no")) << "a folder was made";
}

// A fault at each system call, with a disk that fills at the start, the middle and the last byte: the
// error names the path and the system's reason, no temporary is left, and the old bytes survive.
TEST(WriteOutput, AFailureAtAnyPointLeavesTheOldFileAndNoTemporary) {
    const fs::path dir = freshDir("faults"), target = dir / "out.json";
    const std::string bytes(10000, 'n');
    const WriteFault faults[] = {
        {WriteFault::Point::Open, EACCES, 0},     {WriteFault::Point::Write, ENOSPC, 0},
        {WriteFault::Point::Write, ENOSPC, 5000}, {WriteFault::Point::Write, EDQUOT, bytes.size() - 1},
        {WriteFault::Point::Fsync, EIO, 0},       {WriteFault::Point::Close, EIO, 0},
        {WriteFault::Point::Rename, EXDEV, 0},
    };
    for (const WriteFault& f : faults) {
        std::ofstream(target) << "previous";
        core::setWriteFault(f);
        const std::string message = attempt(target, bytes);
        core::clearWriteFault();
        const std::string label = std::to_string(static_cast<int>(f.point)) + "/" + std::to_string(f.afterBytes);
        EXPECT_NE(message.find("cannot write '" + target.string() + "'"), std::string::npos) << label << message;
        EXPECT_NE(message.find(std::strerror(f.error)), std::string::npos) << label << ": " << message;
        EXPECT_EQ(read(target), "previous") << label;
        EXPECT_EQ(entries(dir), 1) << label << ": a temporary file was left";
    }
    // After the rename only the folder's sync can fail: reported, and the new file is whole.
    core::setWriteFault({WriteFault::Point::FolderFsync, EIO, 0});
    const std::string message = attempt(target, bytes);
    core::clearWriteFault();
    EXPECT_NE(message.find("the new file is in place"), std::string::npos) << message;
    EXPECT_EQ(read(target), bytes);
    // Without a fault the same write succeeds: the faults above were the only cause.
    EXPECT_EQ(attempt(target, "fine"), "written");
    EXPECT_EQ(read(target), "fine");
}

// A device written in place reports a failed write too, and keeps what it is.
TEST(WriteOutput, AFailedWriteToAFifoIsReported) {
    const fs::path dir = freshDir("fifofault"), fifo = dir / "f";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    core::setWriteFault({WriteFault::Point::Write, EIO, 3});
    const std::string message = attempt(fifo, "abcdef");
    core::clearWriteFault();
    ::close(reader);
    EXPECT_NE(message.find(std::strerror(EIO)), std::string::npos) << message;
}

TEST(AtomicFile, NothingReachesTheDiskBeforeCommit) {
    const fs::path dir = freshDir("commit"), target = dir / "out.txt";
    std::ofstream(target) << "old contents";
    {
        core::AtomicFile f(target);
        f.stream() << "half of something";
        EXPECT_EQ(entries(dir), 1);
    } // destroyed without commit
    EXPECT_EQ(read(target), "old contents");
    {
        core::AtomicFile f(target);
        f.stream() << "new";
        f.commit();
    }
    EXPECT_EQ(read(target), "new");
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, ARefusedPathFailsAtConstructionNamingIt) {
    const fs::path target = freshDir("missing") / "no" / "such" / "out.txt";
    try {
        core::AtomicFile f(target);
        FAIL() << "accepted a file in a folder that does not exist";
    } catch (const core::OutputError& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
}

} // namespace

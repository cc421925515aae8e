// The one writer of every output file the game and the lab make (settings, state dumps, screenshots, capture
// frames, recordings, frame stats, soak reports, lab CSV/SVG/MD), with one rule for what is at the path
// (docs/SCRIPTS.md, "Output files"):
//
// - nothing there: a new file, mode 0666 & ~umask. Its folder must exist (OutputError naming it
//   otherwise); the callers create only folders the user names as folders (--capture-dir, the lab's --out).
// - a regular file: replaced whole or left as it was. The bytes go to a temporary file beside it (created
//   with O_CREAT|O_EXCL|O_NOFOLLOW), are written with a loop that survives short writes and EINTR, fsync'd
//   and closed (both checked), then renamed over it and the folder fsync'd. The new file takes the old one's
//   permission bits; other hard links to the old file keep the old bytes.
// - a symbolic link: followed, and the file it leads to is replaced by the rule for what is there; the link
//   stays. A link to nothing, or a loop of links, is refused.
// - a FIFO or a character device (/dev/stdout, /dev/null): written in place, never replaced. It is opened
//   with O_NONBLOCK, so a FIFO that no process reads is refused at once instead of hanging.
// - a folder, a socket or a block device: refused.
//
// Every failure (no space, quota, an I/O error, at the open, any write, the fsync, the close or the rename)
// throws OutputError "cannot write 'PATH': what failed: the system's reason", removes the temporary
// file, and leaves the previous file as it was. The bytes are gathered in memory first, so an encoder's
// own errors (a PNG encoder ignoring fwrite's) cannot leave a short file.
//
// Worlds are SQLite databases written in place through their journal (save/world_save.cpp), not here.
#pragma once
#include <cstddef>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace core {

// A refused output path or a failed write; the game and the lab exit with 2 on it, naming the path.
class OutputError : public std::runtime_error {
    using runtime_error::runtime_error;
};

// What an output path leads to and how it will be written; resolveOutput throws OutputError naming
// the path for the cases the rule refuses (a missing or non-folder parent, a dangling link, a loop of links,
// a folder, a socket, a block device).
struct OutputPath {
    enum class Kind { NewFile, ReplaceFile, InPlace };
    Kind kind = Kind::NewFile;
    std::filesystem::path resolved; // the path after symbolic links
};
OutputPath resolveOutput(const std::filesystem::path& target);

// A symbolic link on the way to `path` (the path itself or a folder above it) that leads nowhere or into a loop,
// described ("'LINK' is a symbolic link to 'TARGET', which does not exist"); "" when there is none. For the
// folders the callers create (--capture-dir, --screenshot-dir, the lab's --out): creating one through such a
// link fails with a bare "File exists".
std::string brokenLinkOnPath(const std::filesystem::path& path);

// Writes `bytes` to `target` by the rule above.
void writeOutput(const std::filesystem::path& target, std::string_view bytes);

// A text or binary output built in a stream and written by writeOutput at commit(). The constructor checks
// the path by the rule (resolveOutput), so a refused path fails before any work; nothing reaches the file
// system before commit(), so a writer destroyed without one leaves nothing behind.
class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path target);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return m_out; }
    const std::filesystem::path& target() const { return m_target; }
    void commit(); // writeOutput; throws as it does

private:
    std::filesystem::path m_target;
    std::ostringstream m_out;
};

// For tests: the writer's system calls fail as told. `point` names the call; `error` is the errno it fails
// with; for Write, the first `afterBytes` bytes are written before the failure (a disk that fills midway).
// One fault at a time, for the calling thread; clearWriteFault() ends it.
struct WriteFault {
    enum class Point { None, Open, Write, Fsync, Close, Rename, FolderFsync };
    Point point = Point::None;
    int error = 0;
    std::size_t afterBytes = 0;
};
void setWriteFault(const WriteFault& fault);
void clearWriteFault();

} // namespace core

#include "core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace core {

namespace {

thread_local WriteFault t_fault;

// The fault for this call, if one is set for it: errno is set and true returned.
bool faulted(WriteFault::Point point) {
    if (t_fault.point != point) return false;
    errno = t_fault.error;
    return true;
}

[[noreturn]] void fail(const std::filesystem::path& target, const std::string& what, int error) {
    throw OutputError("cannot write '" + target.string() + "': " + what + ": " + std::strerror(error));
}
[[noreturn]] void refuse(const std::filesystem::path& target, const std::string& why) {
    throw OutputError("cannot write '" + target.string() + "': " + why);
}

std::string uniqueSuffix() {
    // Two writers in one process (or two processes) aiming at the same folder must not share a name.
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    return std::to_string(rd()) + "-" + std::to_string(counter.fetch_add(1));
}

// All of `bytes` to fd, through short writes and EINTR; false with errno set on a failure.
bool writeAll(int fd, std::string_view bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        std::size_t chunk = bytes.size() - done;
        bool failNow = false;
        if (t_fault.point == WriteFault::Point::Write) {
            if (done >= t_fault.afterBytes) {
                failNow = true;
            } else {
                chunk = std::min(chunk, t_fault.afterBytes - done);
            }
        }
        if (failNow) {
            errno = t_fault.error;
            return false;
        }
        const ssize_t n = ::write(fd, bytes.data() + done, chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    return true;
}

const char* typeName(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISBLK(mode)) return "a block device";
    return "not a file";
}

void writeInPlace(const std::filesystem::path& target, const std::filesystem::path& resolved, std::string_view bytes) {
    int fd =
        faulted(WriteFault::Point::Open) ? -1 : ::open(resolved.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        if (errno == ENXIO) refuse(target, "it is a FIFO that no process reads");
        fail(target, "opening it", errno);
    }
    // Blocking from here: a reader that is slower than us is waited for, as a pipe's writer should.
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    if (!writeAll(fd, bytes)) {
        const int error = errno;
        ::close(fd);
        fail(target, "writing", error);
    }
    if (faulted(WriteFault::Point::Close) || ::close(fd) != 0) fail(target, "closing", errno);
}

void replaceFile(const std::filesystem::path& target, const std::filesystem::path& resolved, std::string_view bytes,
                 const struct stat* old) {
    std::filesystem::path temp = resolved;
    std::string tempName = ".";
    tempName += resolved.filename().string();
    tempName += ".tmp-";
    tempName += uniqueSuffix();
    temp.replace_filename(tempName);
    const int fd = faulted(WriteFault::Point::Open)
                       ? -1
                       : ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) fail(target, "creating a file in '" + resolved.parent_path().string() + "'", errno);
    const auto abandon = [&](const std::string& what, int error, bool open) {
        if (open) ::close(fd);
        ::unlink(temp.c_str());
        fail(target, what, error);
    };
    if (old && ::fchmod(fd, old->st_mode & 07777) != 0) abandon("keeping its permissions", errno, true);
    if (!writeAll(fd, bytes)) abandon("writing", errno, true);
    if (faulted(WriteFault::Point::Fsync) || ::fsync(fd) != 0) abandon("flushing it to disk", errno, true);
    if (faulted(WriteFault::Point::Close) || ::close(fd) != 0) abandon("closing", errno, false);
    if (faulted(WriteFault::Point::Rename) || ::rename(temp.c_str(), resolved.c_str()) != 0)
        abandon("renaming it into place", errno, false);
    // The rename is durable once the folder is: a crash now keeps either file whole, never neither.
    const std::filesystem::path folder = resolved.has_parent_path() ? resolved.parent_path() : ".";
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        const bool synced = !faulted(WriteFault::Point::FolderFsync) && ::fsync(dir) == 0;
        const int error = errno;
        ::close(dir);
        // EINVAL: a file system that cannot sync folders; the file is in place whole either way.
        if (!synced && error != EINVAL) fail(target, "flushing its folder to disk (the new file is in place)", error);
    }
}

} // namespace

OutputPath resolveOutput(const std::filesystem::path& target) {
    if (target.empty() || target.filename().empty()) refuse(target, "not a file name");
    OutputPath out;
    out.resolved = target;
    struct stat st {};
    if (::lstat(target.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        char* real = ::realpath(target.c_str(), nullptr);
        if (!real) {
            if (errno == ELOOP) refuse(target, "a loop of symbolic links");
            if (errno == ENOENT) {
                std::error_code ec;
                refuse(target, "a symbolic link to '" + std::filesystem::read_symlink(target, ec).string() +
                                   "', which does not exist");
            }
            fail(target, "following its symbolic link", errno);
        }
        out.resolved = real;
        std::free(real);
    }
    if (::stat(out.resolved.c_str(), &st) == 0) {
        if (S_ISREG(st.st_mode)) {
            out.kind = OutputPath::Kind::ReplaceFile;
        } else if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) {
            out.kind = OutputPath::Kind::InPlace;
        } else {
            refuse(target, std::string("it is ") + typeName(st.st_mode));
        }
        return out;
    }
    const std::filesystem::path folder = out.resolved.has_parent_path() ? out.resolved.parent_path() : ".";
    if (errno == ELOOP) refuse(target, "a loop of symbolic links");
    if (errno == ENOTDIR) refuse(target, "'" + folder.string() + "' is not a folder");
    if (errno != ENOENT) fail(target, "looking at it", errno);
    if (::stat(folder.c_str(), &st) != 0) {
        if (errno == ENOENT) refuse(target, "the folder '" + folder.string() + "' does not exist");
        fail(target, "looking at its folder '" + folder.string() + "'", errno);
    }
    if (!S_ISDIR(st.st_mode)) refuse(target, "'" + folder.string() + "' is not a folder");
    out.kind = OutputPath::Kind::NewFile;
    return out;
}

std::string brokenLinkOnPath(const std::filesystem::path& path) {
    for (std::filesystem::path p = path; !p.empty(); p = p.parent_path()) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) == 0 && S_ISLNK(st.st_mode) && ::stat(p.c_str(), &st) != 0) {
            // Piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + string + "...".
            std::string text = "'";
            text += p.string();
            if (errno == ELOOP) return text += "' is a loop of symbolic links";
            std::error_code ec;
            text += "' is a symbolic link to '";
            text += std::filesystem::read_symlink(p, ec).string();
            return text += "', which does not exist";
        }
        if (p == p.parent_path()) break; // the root
    }
    return {};
}

void writeOutput(const std::filesystem::path& target, std::string_view bytes) {
    const OutputPath out = resolveOutput(target);
    if (out.kind == OutputPath::Kind::InPlace) {
        writeInPlace(target, out.resolved, bytes);
        return;
    }
    struct stat old {};
    const bool hadFile = out.kind == OutputPath::Kind::ReplaceFile && ::stat(out.resolved.c_str(), &old) == 0;
    replaceFile(target, out.resolved, bytes, hadFile ? &old : nullptr);
}

AtomicFile::AtomicFile(std::filesystem::path target) : m_target(std::move(target)) {
    m_out.exceptions(std::ios::badbit);
    (void)resolveOutput(m_target);
}

void AtomicFile::commit() {
    const std::string bytes = std::move(m_out).str();
    writeOutput(m_target, bytes);
}

void setWriteFault(const WriteFault& fault) { t_fault = fault; }
void clearWriteFault() { t_fault = {}; }

} // namespace core
